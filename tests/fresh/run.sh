#!/bin/sh
# Proves the README on a pristine Debian: makes a minimal chroot of SUITE
# (debootstrap --variant=minbase, from this machine's Debian mirror), clones this
# checkout into it and runs the README's two commands there, exactly as the
# README writes them, as root.
#
#   sh tests/fresh/run.sh bookworm          # Debian 12, FreeCAD 0.20.2: both commands
#   sh tests/fresh/run.sh trixie test       # Debian 13, FreeCAD 1.0: the test command only
#   sh tests/fresh/run.sh trixie main       # ... the main command only
#   sh tests/fresh/run.sh forky             # Debian testing, FreeCAD 1.1: both
#
# Only the debootstrap result is cached (PLUNGE_FRESH_CACHE, default
# /var/cache/plungerough-fresh/SUITE-minbase.tar): it *is* the fresh machine.
# Everything the README installs is installed again on every run, in a new
# root extracted from that tarball (PLUNGE_FRESH_ROOT, default
# /var/tmp/plungerough-fresh/SUITE). The clone is of the checkout's HEAD
# (commit first); PLUNGE_FRESH_WORKTREE=1 copies the working tree instead.
# The environment inside is a clean root login's, plus PLUNGE_WERROR (CI's
# -Werror, see resources/setup.sh) and the bundle under test (below).
# Needs root on a Debian host (debootstrap is installed if missing).
set -eu
SUITE=${1:?usage: run.sh bookworm|trixie|forky [all|main|test]}
WHAT=${2:-all}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
CACHE=${PLUNGE_FRESH_CACHE:-/var/cache/plungerough-fresh}
BASE=${PLUNGE_FRESH_ROOT:-/var/tmp/plungerough-fresh}
DIR=$BASE/$SUITE
COPIER=  # the background copy of the bundle under test (bundle_in)
say() { echo "fresh[$SUITE]: $*"; }
die() { echo "fresh[$SUITE]: $*" >&2; exit 1; }

case $SUITE in bookworm|trixie|forky) ;; *) die "unknown suite '$SUITE' (bookworm, trixie or forky)";; esac
case $WHAT in all|main|test) ;; *) die "unknown step '$WHAT' (all, main or test)";; esac
[ "$(id -u)" -eq 0 ] || die "needs root (debootstrap, chroot, mounts)"

# The README's two commands: the first ```sh block, one command per line.
COMMANDS=$(awk '/^```sh$/ {on=1; next} on && /^```/ {exit} on && NF' "$ROOT/README.md")
[ "$(printf '%s\n' "$COMMANDS" | wc -l)" -eq 2 ] || die "README.md does not start with exactly two commands"
MAIN_CMD=$(printf '%s\n' "$COMMANDS" | sed -n 1p)
TEST_CMD=$(printf '%s\n' "$COMMANDS" | sed -n 2p)

. "$ROOT/resources/apt.sh"  # install_missing, mirror

mounted_under() { awk -v d="$1" '$2 == d || index($2, d "/") == 1 {print $2}' /proc/mounts; }

release() {
  [ -z "$COPIER" ] || kill "$COPIER" 2>/dev/null || true
  [ -d "$DIR" ] || return 0
  # Processes left in the chroot (Xvfb, FreeCAD) hold its mounts.
  for p in /proc/[0-9]*; do
    [ "$(readlink "$p/root" 2>/dev/null)" = "$DIR" ] && kill -9 "${p#/proc/}" 2>/dev/null || true
  done
  for m in $(mounted_under "$DIR" | sort -r); do umount -l "$m" 2>/dev/null || true; done
  [ -z "$(mounted_under "$DIR")" ] || die "could not unmount everything under $DIR"
}

install_missing debootstrap

