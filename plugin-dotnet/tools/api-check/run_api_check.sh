#!/usr/bin/env bash
# The API check (tests/run_dotnet_tests.sh runs it after type-checking the adapters):
#   1. reads every RhinoCommon/Grasshopper type, member, overload and override the compiled
#      adapters use (ApiRefs.exe, Mono.Cecil on Tpi.Rhino.dll and Tpi.Grasshopper.dll built
#      against the fakes) and every member the fakes define, and checks all of them against
#      the official typed stubs from PyPI (check_api.py): the adapters use nothing the real API
#      lacks, and the fakes cannot drift from it;
#   2. proves the check can fail: a renamed member in the adapters' uses, and the same member
#      renamed in a copy of the stubs, must each fail naming it.
# Usage: run_api_check.sh BUILD_DIR   (BUILD_DIR holds fakes/*.dll from the type check)
# Environment: TPI_STUBS_DIR  folder with Rhino/ and Grasshopper/ stubs (default: downloaded
#              with pip into BUILD_DIR/stubs, pinned to 8.20.25157, the version the adapters
#              name in their headers).
# Prints PASS/FAIL lines and "API check: N passed, M failed"; exits 1 on a failure.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:?usage: run_api_check.sh BUILD_DIR}
stubs_version=8.20.25157
passed=0; failed=0
pass() { passed=$((passed + 1)); echo "PASS  API check: $*"; }
failure() { failed=$((failed + 1)); echo "FAIL  API check: $*"; }
die() { echo "run_api_check.sh: $*" >&2; echo "API check: $passed passed, $((failed + 1)) failed"; exit 1; }

