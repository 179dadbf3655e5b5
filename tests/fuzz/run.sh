#!/usr/bin/env bash
# Runs a libFuzzer target for SECONDS on a seed corpus gathered at run time:
# up to 64 files smaller than 64 KiB with extension EXT from each SEED_DIR
# (copied into WORK/seeds; the seed folders are only read). New inputs go to
# WORK/corpus, findings to WORK/ as crash-*/leak-*/timeout-* files.
#
#   tests/fuzz/run.sh TARGET EXT SECONDS WORK SEED_DIR...
set -euo pipefail
target=$1 ext=$2 seconds=$3 work=$4
shift 4
mkdir -p "$work/seeds" "$work/corpus"
# The whole list is read before it is cut: `find | sort | head` would let
# head's early exit kill sort with SIGPIPE, which pipefail turns into a
# failed run whenever a folder holds more than 64 such files.
for d in "$@"; do
  [[ -d $d ]] || continue
  mapfile -t files < <(find "$d" -type f -iname "*.$ext" -size -64k 2>/dev/null | sort)
  for f in "${files[@]:0:64}"; do
    cp "$f" "$work/seeds/seed${f//\//_}"
  done
done
echo "seeds: $(find "$work/seeds" -type f | wc -l) files"
cd "$work"
# lib3mf's libzip leaks a few hundred bytes on every package it opens (not
# ember's memory, and nothing ember can free): leaks are not findings there.
extra=()
if [[ $ext == 3mf ]]; then
  extra+=(-detect_leaks=0)
  export ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0
fi
# -rss_limit_mb: a reader must bound its memory by the input size.
exec "$target" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 "${extra[@]}" corpus seeds
