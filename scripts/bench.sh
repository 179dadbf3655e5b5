#!/usr/bin/env bash
# The comparison benchmark: ember vs CGAL corefinement (Epick) vs
# Manifold (manifold-3d WASM) on the EMBER paper's Section 5.1 protocol.
# Details: docs/benchmark.md.
#
#   scripts/bench.sh [--quick] [--threads 1,2] [--runs 5] [--out DIR] [more bench.py options]
#
# One command: installs what it needs (apt: cmake, g++, libcgal-dev, libtbb-dev,
# python3-matplotlib, valgrind, nodejs/npm; npm: manifold-3d into bench/peers/node_modules),
# builds ember_bench and cgal_runner into build-bench/ (-DEMBER_BUILD_PEERS=ON),
# runs every case over ../shared/data and writes DIR (default bench-results/):
#   results.csv  one row per case and operation (times, ratios, throughput, RSS, volumes, failures)
#   summary.md   geometric means, per-case times and ratios, throughput, per-phase times,
#                thread scaling, first-run times, peak RSS and instructions (callgrind) per input
#                triangle, failures, volume check, machine, date; printed at the end and, on a
#                full run, copied to docs/benchmark-results.md
#   time_vs_size.png  time vs input triangles (log-log), one series per tool
# Options:
#   --quick        a few small cases (smoke run, ~3 min)
#   --threads L    ember thread counts, comma separated (default 1,<nproc>)
#   --runs R       timed runs per case/tool/op, median reported (default 5)
#   --out DIR      output folder (default bench-results)
#   --no-install   skip apt/npm (everything already there)
#   any other option goes to bench/compare/bench.py (see --help there), e.g.
#   --pairs N, --seed S, --budget-ms B, --tools ember,cgal, --scaling-ops union,difference
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD

install=1
quick=0
pass=()
for a in "$@"; do
  if [[ "$a" == "--no-install" ]]; then install=0; else pass+=("$a"); fi
  [[ "$a" == "--quick" ]] && quick=1
done
# A full run is the project's published figure: it regenerates docs/benchmark-results.md.
[[ $quick == 0 ]] && pass+=(--docs "$ROOT/docs/benchmark-results.md")

if [[ $install == 1 ]]; then
  need_apt=()
  for p in cmake g++ libtbb-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev python3 python3-matplotlib valgrind; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need_apt+=("$p")
  done
  # node/npm may come from elsewhere than Debian; only ask apt when they are missing
  command -v node >/dev/null || need_apt+=(nodejs)
  command -v npm >/dev/null || need_apt+=(npm)
  if (( ${#need_apt[@]} )); then
    echo "bench.sh: apt-get install ${need_apt[*]}" >&2
    SUDO=""; [[ $(id -u) == 0 ]] || SUDO=sudo
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need_apt[@]}" >/dev/null
  fi
  if [[ ! -d bench/peers/node_modules/manifold-3d ]]; then
    echo "bench.sh: npm install (manifold-3d) in bench/peers" >&2
    (cd bench/peers && npm install --no-audit --no-fund --loglevel=error)
  fi
fi

echo "bench.sh: building ember_bench and cgal_runner in build-bench/" >&2
cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DEMBER_BUILD_PEERS=ON \
      -DEMBER_BUILD_TESTS=OFF -DEMBER_BUILD_BENCH=OFF >/dev/null
cmake --build build-bench -j"$(nproc)" --target ember_bench cgal_runner >/dev/null

# Debian's python3 has python3-matplotlib; a python3 earlier on PATH (pyenv, venv) may not
PY=python3; [[ -x /usr/bin/python3 ]] && PY=/usr/bin/python3
exec "$PY" bench/compare/bench.py --bin "$ROOT/build-bench/bin" "${pass[@]}"