stubs=${TPI_STUBS_DIR:-$build/stubs}
if [ ! -d "$stubs/Rhino" ] || [ ! -d "$stubs/Grasshopper" ]; then
    mkdir -p "$build/stubs-wheels"
    python3 -m pip download --quiet --disable-pip-version-check --no-deps -d "$build/stubs-wheels" \
        "rhino-stubs-typed==$stubs_version" "grasshopper-stubs-typed==$stubs_version" \
        || die "could not download rhino-stubs-typed/grasshopper-stubs-typed $stubs_version from PyPI (set TPI_STUBS_DIR to an unpacked copy)"
    python3 - "$stubs" "$build"/stubs-wheels/*.whl <<'PY' || die "could not unpack the stubs"
import sys, zipfile
for wheel in sys.argv[2:]:
    zipfile.ZipFile(wheel).extractall(sys.argv[1])
PY
fi

cecil=$(find /usr/lib/mono -name Mono.Cecil.dll -path '*0.11*' 2>/dev/null | head -n 1)
[ -n "$cecil" ] || cecil=$(find /usr/lib/mono -name Mono.Cecil.dll 2>/dev/null | sort -r | head -n 1)
[ -n "$cecil" ] || die "Mono.Cecil.dll not found (it comes with mono-devel)"
cp "$cecil" "$build/Mono.Cecil.dll"
mcs -langversion:7.2 -nologo -warnaserror -out:"$build/ApiRefs.exe" -r:"$build/Mono.Cecil.dll" "$here/ApiRefs.cs" \
    || die "compiling ApiRefs.cs failed"

uses=$build/api-uses
rm -rf "$uses"; mkdir -p "$uses"
for a in Tpi.Rhino Tpi.Grasshopper; do
    mono "$build/ApiRefs.exe" "$build/fakes/$a.dll" "$build/fakes" > "$uses/$a.uses" || die "reading $a.dll failed"
    [ -s "$uses/$a.uses" ] || die "no API use read from $a.dll"
done
for a in RhinoCommon Grasshopper; do
    mono "$build/ApiRefs.exe" --definitions "$build/fakes/$a.dll" > "$uses/fakes-$a.defs" || die "reading the $a fakes failed"
done
check() { python3 "$here/check_api.py" --stubs "$1" --allow "$here/not-in-stubs.txt" "${@:2}"; }

if out=$(check "$stubs" "$uses"/*.uses "$uses"/*.defs 2>&1); then
    pass "adapters' uses and the fakes found in the stubs ($(tail -n 1 <<<"$out"))"
else
    failure "adapters' uses or fakes missing from the stubs"; sed 's/^/      /' <<<"$out"
fi

# The check must fail when a member is renamed. The member: Mesh.DuplicateMesh, which the
# watcher calls (the test fails if it stops being used, so it never checks nothing).
member='M Rhino.Geometry.Mesh::DuplicateMesh()'
if grep -qxF "$member" "$uses/Tpi.Rhino.uses"; then
    pass "the adapters' uses include $member"
else
    failure "the adapters' uses lack $member (pick another member for the rename tests)"
fi
mkdir -p "$uses/renamed"
sed 's/^M Rhino\.Geometry\.Mesh::DuplicateMesh()$/M Rhino.Geometry.Mesh::DuplicateMeshes()/' "$uses/Tpi.Rhino.uses" > "$uses/renamed/Tpi.Rhino.uses"
if out=$(check "$stubs" "$uses/renamed/Tpi.Rhino.uses" "$uses/Tpi.Grasshopper.uses" "$uses"/*.defs 2>&1); then
    failure "a use renamed to Mesh.DuplicateMeshes passed"
elif grep -q "Rhino.Geometry.Mesh has no member DuplicateMeshes" <<<"$out"; then
    pass "a use renamed to Mesh.DuplicateMeshes fails, naming it"
else
    failure "a renamed use failed without naming it"; sed 's/^/      /' <<<"$out"
fi
renamed_stubs=$build/stubs-renamed
rm -rf "$renamed_stubs"; mkdir -p "$renamed_stubs"
cp -r "$stubs/Rhino" "$stubs/Grasshopper" "$renamed_stubs/"
sed -i 's/def DuplicateMesh(self)/def DuplicateMeshRenamed(self)/' "$renamed_stubs/Rhino/Geometry/__init__.pyi"
if out=$(check "$renamed_stubs" "$uses"/*.uses "$uses"/*.defs 2>&1); then
    failure "stubs with Mesh.DuplicateMesh renamed passed"
elif grep -q "Rhino.Geometry.Mesh has no member DuplicateMesh" <<<"$out"; then
    pass "stubs with Mesh.DuplicateMesh renamed fail, naming it"
else
    failure "renamed stubs failed without naming the member"; sed 's/^/      /' <<<"$out"
fi
# A wrong overload (argument count) and a wrong enum value must fail too.
sed 's/^M Rhino\.RhinoDoc::BeginUndoRecord(System\.String)$/M Rhino.RhinoDoc::BeginUndoRecord(System.String, System.Int32)/' \
    "$uses/Tpi.Rhino.uses" > "$uses/renamed/Tpi.Rhino.uses"
out=$(check "$stubs" "$uses/renamed/Tpi.Rhino.uses" "$uses/Tpi.Grasshopper.uses" "$uses"/*.defs 2>&1)
if grep -q "no overload Rhino.RhinoDoc.BeginUndoRecord(System.String, System.Int32)" <<<"$out"; then
    pass "an overload the stubs lack (BeginUndoRecord(string, int)) fails, naming it"
else
    failure "BeginUndoRecord with two arguments was not caught"; sed 's/^/      /' <<<"$out"
fi
sed 's/^M Rhino\.Display\.PointStyle::RoundControlPoint = 5$/M Rhino.Display.PointStyle::RoundControlPoint = 2/' \
    "$uses/fakes-RhinoCommon.defs" > "$uses/renamed/fakes-RhinoCommon.defs"
out=$(check "$stubs" "$uses"/*.uses "$uses/renamed/fakes-RhinoCommon.defs" "$uses/fakes-Grasshopper.defs" 2>&1)
if grep -q "Rhino.Display.PointStyle.RoundControlPoint is 5 in the stubs, 2 here" <<<"$out"; then
    pass "a fake enum value that differs from the stubs fails, naming it"
else
    failure "a fake enum value that differs from the stubs was not caught"; sed 's/^/      /' <<<"$out"
fi

echo "API check: $passed passed, $failed failed"
[ "$failed" = 0 ]