TARBALL=$CACHE/$SUITE-minbase.tar
if [ ! -s "$TARBALL" ]; then
  MIRROR=$(mirror)
  say "debootstrap --variant=minbase $SUITE from $MIRROR (cached in $TARBALL)"
  mkdir -p "$CACHE"
  tmp=$CACHE/$SUITE.tmp
  rm -rf --one-file-system "$tmp"
  # Debian 12's debootstrap has no script for forky; sid's makes testing as well.
  script=
  [ "$SUITE" = forky ] && [ ! -e /usr/share/debootstrap/scripts/forky ] && script=/usr/share/debootstrap/scripts/sid
  debootstrap --variant=minbase "$SUITE" "$tmp" "$MIRROR" $script >"$CACHE/$SUITE-debootstrap.log" 2>&1 \
    || { tail -n 20 "$CACHE/$SUITE-debootstrap.log" >&2; die "debootstrap failed"; }
  rm -rf "$tmp"/var/cache/apt/archives/*.deb
  tar -C "$tmp" -cf "$TARBALL.part" . && mv "$TARBALL.part" "$TARBALL"
  rm -rf --one-file-system "$tmp"
fi

release
rm -rf --one-file-system "$DIR"
mkdir -p "$DIR"
trap release EXIT INT TERM
tar -C "$DIR" -xf "$TARBALL"
cp /etc/resolv.conf "$DIR/etc/resolv.conf"
# A mirror's testing Release file can be past its Valid-Until date (the mirror
# here is a snapshot); a machine on a live mirror never sees that.
[ "$SUITE" = forky ] && printf 'Acquire::Check-Valid-Until "false";\nAcquire::Check-Date "false";\n' \
  >"$DIR/etc/apt/apt.conf.d/99plungerough-snapshot"
mount -t proc proc "$DIR/proc"
mount -t sysfs sysfs "$DIR/sys"
mount --rbind /dev "$DIR/dev"
mount -t tmpfs tmpfs "$DIR/tmp"

# The checkout, as a user clones it.
if [ "${PLUNGE_FRESH_WORKTREE:-0}" = 1 ]; then
  mkdir -p "$DIR/root/PlungeRough"
  (cd "$ROOT" && git ls-files -co --exclude-standard -z | xargs -0 cp --parents -t "$DIR/root/PlungeRough")
  say "copied the working tree of $ROOT"
else
  git clone --quiet "$ROOT" "$DIR/root/PlungeRough"
  say "cloned $ROOT at $(git -C "$ROOT" rev-parse --short HEAD)"
fi

# The bundle under test: PLUNGE_TEST_BUNDLE on the host (CI builds it once,
# on Debian 12, the way users get it, and every FreeCAD version tests that
# one). The host may still be building it when the test command starts (CI
# runs both side by side): it is copied in as soon as it is there (a copy
# under another name, then renamed), and the bundle's suite, which runs late
# in the test command, waits for it (PLUNGE_TEST_BUNDLE_WAIT), up to 40
# minutes in all, or until the host gives up on it (PLUNGE_TEST_BUNDLE.failed,
# passed on as the same name in the chroot). Without it, the test command
# builds this checkout's.
bundle_in() {
  [ -n "${PLUNGE_TEST_BUNDLE:-}" ] || return 0
  name=$(basename "$PLUNGE_TEST_BUNDLE")
  rm -f "$DIR/root/$name" "$DIR/root/$name.failed"
  (
    waited=0
    while [ ! -s "$PLUNGE_TEST_BUNDLE" ] && [ ! -e "$PLUNGE_TEST_BUNDLE.failed" ] && [ $waited -lt 2400 ]; do
      sleep 5
      waited=$((waited + 5))
    done
    if [ -s "$PLUNGE_TEST_BUNDLE" ]; then
      cp "$PLUNGE_TEST_BUNDLE" "$DIR/root/$name.part" && mv "$DIR/root/$name.part" "$DIR/root/$name"
      say "the bundle $PLUNGE_TEST_BUNDLE is in, after $waited s"
    else
      touch "$DIR/root/$name.failed"
      say "no bundle at $PLUNGE_TEST_BUNDLE after $waited s"
    fi
  ) &
  COPIER=$!
  BUNDLE_ENV="PLUNGE_TEST_BUNDLE=/root/$name PLUNGE_TEST_BUNDLE_WAIT=2400"
  say "testing the bundle $PLUNGE_TEST_BUNDLE (copied in when it is there)"
}
BUNDLE_ENV=

run_in_chroot() {
  say "\$ $1"
  env -i HOME=/root TERM=dumb LANG=C.UTF-8 PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    PLUNGE_WERROR="${PLUNGE_WERROR:-OFF}" PLUNGE_TEST_ADDON_BUILD="${PLUNGE_TEST_ADDON_BUILD:-0}" $2 \
    chroot "$DIR" /bin/sh -c "cd /root/PlungeRough && $1"
}

start=$(date +%s)
[ "$WHAT" = test ] || run_in_chroot "$MAIN_CMD" ""
[ "$WHAT" = main ] || { bundle_in; run_in_chroot "$TEST_CMD" "$BUNDLE_ENV"; }
say "passed ($WHAT) in $(( $(date +%s) - start )) s"
