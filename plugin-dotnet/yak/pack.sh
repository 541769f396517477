#!/usr/bin/env bash
# Lays out the Yak package in plugin-dotnet/yak/dist/ from a Release build of both plug-ins:
#   dist/manifest.yml (version and url filled in), dist/icon.png,
#   dist/net48/  (Windows, .NET Framework): Tpi.Rhino.rhp, Tpi.Grasshopper.gha, Tpi.Native.dll, Tpi.Logic.dll, tpi.dll
#   dist/net7.0/ (Windows and macOS, .NET 7): the same plus libtpi.dylib
# then run Rhino's yak tool in dist/: `yak build` (and `yak push <file>.yak`).
#
# Usage: bash plugin-dotnet/yak/pack.sh VERSION URL   (after dotnet build -c Release, see README.md)
#   URL: the project's address (the release workflow passes its GitHub repository's).
# Environment: TPI_BUILD_ROOT   where the projects' bin/Release folders are (default: plugin-dotnet)
#              TPI_DIST_DIR     where to lay out the package (default: plugin-dotnet/yak/dist)
#
# Fails, naming what is wrong, when anything is missing: a project output, a managed assembly,
# the Windows tpi.dll (x86-64 PE), the macOS libtpi.dylib (universal: x86_64 and arm64), or a
# real URL. Architectures are checked with lipo -info when present, else with file(1).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
version=${1:?usage: pack.sh VERSION URL}
url=${2:?usage: pack.sh VERSION URL (the project address, e.g. https://github.com/OWNER/REPO)}
root=${TPI_BUILD_ROOT:-$here/..}
dist=${TPI_DIST_DIR:-$here/dist}

die() { echo "pack.sh: $*" >&2; exit 1; }

case "$version" in
    *[!0-9A-Za-z.+-]*|"") die "bad version '$version'" ;;
esac
case "$url" in
    https://*/*) ;;
    *) die "URL must be the project's https address, got '$url'" ;;
esac
case "$url" in
    *example.invalid*|*example.com*|https://github.com/|https://github.com) die "URL '$url' is a placeholder" ;;
esac

# Architecture checks: print nothing and succeed, or fail naming the file and what it holds.
describe() { file -b "$1" 2>/dev/null || echo "unknown (file(1) not installed)"; }
check_windows_dll() {
    local f=$1 what
    what=$(describe "$f")
    case "$what" in
        *PE32+*x86-64*) ;;
        *) die "$f is not a Windows x64 DLL: $what" ;;
    esac
}
check_universal_dylib() {
    local f=$1 archs
    if command -v lipo >/dev/null 2>&1; then
        archs=$(lipo -info "$f" 2>&1) || die "lipo -info $f failed: $archs"
    else
        archs=$(describe "$f")
    fi
    case "$archs" in *x86_64*) ;; *) die "$f lacks x86_64 (Intel Macs): $archs" ;; esac
    case "$archs" in *arm64*) ;; *) die "$f lacks arm64 (Apple silicon): $archs" ;; esac
}

rm -rf "$dist"
mkdir -p "$dist"
sed -e "s/\$version/$version/" -e "s|\$url|$url|" "$here/manifest.yml" > "$dist/manifest.yml"
cp "$here/../Tpi.Grasshopper/Icons/discretise.png" "$dist/icon.png"
for tfm in net48 net7.0; do
    mkdir -p "$dist/$tfm"
    for project in Tpi.Rhino Tpi.Grasshopper; do
        out=$root/$project/bin/Release/$tfm
        [ -d "$out" ] || die "missing $out: build $project -c Release first"
        case $project in Tpi.Rhino) plugin=Tpi.Rhino.rhp ;; *) plugin=Tpi.Grasshopper.gha ;; esac
        for f in "$plugin" Tpi.Native.dll Tpi.Logic.dll; do
            [ -f "$out/$f" ] || die "missing $out/$f"
            cp "$out/$f" "$dist/$tfm/"
        done
        # The Windows library in both folders (Rhino 8 for Windows runs either runtime); the
        # macOS one in net7.0 only (Rhino 8 for Mac runs .NET 7).
        [ -f "$out/tpi.dll" ] || die "missing the Windows native library tpi.dll in $out (put it in TpiNativeDir before building)"
        check_windows_dll "$out/tpi.dll"
        cp "$out/tpi.dll" "$dist/$tfm/"
        if [ "$tfm" = net7.0 ]; then
            [ -f "$out/libtpi.dylib" ] || die "missing the macOS native library libtpi.dylib in $out (lipo -create the x86_64 and arm64 builds into TpiNativeDir before building)"
            check_universal_dylib "$out/libtpi.dylib"
            cp "$out/libtpi.dylib" "$dist/$tfm/"
        fi
    done
done
ls -R "$dist"
