#!/usr/bin/env bash
# Lays out the Yak package in plugin-dotnet/yak/dist/ from a Release build of both plug-ins:
#   dist/manifest.yml (version filled in), dist/icon.png,
#   dist/net48/  (Windows, .NET Framework): Tpi.Rhino.rhp, Tpi.Grasshopper.gha, Tpi.Native.dll, Tpi.Logic.dll, tpi.dll
#   dist/net7.0/ (Windows and macOS, .NET 7): the same plus libtpi.dylib
# then run Rhino's yak tool in dist/: `yak build` (and `yak push <file>.yak`).
# Usage: bash plugin-dotnet/yak/pack.sh 0.1.0   (after dotnet build -c Release, see README.md)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
version=${1:?usage: pack.sh VERSION}
dist=$here/dist
rm -rf "$dist"
mkdir -p "$dist"
sed "s/\$version/$version/" "$here/manifest.yml" > "$dist/manifest.yml"
cp "$here/../Tpi.Grasshopper/Icons/discretise.png" "$dist/icon.png"
for tfm in net48 net7.0; do
    mkdir -p "$dist/$tfm"
    for project in Tpi.Rhino Tpi.Grasshopper; do
        out=$here/../$project/bin/Release/$tfm
        [ -d "$out" ] || { echo "missing $out: build Release first" >&2; exit 1; }
        cp "$out"/*.rhp "$out"/*.gha "$out"/Tpi.Native.dll "$out"/Tpi.Logic.dll "$dist/$tfm/" 2>/dev/null || true
        for lib in tpi.dll libtpi.dylib; do
            if [ -f "$out/$lib" ]; then cp "$out/$lib" "$dist/$tfm/"; fi
        done
    done
done
ls -R "$dist"
