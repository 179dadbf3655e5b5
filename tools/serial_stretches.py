#!/usr/bin/env python3
"""Where a Boolean runs serially: a perf profile split by whether each sample's call stack
is inside a oneTBB parallel construct.

A sample inside ember::boolean whose stack holds no parallel loop body, reduction, scan,
task group or parallel_invoke branch ran while the other threads could only wait (or
spin). At 1 thread their share s of all samples is the serial share of the work, and
Amdahl's law bounds the speed-up on P threads by 1 / (s + (1 - s) / P). The one
deliberate exception is the manifold components' flood fill, which ember runs only at one
thread (at more, a concurrent union-find): it is listed apart and left out of s.

  tools/serial_stretches.py build/bin/ember_bench A.bin B.bin [--threads 1] [--runs 3]

Needs perf (Debian: linux-perf) and a build with debug information (for example
-DCMAKE_CXX_FLAGS=-g) so that perf can unwind through inlined frames; ember_bench is the
comparison benchmark's runner (bench/compare, EMBER_BUILD_PEERS=ON), the meshes its .bin
files (`ember_bench prepare`).
"""
import argparse
import collections
import re
import subprocess
import sys
import tempfile

# The bodies of oneTBB's loops, reductions, scans, task groups and parallel_invoke branches
# (namespace d1 in oneTBB 2021; any dN, should a later version move them).
PARALLEL = re.compile(r"tbb::detail::d\d+::(start_for|start_reduce|start_scan|start_deterministic_reduce|"
                      r"function_invoker|function_task|function_stack_task|sum_node|final_sum)|parallel_scan<")
# At one thread the components' flood fill (serial_components, often unwound as its caller
# components<...>) is the chosen algorithm, not a stretch the other threads wait through.
ONE_THREAD_ONLY = re.compile(r"serial_components|::components<")


def stacks(perf_script_text):
    """Per sample, its frames' symbols, innermost first."""
    for block in perf_script_text.split("\n\n"):
        lines = [line.strip() for line in block.strip().split("\n")[1:]]
        yield [line.split(" ", 1)[1] if " " in line else "" for line in lines]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("bench")
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--op", default="union")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--top", type=int, default=12, help="serial call stacks to list")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        data = f"{tmp}/perf.data"
        subprocess.run(["perf", "record", "-q", "-F", "2000", "--call-graph", "dwarf,16384", "-o", data, args.bench,
                        "run", args.a, args.b, "--ops", args.op, "--runs", str(args.runs), "--threads",
                        str(args.threads)], check=True, stdout=subprocess.DEVNULL)
        text = subprocess.run(["perf", "script", "-i", data, "-F", "comm,tid,ip,sym"], check=True,
                              capture_output=True, text=True).stdout
    total = serial = one_thread_only = 0
    where = collections.Counter()
    for syms in stacks(text):
        if not any("ember::boolean(" in s for s in syms):
            continue
        total += 1
        if any(PARALLEL.search(s) for s in syms):
            continue
        if any(ONE_THREAD_ONLY.search(s) for s in syms):
            one_thread_only += 1
            continue
        serial += 1
        named = [s for s in syms if "ember::" in s or "std::" in s or "(inlined)" in s]
        where[" < ".join(s[:60] for s in named[:4])] += 1
    if total == 0:
        sys.exit("no samples inside ember::boolean (is perf allowed to profile? is the build's debug info there?)")
    counted = max(1, total - one_thread_only)
    s = serial / counted
    # Only the calling thread's stacks reach ember::boolean: at one thread its samples are all
    # the work; at more, the share is of the calling thread's time (the workers' is left out).
    of_what = "of the work" if args.threads == 1 else "of the calling thread's samples"
    print(f"{args.threads} thread(s), {args.runs} run(s): {total} samples inside ember::boolean")
    print(f"  serial (no parallel construct on the stack): {serial} ({100 * s:.2f}% {of_what},"
          f" not counting the one-thread-only flood fill's {one_thread_only})")
    if args.threads == 1:
        for p in (2, 4, 8, 16):
            print(f"  Amdahl bound on {p:2d} threads: {1 / (s + (1 - s) / p):.1f}x")
    for stack, count in where.most_common(args.top):
        print(f"  {count:5d}  {stack}")


if __name__ == "__main__":
    main()
