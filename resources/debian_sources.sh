#!/bin/sh
# Debian's source packages of what Debian ships only as shared Linux libraries
# (Clipper and muParser, for the bundles' static programs: resources/bundle.sh),
# each from the first suite whose archive serves it whole.
#
#   sh resources/debian_sources.sh DEST SOURCE-PACKAGE...
#
# The suites, in order: this machine's release, then the stable ones down to
# bookworm (forky: forky trixie bookworm; trixie: trixie bookworm). The
# archive can lag its own index: on 2026-12-07 the Sources of trixie and forky
# named libpolyclipping 6.4.2-8/-9 and muparser 2.3.4-1/-2, and their .dsc
# files answered 404, while bookworm's were served. A suite that does not
# serve a package whole (a file missing, or not matching its .dsc, which
# apt-get source checks as usual) is said, and the next one is tried.
#
# Each package is unpacked into DEST/ (apt-get source's own folder name) and
# DEST/ORIGIN gets one line "PACKAGE SOURCE VERSION SUITE". apt runs with a
# package list of its own, so the machine's apt configuration stays as it is.
# PLUNGE_SOURCE_SUITES overrides the order and PLUNGE_SOURCE_MIRROR the
# mirror (the test: tests/python/test_debian_sources.py).
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
. "$ROOT/resources/apt.sh"  # mirror, install_missing

# The suites to try, for a release: its own, then the stable ones, bookworm last.
suites_for() {
  case $1 in
    bookworm) echo bookworm ;;
    trixie) echo trixie bookworm ;;
    forky) echo forky trixie bookworm ;;
    *) echo "$1" forky trixie bookworm ;;  # a later release, or testing by another name
  esac
}
if [ "${1:-}" = --suites-for ]; then suites_for "${2:?--suites-for CODENAME}"; exit 0; fi
DEST=${1:?usage: debian_sources.sh DEST PACKAGE...}
shift
[ $# -gt 0 ] || { echo "sources: no package named" >&2; exit 2; }

# apt-get source unpacks with dpkg-source (dpkg-dev); the keyring checks the suites' indexes.
install_missing dpkg-dev debian-archive-keyring

codename=$(. /etc/os-release && echo "${VERSION_CODENAME:-bookworm}")
SUITES=${PLUNGE_SOURCE_SUITES:-$(suites_for "$codename")}
MIRROR=${PLUNGE_SOURCE_MIRROR:-$(mirror)}
mkdir -p "$DEST"
DEST=$(cd "$DEST" && pwd)
APT=$DEST/.apt
rm -rf "$APT"
trap 'rm -rf "$APT"' EXIT

# SUITE's deb-src as apt's only list, its index fetched once; says why not.
# No dpkg status either: apt would look for the source of the version this
# machine has installed (trixie's 6.4.2-8+b1), which another suite lacks.
opts() { echo "-o Dir::Etc::SourceList=$APT/$1/sources.list -o Dir::Etc::SourceParts=$APT/$1/none \
  -o Dir::State::Lists=$APT/$1/lists -o Dir::Cache=$APT/$1/cache -o Dir::State::status=/dev/null \
  -o APT::Sandbox::User=root"; }
indexed() {  # indexed SUITE
  dir=$APT/$1
  [ ! -e "$dir/updated" ] || return 0
  [ ! -e "$dir/failed" ] || { cat "$dir/failed"; return 1; }
  mkdir -p "$dir/lists/partial" "$dir/cache/archives/partial"
  echo "deb-src [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] $MIRROR $1 main" >"$dir/sources.list"
  if apt-get $(opts "$1") -qq update >"$dir/update.log" 2>&1; then touch "$dir/updated"; return 0; fi
  { grep -m1 '^[EW]:' "$dir/update.log" | sed 's/^[EW]: //'; } >"$dir/failed" || echo "apt-get update failed" >"$dir/failed"
  cat "$dir/failed"
  return 1
}

: >"$DEST/ORIGIN.part"
for package in "$@"; do
  got=
  for suite in $SUITES; do
    try=$APT/try
    rm -rf "$try" && mkdir -p "$try"
    if ! why=$(indexed "$suite"); then
      echo "sources: $package: $suite's index could not be read ($why); trying the next suite"
      continue
    fi
    if (cd "$try" && apt-get $(opts "$suite") -qq source "$package") >"$APT/source.log" 2>&1; then
      dsc=$(cd "$try" && ls ./*.dsc | head -n1)
      dsc=${dsc#./}
      source=${dsc%%_*}
      version=${dsc#*_}
      version=${version%.dsc}
      unpacked=$(find "$try" -mindepth 1 -maxdepth 1 -type d | head -n1)
      [ -n "$unpacked" ] || { echo "sources: $package from $suite: apt-get source unpacked nothing" >&2; exit 1; }
      rm -rf "$DEST/${unpacked##*/}"
      mv "$unpacked" "$DEST/"
      echo "$package $source $version $suite" >>"$DEST/ORIGIN.part"
      echo "sources: $package: Debian's $source $version, from $suite"
      got=1
      break
    fi
    # apt says "E: Failed to fetch URL  404  Not Found [IP: ...]": the file and the answer.
    missing=$(sed -n 's|^.*Failed to fetch [^ ]*/\([^/ ]*\) *\(.*\)$|\1: \2|p' "$APT/source.log" | head -n1 \
      | sed 's/ *\[IP:.*//; s/  */ /g')
    [ -n "$missing" ] || missing=$(grep -m1 '^E:' "$APT/source.log" | sed 's/^E: //')
    echo "sources: $package: $suite's archive does not serve its source whole (${missing:-apt-get source failed}); trying the next suite"
  done
  [ -n "$got" ] || { echo "sources: no suite of $SUITES serves $package's source whole (mirror $MIRROR)" >&2; exit 1; }
done
mv "$DEST/ORIGIN.part" "$DEST/ORIGIN"
