#!/usr/bin/env bash
# Tests of pack.sh on fake build outputs (tests/run_dotnet_tests.sh runs it): a complete layout
# packs; a missing Windows DLL, a missing or thin macOS dylib, a non-PE tpi.dll and a
# placeholder URL each fail with a message naming the problem. The native libraries are
# minimal headers that file(1) (or lipo) identifies: a PE32+ x86-64 DLL and Mach-O files.
# Prints one PASS/FAIL line per case and "pack.sh: N passed, M failed"; exits 1 on a failure.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
dist=$work/dist
passed=0; failed=0

pe_dll() { # a PE32+ x86-64 DLL header: MZ, e_lfanew = 0x40, PE\0\0, machine 0x8664, optional header 0x20b, DLL flag
    python3 - "$1" <<'PY'
import struct, sys
b = bytearray(512)
b[0:2] = b'MZ'; struct.pack_into('<I', b, 0x3c, 0x40)
b[0x40:0x44] = b'PE\0\0'
struct.pack_into('<HHIIIHH', b, 0x44, 0x8664, 0, 0, 0, 0, 0xf0, 0x2022)
struct.pack_into('<H', b, 0x58, 0x20b)
struct.pack_into('<H', b, 0x58 + 68, 3)  # subsystem: console
open(sys.argv[1], 'wb').write(bytes(b))
PY
}
macho() { # $1 file, then cpu types: one -> thin Mach-O 64, several -> fat (universal)
    python3 - "$@" <<'PY'
import struct, sys
cpu = {'x86_64': (0x01000007, 3), 'arm64': (0x0100000c, 0)}
path, archs = sys.argv[1], sys.argv[2:]
def thin(a):
    t, s = cpu[a]
    return struct.pack('<IiiIIIII', 0xfeedfacf, t, s, 6, 0, 0, 0, 0).ljust(4096, b'\0')
if len(archs) == 1:
    open(path, 'wb').write(thin(archs[0])); sys.exit()
head = struct.pack('>II', 0xcafebabe, len(archs))
offset = 4096; body = b''
for a in archs:
    t, s = cpu[a]
    head += struct.pack('>iiIII', t, s, offset + len(body), 4096, 12)
    body += thin(a)
open(path, 'wb').write(head.ljust(4096, b'\0') + body)
PY
}
layout() { # a build root with both projects, both TFMs, and the given native files
    local root=$1 dll=$2 dylib=$3
    rm -rf "$root"
    for p in Tpi.Rhino Tpi.Grasshopper; do
        for tfm in net48 net7.0; do
            local out=$root/$p/bin/Release/$tfm
            mkdir -p "$out"
            touch "$out/Tpi.Native.dll" "$out/Tpi.Logic.dll" "$out/Tpi.Rhino.rhp" "$out/Tpi.Grasshopper.gha"
            [ -z "$dll" ] || cp "$dll" "$out/tpi.dll"
            [ -z "$dylib" ] || cp "$dylib" "$out/libtpi.dylib"
        done
    done
}
expect() { # name, expected exit (0 or fail), text the output must contain, then the command
    local name=$1 want=$2 text=$3; shift 3
    local out rc
    out=$("$@" 2>&1); rc=$?
    if { [ "$want" = 0 ] && [ $rc = 0 ]; } || { [ "$want" = fail ] && [ $rc != 0 ]; }; then
        if [ -z "$text" ] || grep -qF -- "$text" <<<"$out"; then
            passed=$((passed + 1)); echo "PASS  pack.sh: $name"; return
        fi
    fi
    failed=$((failed + 1)); echo "FAIL  pack.sh: $name (exit $rc)"; sed 's/^/      /' <<<"$out"
}

pe_dll "$work/tpi.dll"
macho "$work/universal.dylib" x86_64 arm64
macho "$work/intel.dylib" x86_64
printf '\177ELF\002\001\001' > "$work/elf.so"; head -c 200 /dev/zero >> "$work/elf.so"
url=https://github.com/tpi-project/tpi
pack() { TPI_BUILD_ROOT=$work/root TPI_DIST_DIR=$dist bash "$here/pack.sh" "$@"; }

layout "$work/root" "$work/tpi.dll" "$work/universal.dylib"
expect "complete layout packs" 0 "" pack 1.2.3 "$url"
if [ -f "$dist/net7.0/libtpi.dylib" ] && [ -f "$dist/net48/tpi.dll" ] && [ ! -f "$dist/net48/libtpi.dylib" ] \
    && grep -qx "version: 1.2.3" "$dist/manifest.yml" && grep -qx "url: $url" "$dist/manifest.yml"; then
    passed=$((passed + 1)); echo "PASS  pack.sh: dist holds the libraries and the filled-in manifest"
else
    failed=$((failed + 1)); echo "FAIL  pack.sh: dist holds the libraries and the filled-in manifest"; ls -R "$dist" 2>&1 | sed 's/^/      /'
fi
layout "$work/root" "" "$work/universal.dylib"
expect "no Windows DLL: fails naming tpi.dll" fail "missing the Windows native library tpi.dll" pack 1.2.3 "$url"
layout "$work/root" "$work/tpi.dll" ""
expect "no macOS dylib: fails naming libtpi.dylib" fail "missing the macOS native library libtpi.dylib" pack 1.2.3 "$url"
layout "$work/root" "$work/tpi.dll" "$work/intel.dylib"
expect "thin Intel dylib: fails naming arm64" fail "lacks arm64" pack 1.2.3 "$url"
layout "$work/root" "$work/elf.so" "$work/universal.dylib"
expect "ELF as tpi.dll: fails" fail "is not a Windows x64 DLL" pack 1.2.3 "$url"
layout "$work/root" "$work/tpi.dll" "$work/universal.dylib"
expect "placeholder URL: fails" fail "placeholder" pack 1.2.3 https://example.invalid/tpi
rm -f "$work/root/Tpi.Grasshopper/bin/Release/net48/Tpi.Grasshopper.gha"
expect "missing .gha: fails naming it" fail "Tpi.Grasshopper.gha" pack 1.2.3 "$url"

echo "pack.sh: $passed passed, $failed failed"
[ "$failed" = 0 ]
