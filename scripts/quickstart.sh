#!/usr/bin/env bash
# README command (1): install dependencies, build, and run the demo Boolean.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
build/bin/ember demo -o build/demo
