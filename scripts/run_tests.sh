#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Quick start 2: install what is missing, then build and run the whole test suite in Release,
# and every test once more under run-time checks: the labels unit and cli but not repeat
# with AddressSanitizer, LeakSanitizer and UndefinedBehaviorSanitizer on top of -fcheck=all
# and floating-point traps (build-asan/, where any report fails the test), the rest (labels
# repeat and extremes: tests/CMakeLists.txt says why) in Debug with -fcheck=all and the traps.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/dev/install_deps.sh"
status=0
start=$SECONDS
for type in Release Debug Asan; do
    bash "$root/scripts/dev/build.sh" "$type"
    folder="$root/build-$(echo "$type" | tr '[:upper:]' '[:lower:]')"
    [[ $type != Release ]] || folder="$root/build"
    labels=()
    case $type in
        Debug) labels=(-L 'repeat|extremes') ;;
        Asan) labels=(-L 'unit|cli' -LE repeat) ;;
    esac
    echo "== ctest ($type${labels:+: ${labels[*]}})"
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 \
    LSAN_OPTIONS=suppressions="$root/tests/lsan.supp":print_suppressions=0 \
        ctest --test-dir "$folder" --output-on-failure -j "$(nproc)" "${labels[@]}" || status=1
done
echo "== run_tests.sh: $((SECONDS - start)) s"
exit $status
