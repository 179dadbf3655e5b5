#!/usr/bin/env python3
"""Expressions and layers: ember's one pass against chains of binary Booleans.

    bench/expressions/run.py [--build build] [--threads 2] [--repeats 5] [--operands 4]
                             [--meshes A B C D ...] [--peer-manifold PATH]

Runs build/bin/bench_expressions on four or more overlapping meshes (by
default the first --operands meshes of ../shared/data/clean_pool_1k_100k.txt
after a seeded shuffle; procedural solids when the data is absent). That
binary times, in one process, each expression in one pass and as a chain of
binary Booleans through ember (each step's rounded result the next step's
operand), and all layers from one call against one --min-k Boolean per k.

With --peer-manifold (the native Manifold driver built from ../shared/peers,
`peer-manifold OP A.obj B.obj OUT.obj`, timing contract time_ms=...), the same
chains run through native Manifold on the same placed operands, and the table
gives ember's one-pass speed-up over them. Manifold's figure is the sum of
its steps' Boolean times (each step imports the previous step's mesh, as a
chain of separate Booleans must); file I/O is not counted for either tool.
"""
from __future__ import annotations

import argparse
import os
import random
import re
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
DATA = REPO.parent / "shared" / "data"

# Each expression as binary steps: (op, left, right, result); names are
# operands op0..op3 or earlier results.
CHAINS = {
    "((A|B)-C)&D": [("union", "op0", "op1", "t1"), ("difference", "t1", "op2", "t2"), ("intersection", "t2", "op3", "out")],
    "(A^B)|(C-D)": [("difference", "op0", "op1", "x1"), ("difference", "op1", "op0", "x2"), ("union", "x1", "x2", "x"),
                    ("difference", "op2", "op3", "y"), ("union", "x", "y", "out")],
    "A-B-C-D": [("difference", "op0", "op1", "t1"), ("difference", "t1", "op2", "t2"), ("difference", "t2", "op3", "out")],
}


def pick_meshes(count: int, seed: int) -> list[str]:
    pool = DATA / "clean_pool_1k_100k.txt"
    if not pool.exists():
        return []
    names = [l.strip() for l in pool.read_text().splitlines() if l.strip()]
    random.Random(seed).shuffle(names)
    return [str(DATA / n) for n in names[:count]]


def manifold_chain(peer: str, work: Path, steps, threads: int) -> float | None:
    env = dict(os.environ, PEER_THREADS=str(threads))
    total = 0.0
    for op, a, b, out in steps:
        r = subprocess.run([peer, op, str(work / f"{a}.obj"), str(work / f"{b}.obj"), str(work / f"{out}.obj")],
                           capture_output=True, text=True, env=env, timeout=600)
        m = re.search(r"time_ms=([0-9.]+) status=ok", r.stdout)
        if not m:
            print(f"  manifold {op} {a} {b}: {r.stdout.strip()} {r.stderr.strip()[:200]}", file=sys.stderr)
            return None
        total += float(m.group(1))
    return total


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(REPO / "build"))
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--operands", type=int, default=4, help="operands for the layers (the expressions use 4)")
    ap.add_argument("--seed", type=int, default=3)
    ap.add_argument("--meshes", nargs="*")
    ap.add_argument("--peer-manifold", help="path of the native Manifold driver (peer-manifold)")
    args = ap.parse_args()
    meshes = args.meshes or pick_meshes(max(4, args.operands), args.seed)
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        cmd = [str(Path(args.build) / "bin" / "bench_expressions"), "--threads", str(args.threads), "--repeats",
               str(args.repeats), "--write", str(work), *meshes]
        print("meshes:", " ".join(Path(m).name for m in meshes) or "procedural")
        r = subprocess.run(cmd, capture_output=True, text=True)
        sys.stdout.write(r.stdout)
        if r.returncode != 0:
            sys.stderr.write(r.stderr)
            return r.returncode
        if not args.peer_manifold:
            return 0
        one_pass = {}
        for line in r.stdout.splitlines():
            parts = line.split()
            if parts and parts[0] in CHAINS:
                one_pass[parts[0]] = float(parts[1])
        print(f"\nnative Manifold ({args.threads} threads), the same chains of binary Booleans:")
        print(f"{'expression':<14} {'ember 1-pass':>12} {'Manifold ms':>12} {'speedup':>8}")
        for name, steps in CHAINS.items():
            t = manifold_chain(args.peer_manifold, work, steps, args.threads)
            shown = f"{t:12.1f} {t / one_pass[name]:7.2f}x" if t is not None else f"{'failed':>12}"
            print(f"{name:<14} {one_pass[name]:12.1f} {shown}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
