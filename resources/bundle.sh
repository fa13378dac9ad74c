#!/bin/sh
# The bundles for FreeCAD users without a compiler: one zip per platform, with
# one folder PlungeRough/ (the addon as FreeCAD's Mod folder wants it) and the
# planner program for that platform in PlungeRough/bin/, fully static, built
# without OpenCASCADE (floors of faces go to it as meshes) and without Python.
#
#   sh resources/bundle.sh linux     # -> dist/PlungeRough-linux-x86_64.zip
#   sh resources/bundle.sh windows   # -> dist/PlungeRough-windows-x86_64.zip (MinGW-w64)
#
# Runs as root on Debian 12, 13 or testing and installs what it needs
# (idempotent). Clipper and muParser, which Debian ships only as shared Linux
# libraries, are built here from Debian's own source packages, from the first
# suite that serves them whole (resources/debian_sources.sh); the header-only
# libraries are Debian's. Nothing else is downloaded. What the program was
# built from is in the bundle's PlungeRough/bin/build-info.txt.
# build-bundle/ keeps the sources and builds for the next run.
set -eu
PLATFORM=${1:-}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
. "$ROOT/resources/apt.sh"
die() { echo "bundle: $*" >&2; exit 1; }

case $PLATFORM in
  linux) CXX=g++ AR=ar STRIP=strip TOOLCHAIN="" EXE=plunge-rough
         EXTRA="" ;;
  windows) CXX=x86_64-w64-mingw32-g++-posix AR=x86_64-w64-mingw32-ar STRIP=x86_64-w64-mingw32-strip
           TOOLCHAIN="-DCMAKE_TOOLCHAIN_FILE=$ROOT/resources/mingw-w64.cmake" EXE=plunge-rough.exe
           EXTRA="g++-mingw-w64-x86-64-posix binutils-mingw-w64-x86-64" ;;
  *) die "usage: sh resources/bundle.sh linux|windows" ;;
esac
install_missing cmake make g++ binutils dpkg-dev python3 libboost-dev libcgal-dev nlohmann-json3-dev \
  libcli11-dev libeigen3-dev $EXTRA

WORK=$ROOT/build-bundle
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
cp "$CLIPPER/cpp/clipper.hpp" "$MUPARSER"/include/*.h "$HEADERS/"

# Clipper and muParser as static libraries, for the target.
DEPS=$OUT/deps
if [ ! -s "$DEPS/lib/libpolyclipping.a" ] || [ ! -s "$DEPS/lib/libmuparser.a" ]; then
  echo "bundle: building Clipper and muParser for $PLATFORM"
  rm -rf "$DEPS" && mkdir -p "$DEPS/lib" "$DEPS/obj"
  $CXX -O2 -std=c++17 -c "$CLIPPER/cpp/clipper.cpp" -o "$DEPS/obj/clipper.o"
  $AR rcs "$DEPS/lib/libpolyclipping.a" "$DEPS/obj/clipper.o"
  for f in muParser muParserBase muParserBytecode muParserCallback muParserError muParserInt muParserTokenReader; do
    $CXX -O2 -std=c++17 -DMUPARSER_STATIC -I"$MUPARSER/include" -c "$MUPARSER/src/$f.cpp" -o "$DEPS/obj/$f.o"
  done
  $AR rcs "$DEPS/lib/libmuparser.a" "$DEPS"/obj/muParser*.o
fi

# The planner program, and the addon's files (CMake's freecad_addon component).
cmake -S "$ROOT" -B "$OUT/build" $TOOLCHAIN -DCMAKE_BUILD_TYPE=Release -DPLUNGE_PORTABLE=ON \
  -DPLUNGE_HEADERS="$HEADERS" -DPLUNGE_DEPS="$DEPS" -DPLUNGE_WERROR="${PLUNGE_WERROR:-OFF}" >/dev/null
cmake --build "$OUT/build" -j"$(nproc)" --target plunge-rough
STAGE=$OUT/stage
rm -rf "$STAGE"
cmake --install "$OUT/build" --component freecad_addon --prefix "$STAGE" >/dev/null
PROGRAM=$STAGE/PlungeRough/bin/$EXE
[ -f "$PROGRAM" ] || die "the install put no $EXE in PlungeRough/bin"
$STRIP "$PROGRAM"

# Fully static: no loader and no library on Linux; Windows' own DLLs only.
if [ "$PLATFORM" = linux ]; then
  readelf -lW "$PROGRAM" | grep -q INTERP && die "$EXE asks for a dynamic loader"
  readelf -d "$PROGRAM" | grep -q NEEDED && die "$EXE needs shared libraries: $(readelf -d "$PROGRAM" | grep NEEDED)"
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
  echo "PlungeRough's planner for $PLATFORM x86-64: $EXE"
  echo "commit: $(commit)"
  echo "built on: $(. /etc/os-release && echo "$PRETTY_NAME"), $($CXX --version | head -n1)"
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
ZIP=$ROOT/dist/PlungeRough-$PLATFORM-x86_64.zip
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
