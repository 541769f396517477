#!/usr/bin/env bash
# Runs every test of the project:
#   0. formatting (rustfmt --check), lints (clippy, every target, warnings are errors) and
#      the API docs (rustdoc, private items too, warnings such as broken links are errors);
#   1. the Rust workspace (unit, integration and doc tests, including the openNURBS
#      conformance tests that drive rhino3dm from Python, the CLI's end-to-end tests, the C
#      ABI's Rust tests and the header check);
#   2. the C ABI tested from C (tests/run_c_tests.sh: compile against include/tpi.h, run,
#      run again under valgrind);
#   3. the .NET binding and the Rhino-free plugin logic with Mono against the real native
#      library, the API check of the Rhino/Grasshopper adapters against the RhinoCommon and
#      Grasshopper typed stubs, the pack.sh tests and actionlint on the release workflow
#      (tests/run_dotnet_tests.sh);
#   4. the four cargo-fuzz targets, built with the nightly toolchain and run from a fixed
#      seed for a fixed number of inputs each, about 30 s per target (tests/run_fuzz.sh).
# Each of 2, 3 and 4 ends with its own line "N passed, N failed".
# Installs what it needs when missing, so it also works on a fresh machine.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! python3 -c 'import rhino3dm' 2>/dev/null; then
    python3 -m pip install --quiet --disable-pip-version-check 'rhino3dm==8.*'
fi
# ezdxf reads sheets.dxf back in the fabrication test (an independent DXF reader).
if ! python3 -c 'import ezdxf' 2>/dev/null; then
    python3 -m pip install --quiet --disable-pip-version-check 'ezdxf==1.4.*'
fi
missing=()
for tool in cc c++ nm valgrind script; do
    command -v "$tool" >/dev/null 2>&1 || missing+=("$tool")
done
if [ ${#missing[@]} -gt 0 ]; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        DEBIAN_FRONTEND=noninteractive apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq build-essential binutils valgrind bsdutils >/dev/null
    else
        echo "run_all.sh: missing ${missing[*]}: install build-essential binutils valgrind" >&2
        exit 1
    fi
fi

if command -v rustup >/dev/null 2>&1; then
    rustup component add rustfmt clippy >/dev/null 2>&1 || true
fi
cargo fmt --all -- --check
cargo clippy --workspace --all-targets --locked -- -D warnings
RUSTDOCFLAGS='-D warnings' cargo doc --workspace --no-deps --document-private-items --locked
cargo test --workspace --locked
bash tests/run_c_tests.sh
bash tests/run_dotnet_tests.sh
bash tests/run_fuzz.sh
