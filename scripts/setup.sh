#!/usr/bin/env bash
# Installs ember's build and test dependencies from Debian packages (skips apt when all are present).
set -euo pipefail
packages=(cmake make g++ libgtest-dev libbenchmark-dev libtbb-dev libgmp-dev libcli11-dev lib3mf-dev libtinygltf-dev zlib1g-dev
          python3 python3-dev pybind11-dev python3-pybind11 python3-numpy python3-distributed)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y "${missing[@]}"
fi
