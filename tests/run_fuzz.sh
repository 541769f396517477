#!/usr/bin/env bash
# Builds the four cargo-fuzz targets of fuzz/ (docs/reliability.md, "Fuzzing") and runs each
# for a fixed number of inputs from a fixed seed, starting from the samples: the same inputs
# on every run, so a finding here is reproducible and a green run stays green. About 30 s per
# target on a 2-core machine; a wall-clock cap (FUZZ_CAP seconds, default 90) stops a target on
# a slower machine, which then runs fewer inputs and says so.
# Any crash, panic, timeout or leak fails the run; libFuzzer keeps the input that did it in
# fuzz/artifacts/TARGET/ (reproduce: cargo +nightly fuzz run -O TARGET fuzz/artifacts/TARGET/FILE). Installs cargo-fuzz when missing (needs the nightly
# toolchain, which the machines have).
# Ends with the line "N passed, N failed".
set -euo pipefail
cd "$(dirname "$0")/../fuzz"

if ! cargo +nightly --version >/dev/null 2>&1; then
    echo "run_fuzz.sh: the nightly toolchain is missing (rustup toolchain install nightly)" >&2
    exit 1
fi
if ! cargo +nightly fuzz --version >/dev/null 2>&1; then
    cargo install --locked cargo-fuzz
fi
cargo +nightly fuzz build -O

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/corpus/surface_json" "$work/corpus/pattern_input" "$work/corpus/discretise" \
    "$work/corpus/c_abi"
for f in ../samples/*.json; do
    if grep -q '"uv"' "$f"; then
        cp "$f" "$work/corpus/pattern_input/"
    else
        cp "$f" "$work/corpus/surface_json/"
    fi
done

cap=${FUZZ_CAP:-90}
passed=0
failed=0
# Inputs per target: about 30 s each at the rates measured on the 2-core machine.
for spec in surface_json:360000 pattern_input:200000 discretise:20000 c_abi:20000; do
    target=${spec%%:*}
    runs=${spec##*:}
    log="$work/$target.log"
    mkdir -p "artifacts/$target"
    start=$(date +%s)
    if cargo +nightly fuzz run -O "$target" "$work/corpus/$target" -- \
        -seed=1 -runs="$runs" -max_total_time="$cap" -timeout=20 -rss_limit_mb=4096 \
        -dict=dict/json.dict -artifact_prefix="artifacts/$target/" \
        -print_final_stats=1 >"$log" 2>&1; then
        done_runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
        echo "fuzz $target: ok, $done_runs of $runs inputs in $(($(date +%s) - start)) s"
        passed=$((passed + 1))
    else
        echo "fuzz $target: FAILED after $(($(date +%s) - start)) s; the last lines:" >&2
        tail -n 40 "$log" >&2
        ls -l "artifacts/$target" >&2 || true
        failed=$((failed + 1))
    fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
