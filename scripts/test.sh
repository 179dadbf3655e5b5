#!/usr/bin/env bash
# Set-up, build and run the whole test suite (README command 2), then build
# again with AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/) and
# run the suite once more: memory errors and undefined behaviour fail the run.
#
#   scripts/test.sh                  # both passes (what .ci/run does; ~12 min on 2 cores)
#   scripts/test.sh --no-sanitizers  # the Release pass only (~3 min)
set -euo pipefail
cd "$(dirname "$0")/.."
sanitizers=1
for a in "$@"; do
  case "$a" in
    --no-sanitizers) sanitizers=0 ;;
    *) echo "usage: scripts/test.sh [--no-sanitizers]" >&2; exit 2 ;;
  esac
done
scripts/setup.sh
scripts/build.sh
(cd build && ctest --output-on-failure -j"$(nproc)")
if [[ $sanitizers == 1 ]]; then
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DEMBER_SANITIZE=ON >/dev/null
  cmake --build build-asan -j"$(nproc)"
  # halt_on_error: the first finding fails its test; UBSan findings are fatal (-fno-sanitize-recover).
  # Leak checking is off: LeakSanitizer needs ptrace, which some CI sandboxes forbid.
  (cd build-asan && ASAN_OPTIONS=halt_on_error=1:detect_leaks=0 ctest --output-on-failure -j"$(nproc)")
fi
