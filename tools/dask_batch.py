#!/usr/bin/env python3
"""Booleans over a whole folder of meshes on Dask (distributed), or in a plain loop.

    tools/dask_batch.py DIR OUT [--op union] [--pairs | --each] [--scheduler ADDR]
                        [--workers 2] [--threads 1] [--limit N] [--serial]
    tools/dask_batch.py --cases ../shared/data/peer-tests/manifold/ember/cases_with_local_meshes.tsv OUT ...

Pairs up the mesh files of DIR (sorted by name: file 0 with 1, 2 with 3, ...;
--each: every file with itself turned by 5 degrees) and runs one ember
Boolean per pair as one Dask task. Each operand is scaled into the unit box
and the second one turned, so that the pair overlaps (as the EMBER paper's
benchmark does). Results are written atomically to OUT/NAME.ply (a temporary
name, then a rename), and a task that fails (a broken mesh, an open one, an
error of any kind) is recorded as a result: the batch never stops on one bad
file. Prints a summary table (tasks, failures with their messages, time,
throughput) and writes it to OUT/summary.md.

Without --scheduler it starts a LocalCluster of --workers processes with
--threads ember threads per task; with --scheduler tcp://HOST:PORT it
submits to a running cluster whose workers can import ember (PYTHONPATH or
an installed module). --serial runs the same tasks in a plain loop here,
for comparison. --cases TSV runs the EMBER paper's benchmark cases instead
(columns path_a, path_b relative to --data, transform_a/b_colmajor_4x4).
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import tempfile
import time
from pathlib import Path

MESH_EXTENSIONS = {".obj", ".stl", ".ply", ".off", ".3mf", ".gltf", ".glb"}


def placed(vertices, turn_degrees):
    """Scaled into the unit box around the origin, turned about (1, 2, 3)."""
    import numpy as np

    v = np.asarray(vertices, dtype=np.float64)
    lo, hi = v.min(axis=0), v.max(axis=0)
    v = (v - (lo + hi) / 2) / max(float((hi - lo).max()), 1e-300)
    if turn_degrees:
        axis = np.array([1.0, 2.0, 3.0]) / math.sqrt(14.0)
        a = math.radians(turn_degrees)
        k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
        r = np.eye(3) + math.sin(a) * k + (1 - math.cos(a)) * (k @ k)
        v = v @ r.T + np.array([0.1, 0.05, 0.0])
    return v


def transformed(vertices, colmajor):
    import numpy as np

    m = np.array(colmajor, dtype=np.float64).reshape(4, 4).T
    v = np.asarray(vertices, dtype=np.float64)
    return v @ m[:3, :3].T + m[:3, 3]


def run_task(a: str, b: str | None, op: str, out: str, threads: int, transforms=None) -> dict:
    """One Boolean; never raises: a failure is a result with its message."""
    import warnings

    import ember

    name = Path(out).stem
    start = time.perf_counter()
    try:
        va, fa = ember.read(a)
        vb, fb = ember.read(b) if b else (va, fa)
        if transforms:
            mesh_a, mesh_b = (transformed(va, transforms[0]), fa), (transformed(vb, transforms[1]), fb)
        else:
            mesh_a = (placed(va, 0), fa)
            mesh_b = (placed(vb, 5.0 if b is None else 20.0), fb)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            v, f, stats = getattr(ember, op)(mesh_a, mesh_b, threads=threads, return_stats=True)
        # Atomic: a reader of OUT never sees a half-written result.
        fd, tmp = tempfile.mkstemp(dir=os.path.dirname(out), prefix=".ember-", suffix=".ply")
        os.close(fd)
        try:
            ember.write(tmp, (v, f))
            os.replace(tmp, out)
        finally:
            if os.path.exists(tmp):
                os.remove(tmp)
        return {"name": name, "ok": True, "ms": (time.perf_counter() - start) * 1e3,
                "boolean_ms": stats["time_ms"], "triangles": int(stats["input_triangles"]), "error": "",
                "warnings": len(caught)}
    except Exception as e:  # a bad mesh is a result, not the end of the batch
        return {"name": name, "ok": False, "ms": (time.perf_counter() - start) * 1e3, "boolean_ms": 0.0,
                "triangles": 0, "error": f"{type(e).__name__}: {e}", "warnings": 0}


def cases_of(tsv: Path, data: Path, out: Path, limit: int | None):
    import csv

    rows = list(csv.DictReader(tsv.open(), delimiter="\t"))[:limit]
    return [(str(data / r["path_a"]), str(data / r["path_b"]), str(out / f"case{r['case_index']}.ply"),
             ([float(x) for x in r["transform_a_colmajor_4x4"].split(",")],
              [float(x) for x in r["transform_b_colmajor_4x4"].split(",")])) for r in rows]


def tasks_of(folder: Path, out: Path, each: bool, limit: int | None):
    files = sorted(p for p in folder.iterdir() if p.is_file() and p.suffix.lower() in MESH_EXTENSIONS)
    if limit:
        files = files[: limit if each else 2 * limit]
    if each:
        return [(str(f), None, str(out / f"{f.stem}.ply"), None) for f in files]
    return [(str(files[i]), str(files[i + 1]), str(out / f"{files[i].stem}+{files[i + 1].stem}.ply"), None)
            for i in range(0, len(files) - 1, 2)]


def summary(results, wall_s: float, mode: str) -> str:
    ok = [r for r in results if r["ok"]]
    tris = sum(r["triangles"] for r in ok)
    lines = [f"## ember batch ({mode})", "",
             "| tasks | ok | failed | with warnings | wall s | Booleans/s | input triangles/s | sum of Boolean ms |",
             "|---|---|---|---|---|---|---|---|",
             f"| {len(results)} | {len(ok)} | {len(results) - len(ok)} | {sum(1 for r in ok if r['warnings'])} | "
             f"{wall_s:.2f} | {len(ok) / wall_s:.2f} | {tris / wall_s:,.0f} | "
             f"{sum(r['boolean_ms'] for r in ok):.0f} |", ""]
    failed = [r for r in results if not r["ok"]]
    if failed:
        lines += ["| failed task | error |", "|---|---|"]
        lines += [f"| {r['name']} | {r['error'][:200].replace('|', '/')} |" for r in failed]
        lines.append("")
    return "\n".join(lines)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("folder", type=Path, nargs="?", help="a folder of meshes (or use --cases)")
    ap.add_argument("out", type=Path)
    ap.add_argument("--cases", type=Path, help="a TSV of benchmark cases (path_a, path_b, transforms)")
    ap.add_argument("--data", type=Path, default=Path(__file__).resolve().parents[2] / "shared" / "data",
                    help="root of the case paths (default ../shared/data)")
    ap.add_argument("--op", default="union", choices=["union", "intersection", "difference", "xor"])
    mode = ap.add_mutually_exclusive_group()
    mode.add_argument("--pairs", action="store_true", help="file 2i with file 2i+1 (default)")
    mode.add_argument("--each", action="store_true", help="every file with itself turned by 5 degrees")
    ap.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster)")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes")
    ap.add_argument("--threads", type=int, default=1, help="ember threads per task")
    ap.add_argument("--limit", type=int, help="at most this many tasks")
    ap.add_argument("--serial", action="store_true", help="a plain loop in this process instead of Dask")
    args = ap.parse_args()
    if args.cases is None and (args.folder is None or not args.folder.is_dir()):
        print(f"dask_batch: {args.folder} is not a folder (give a folder of meshes or --cases TSV)", file=sys.stderr)
        return 2
    args.out.mkdir(parents=True, exist_ok=True)
    tasks = (cases_of(args.cases, args.data, args.out, args.limit) if args.cases
             else tasks_of(args.folder, args.out, args.each, args.limit))
    if not tasks:
        print(f"dask_batch: no mesh files in {args.folder}", file=sys.stderr)
        return 2
    start = time.perf_counter()
    if args.serial:
        results = [run_task(a, b, args.op, o, args.threads, t) for a, b, o, t in tasks]
        label = "plain loop, 1 process"
    else:
        from dask.distributed import Client, LocalCluster

        cluster = None
        if args.scheduler:
            client = Client(args.scheduler)
            label = f"Dask scheduler {args.scheduler}"
        else:
            cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None)
            client = Client(cluster)
            label = f"Dask LocalCluster, {args.workers} workers"
        start = time.perf_counter()  # the cluster's start-up is not the batch's
        futures = [client.submit(run_task, a, b, args.op, o, args.threads, t, pure=False) for a, b, o, t in tasks]
        results = client.gather(futures)
        client.close()
        if cluster:
            cluster.close()
    wall = time.perf_counter() - start
    text = summary(results, wall, label)
    print(text)
    (args.out / "summary.md").write_text(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
