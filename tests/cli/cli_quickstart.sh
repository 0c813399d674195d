#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The quick start's scripts, with stand-ins for apt-get, dpkg-query and cmake on the PATH
# (nothing is installed or built): install_deps.sh waits while another apt holds the
# package lock (it failed at once, exit 100), saying so in one line, and gives up after
# NCEIG_APT_LOCK_WAIT seconds with apt's message; any other apt failure fails at once;
# run_reference.sh builds the program alone (it built every test program first, 11 minutes
# on a loaded machine) and runs the reference scene.
# Usage: cli_quickstart.sh NCEIG SOURCE_DIR
set -u
source_dir=$2
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_quickstart
cd "$work"
mkdir bin
# dpkg-query: every package missing; sudo: runs its command (a test run as another user).
printf '#!/bin/sh\nexit 1\n' >bin/dpkg-query
printf '#!/bin/sh\nexec "$@"\n' >bin/sudo
# apt-get: fails with apt's lock message while the file `locked` holds a number above 0
# (counting it down), or with the message in `fails` when that file exists; logs its calls.
cat >bin/apt-get <<'SH'
#!/bin/sh
echo "apt-get $*" >>calls.log
if [ -s fails ]; then cat fails >&2; exit 100; fi
n=$(cat locked 2>/dev/null || echo 0)
if [ "$n" -gt 0 ]; then
    echo $((n - 1)) >locked
    echo "E: Could not get lock /var/lib/dpkg/lock-frontend. It is held by process 4242 (apt-get)" >&2
    echo "E: Unable to acquire the dpkg frontend lock (/var/lib/dpkg/lock-frontend), is another process using it?" >&2
    exit 100
fi
exit 0
SH
chmod +x bin/*
install_deps() {
    rm -f calls.log
    PATH="$work/bin:$PATH" NCEIG_APT_LOCK_POLL=0.1 NCEIG_APT_LOCK_WAIT=$1 \
        bash "$source_dir/scripts/dev/install_deps.sh" >out 2>err
    rc=$?
}

echo 3 >locked
install_deps 60
check 'the lock held for three tries: waits, then installs (exit 0)' \
    '[[ $rc -eq 0 && $(grep -c "^apt-get install" calls.log) -eq 1 && $(grep -c "^apt-get update" calls.log) -eq 4 ]]'
check 'one line says it waits for the lock' \
    '[[ $(grep -c "holds the package lock: waiting for it" out) -eq 1 && ! -s err ]]'

echo 1000000 >locked
install_deps 1
check 'a lock never released: gives up after NCEIG_APT_LOCK_WAIT with apt'"'"'s message' \
    '[[ $rc -ne 0 ]] && grep -q "Could not get lock" err && ! grep -q "^apt-get install" calls.log'

rm -f locked
echo 'E: Unable to locate package gmsh' >fails
install_deps 60
check 'another failure fails at once, no waiting' \
    '[[ $rc -ne 0 && $(wc -l <calls.log) -eq 1 ]] && ! grep -q waiting out && grep -q "Unable to locate" err'
rm -f fails

# run_reference.sh in a copy of the scripts, install_deps.sh a stand-in; cmake logs its
# arguments and "builds" build/nceig, which prints its own.
mkdir -p tree/scripts/dev tree/input
cp "$source_dir/scripts/run_reference.sh" tree/scripts/
cp "$source_dir/scripts/dev/build.sh" tree/scripts/dev/
printf '#!/bin/sh\nexit 0\n' >tree/scripts/dev/install_deps.sh
cat >bin/cmake <<'SH'
#!/bin/sh
echo "cmake $*" >>"$CMAKE_LOG"
if [ "$1" = --build ]; then
    mkdir -p "$2"
    printf '#!/bin/sh\necho "nceig $*"\n' >"$2/nceig"
    chmod +x "$2/nceig"
fi
SH
chmod +x bin/cmake
CMAKE_LOG="$work/cmake.log" PATH="$work/bin:$PATH" bash tree/scripts/run_reference.sh >out 2>err
rc=$?
cat cmake.log | sed 's/^/      /'
check 'run_reference.sh builds the nceig target only (not the tests)' \
    '[[ $rc -eq 0 ]] && grep -q -- "^cmake --build .*/build -j [0-9]* --target nceig$" cmake.log'
check 'run_reference.sh then runs the reference scene' 'grep -q "^nceig input/square.nml$" out'

cli_end
