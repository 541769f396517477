#!/usr/bin/env bash
# Runs every test of the project: the Rust workspace (unit, integration, doc tests, including
# the openNURBS conformance tests that drive rhino3dm from Python).
# Installs what it needs when missing, so it also works on a fresh machine.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! python3 -c 'import rhino3dm' 2>/dev/null; then
    python3 -m pip install --quiet --disable-pip-version-check 'rhino3dm==8.*'
fi

cargo test --workspace --locked
