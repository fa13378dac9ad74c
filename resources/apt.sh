# Debian package helpers, sourced by setup.sh and bundle.sh (and tests/fresh/run.sh).

installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }

# Installs the packages that are not yet installed (idempotent).
install_missing() {
  missing=""
  for p in "$@"; do installed "$p" || missing="$missing $p"; done
  [ -n "$missing" ] || return 0
  echo "setup: installing$missing"
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=""; fi
  # One install at a time: CI runs its stages side by side (.ci/run), and apt
  # refuses to run twice.
  $SUDO flock /var/lib/dpkg/plungerough.lock sh -c "apt-get update -qq &&
    DEBIAN_FRONTEND=noninteractive DEBCONF_NOWARNINGS=yes apt-get install -y -qq --no-install-recommends $missing >/dev/null"
}

# This machine's Debian mirror (deb822 sources first, then sources.list).
mirror() {
  m=$(grep -hs '^URIs:' /etc/apt/sources.list.d/*.sources | awk '{print $2}' | grep -v security | head -n1)
  [ -n "$m" ] || m=$(grep -hs '^deb ' /etc/apt/sources.list | awk '{print $2}' | grep -v security | head -n1)
  echo "${m:-http://deb.debian.org/debian}"
}
