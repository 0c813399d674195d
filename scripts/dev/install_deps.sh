#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Install the Debian 12 packages nceig needs to build, test and plot, skipping what is there.
# Another apt or dpkg (unattended-upgrades, a second terminal) may hold the package
# database's lock: then apt-get fails at once (exit 100). Each apt-get here waits for the
# lock instead, up to NCEIG_APT_LOCK_WAIT seconds (default 300; it tries again every
# NCEIG_APT_LOCK_POLL seconds, default 5), saying so in one line.
set -euo pipefail
packages=(cmake make gfortran gcc pkg-config libopenblas-dev liblapack-dev libarpack2-dev
          libsuitesparse-dev libmetis-dev gmsh gnuplot-nox time jq parallel)
lock_wait=${NCEIG_APT_LOCK_WAIT:-300}
lock_poll=${NCEIG_APT_LOCK_POLL:-5}
missing=()
for package in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" \
        || missing+=("$package")
done
((${#missing[@]} > 0)) || exit 0

sudo_cmd=()
[[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
errors=$(mktemp)
trap 'rm -f "$errors"' EXIT
said=0
# apt_get ARGS...: apt-get ARGS, run again every lock_poll s while it fails only because another
# process holds a lock (apt's own messages: "Could not get lock ...", "Unable to acquire the
# dpkg frontend lock ...", "Unable to lock ..."), for lock_wait seconds at most.
apt_get() {
    local start=$SECONDS
    while :; do
        if DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get "$@" 2>"$errors"; then
            cat "$errors" >&2
            return 0
        fi
        if ! grep -q -E 'Could not get lock|Unable to acquire the dpkg frontend lock|Unable to lock' \
                "$errors" || ((SECONDS - start >= lock_wait)); then
            cat "$errors" >&2
            return 1
        fi
        if ((said == 0)); then
            echo "install_deps: another apt or dpkg holds the package lock: waiting for it" \
                "(at most $lock_wait s)"
            said=1
        fi
        sleep "$lock_poll"
    done
}

echo "install_deps: installing ${missing[*]}"
apt_get update -qq
apt_get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
