#!/usr/bin/env bash
# Install the real services and programs the tests start on loopback, from Debian's
# packages: Redis (episode store) and Chromium (viewer tests, driven by Playwright; its
# own browser download cannot work here). Idempotent; needs root or sudo.
set -euo pipefail
missing=()
command -v redis-server >/dev/null || missing+=(redis-server)
[ -x /usr/bin/chromium ] || missing+=(chromium)
[ ${#missing[@]} -eq 0 ] && exit 0
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "installing ${missing[*]} from Debian's packages" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
