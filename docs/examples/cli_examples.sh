#!/usr/bin/env bash
# The commands of docs/cli.md, run by ctest (docs.cli_examples):
#   docs/examples/cli_examples.sh EMBER_BINARY WORK_DIR
# Each step checks what the page says it does.
set -euo pipefail
ember=$1
work=$2
examples=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "cli_examples: $*" >&2; exit 1; }

# Two built-in solids to work on (torus.obj, sphere.obj, and their Booleans).
"$ember" demo -o demo
# A Boolean of two files, the format from the extension; --stats prints JSON on stderr.
"$ember" union demo/torus.obj demo/sphere.obj -o union.3mf --stats 2> stats.json
grep -q '"operation": "union"' stats.json || fail "--stats printed no JSON"
# 3MF in and out; each object of a 3MF file is one operand: here cube 1 - cube 2 - sphere.
"$ember" difference "$examples/two_cubes.3mf" demo/sphere.obj -o cut.3mf
# Any number of inputs; at least 2 of 3.
"$ember" union demo/torus.obj demo/sphere.obj "$examples/two_cubes.3mf" --min-k 2 -o overlap.ply
# Any CSG expression in one Boolean; quote names with spaces; a file named twice is read once.
cp demo/sphere.obj "ball 1.obj"
"$ember" eval "(demo/torus.obj | 'ball 1.obj') - (demo/torus.obj & demo/difference.obj)" -o expr.obj
for f in union.3mf cut.3mf overlap.ply expr.obj; do [[ -s $f ]] || fail "$f not written"; done

# Errors: one line on stderr, exit status 1, no output file.
echo "not a mesh" > broken.stl
if "$ember" union broken.stl demo/sphere.obj -o never.obj 2> error.txt; then fail "a broken input succeeded"; fi
[[ ! -e never.obj ]] || fail "a failed run left an output file"
grep -q '^ember: broken.stl' error.txt || fail "the error does not name the file: $(cat error.txt)"

# Warnings (here: an open input accepted with --allow-open) go to stderr; --quiet silences them.
head -n -1 "$examples/cli_open_tetra.obj" > open.obj
"$ember" union open.obj demo/sphere.obj --allow-open -o open_union.obj 2> warn.txt
grep -q 'warning' warn.txt || fail "no warning for an open input"
"$ember" union open.obj demo/sphere.obj --allow-open --quiet -o open_union.obj 2> quiet.txt
[[ ! -s quiet.txt ]] || fail "--quiet printed: $(cat quiet.txt)"
echo "cli_examples: all passed"
