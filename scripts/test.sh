#!/usr/bin/env bash
# Set-up, build and run the whole test suite (README command 2).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
cd build && ctest --output-on-failure -j"$(nproc)"
