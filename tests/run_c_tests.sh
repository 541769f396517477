#!/usr/bin/env bash
# The C ABI's tests from C: builds the release library (libtpi.so and libtpi.a), generates the
# fixture of Rust-API results for the C test, checks the exported symbols against the header
# and the tests, compiles every tests/c/*.c with `cc -Wall -Wextra -Werror` against
# include/tpi.h, runs each program, then runs each again under valgrind (zero leaks, zero
# invalid reads or writes). Ends with the line "N passed, M failed" and exits non-zero if any
# step failed.
#
# Environment (all optional):
#   CARGO_TARGET_DIR  cargo's target directory (default: target)
#   TPI_LIB_DIR       directory holding libtpi.so and libtpi.a (default: $CARGO_TARGET_DIR/release)
#   TPI_SKIP_BUILD=1  use the library already in TPI_LIB_DIR instead of building it
#   TPI_C_BUILD_DIR   where test binaries and the generated fixture go
#                     (default: $CARGO_TARGET_DIR/c-tests)
#   CC, CXX           C and C++ compilers (default: cc, c++; the C++ header check fails
#                     when there is no C++ compiler)
#   TPI_NO_VALGRIND=1 skip the valgrind runs (they are part of the acceptance; CI runs them)
#
# Needs: a Rust toolchain (cargo), a C compiler and libc headers, nm (binutils), valgrind.
# On Debian/Ubuntu: apt-get install build-essential binutils valgrind
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)

TARGET_DIR=${CARGO_TARGET_DIR:-$ROOT/target}
LIB_DIR=${TPI_LIB_DIR:-$TARGET_DIR/release}
BUILD_DIR=${TPI_C_BUILD_DIR:-$TARGET_DIR/c-tests}
CC=${CC:-cc}
CXX=${CXX:-c++}
CFLAGS=(-std=c11 -Wall -Wextra -Werror -g -O1)

passed=0
failed=0
failures=()

# step NAME COMMAND...: runs one step, counts it, shows its output only when it fails.
step() {
    local name=$1
    shift
    local log
    log=$(mktemp)
    if "$@" >"$log" 2>&1; then
        passed=$((passed + 1))
        echo "PASS  $name"
    else
        failed=$((failed + 1))
        failures+=("$name")
        echo "FAIL  $name"
        sed 's/^/      /' "$log"
    fi
    rm -f "$log"
}

mkdir -p "$BUILD_DIR/generated"

build_library() {
    [ "${TPI_SKIP_BUILD:-0}" = 1 ] && return 0
    cargo build --release --locked -p tpi-ffi
}

# The fixture comes from the Rust API (tpi-core called directly), built in the dev profile so
# that the test-only dev-dependencies never touch the release library.
generate_fixture() {
    cargo run --locked -q -p tpi-ffi --example c_fixture -- "$BUILD_DIR/generated/tpi_fixture.h"
}

exported_functions() {
    nm -D --defined-only "$LIB_DIR/libtpi.so" | awk '$2 == "T" && $3 ~ /^tpi_/ { print $3 }' | sort -u
}

header_functions() {
    grep -oE '\btpi_[a-z0-9_]+\(' include/tpi.h | tr -d '(' | sort -u
}

# Every exported function is declared in the header and vice versa, and no test-only entry
# point (tpi_debug_panic) is exported.
check_symbols() {
    local exported declared
    exported=$(exported_functions)
    declared=$(header_functions)
    [ -n "$exported" ] || { echo "no tpi_* symbols exported by $LIB_DIR/libtpi.so"; return 1; }
    if grep -q debug_panic <<<"$exported"; then
        echo "the release library exports the test-only tpi_debug_panic"
        return 1
    fi
    if [ "$exported" != "$declared" ]; then
        echo "exported functions and header declarations differ:"
        diff <(echo "$exported") <(echo "$declared")
        return 1
    fi
    echo "$(wc -l <<<"$exported") functions exported and declared"
}

# "The C test exercises every exported function": each one is called somewhere in tests/c.
check_coverage() {
    local missing=0 f
    for f in $(exported_functions); do
        if ! grep -qE "\b$f\(" tests/c/*.c; then
            echo "not called by any tests/c/*.c: $f"
            missing=1
        fi
    done
    return $missing
}

header_compiles_as_c() {
    echo '#include "tpi.h"' | "$CC" -std=c99 -pedantic -Wall -Wextra -Werror -fsyntax-only -I include -x c -
}

header_compiles_as_cxx() {
    if ! command -v "$CXX" >/dev/null 2>&1; then
        echo "no C++ compiler ($CXX): install g++ (build-essential)"
        return 1
    fi
    echo '#include "tpi.h"' | "$CXX" -std=c++11 -Wall -Wextra -Werror -fsyntax-only -I include -x c++ -
}

compile() {
    local source=$1 out=$2
    "$CC" "${CFLAGS[@]}" -I include -I tests/c -I "$BUILD_DIR/generated" "$source" \
        -L "$LIB_DIR" -Wl,-rpath,"$LIB_DIR" -ltpi -lm -pthread -o "$out"
}

compile_static() {
    local source=$1 out=$2
    "$CC" "${CFLAGS[@]}" -I include -I tests/c -I "$BUILD_DIR/generated" "$source" \
        "$LIB_DIR/libtpi.a" -lm -pthread -ldl -o "$out"
}

run_valgrind() {
    valgrind --quiet --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite,indirect \
        --show-leak-kinds=definite,indirect "$@"
}

step "build the release library" build_library
step "generate the Rust-API fixture" generate_fixture
step "exported symbols match include/tpi.h" check_symbols
step "tests/c calls every exported function" check_coverage
step "include/tpi.h compiles as C99" header_compiles_as_c
step "include/tpi.h compiles as C++11" header_compiles_as_cxx

for source in tests/c/*.c; do
    name=$(basename "$source" .c)
    binary="$BUILD_DIR/$name"
    step "compile $name" compile "$source" "$binary"
    step "compile $name (static libtpi.a)" compile_static "$source" "$binary-static"
    step "run $name" "$binary"
    step "run $name (static)" "$binary-static"
    if [ "${TPI_NO_VALGRIND:-0}" = 1 ]; then
        echo "SKIP  valgrind $name (TPI_NO_VALGRIND=1)"
    elif ! command -v valgrind >/dev/null 2>&1; then
        step "valgrind is installed" false
    else
        step "valgrind $name" run_valgrind "$binary"
    fi
done

if [ ${#failures[@]} -gt 0 ]; then
    echo "failed: ${failures[*]}"
fi
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
