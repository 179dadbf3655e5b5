#!/usr/bin/env python3
"""Comparison benchmark driver: ember vs CGAL corefinement vs Manifold.

Run through scripts/bench.sh (which installs the peers and builds the runners);
the full protocol is described in docs/benchmark.md. This script:

  1. builds the case list (seeded): random overlapping pool pairs (EMBER paper
     Section 5.1), the paper's own cases that have local meshes, and a scaling
     series (a mesh against itself slightly rotated, ~10k to ~1.2M input triangles);
  2. per case, writes both operands once to binary files (`ember_bench prepare`,
     untimed), then runs each tool as a separate process on them:
     `ember_bench run` (per thread count), `cgal_runner`, `node manifold_runner.mjs`;
     a crash, timeout or error in one tool is recorded and the harness goes on;
  3. writes results.csv, summary.md and time_vs_size.png into the output folder.
"""
from __future__ import annotations

import argparse
import csv
import datetime
import json
import math
import os
import platform
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import profile_tables
from profile_tables import fmt, gmean

OPS = ["union", "intersection", "difference"]
REPO = Path(__file__).resolve().parents[2]
T_START = time.monotonic()


def log(msg: str) -> None:
    el = time.monotonic() - T_START
    print(f"[bench {int(el) // 60:02d}:{int(el) % 60:02d}] {msg}", file=sys.stderr, flush=True)


# ---------------------------------------------------------------- transforms
def random_rotation(rng: random.Random) -> list[list[float]]:
    """Uniformly random rotation (Shoemake's method) as a row-major 3x3."""
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    q = (math.sqrt(1 - u1) * math.sin(2 * math.pi * u2), math.sqrt(1 - u1) * math.cos(2 * math.pi * u2),
         math.sqrt(u1) * math.sin(2 * math.pi * u3), math.sqrt(u1) * math.cos(2 * math.pi * u3))
    return quat_to_matrix(q)


def axis_angle(axis: tuple[float, float, float], degrees: float) -> list[list[float]]:
    n = math.sqrt(sum(a * a for a in axis))
    h = math.radians(degrees) / 2
    s = math.sin(h) / n
    return quat_to_matrix((axis[0] * s, axis[1] * s, axis[2] * s, math.cos(h)))


def quat_to_matrix(q) -> list[list[float]]:
    x, y, z, w = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def colmajor(r: list[list[float]], t: tuple[float, float, float]) -> list[float]:
    return [r[0][0], r[1][0], r[2][0], 0, r[0][1], r[1][1], r[2][1], 0, r[0][2], r[1][2], r[2][2], 0,
            t[0], t[1], t[2], 1]


# ---------------------------------------------------------------- cases
class Operand:
    def __init__(self, path: str, matrix: list[float], normalize: bool, subdivide: int = 0):
        self.path, self.matrix, self.normalize, self.subdivide = path, matrix, normalize, subdivide

    def label(self) -> str:
        return self.path + (f" (midpoint x{self.subdivide})" if self.subdivide else "")


class Case:
    def __init__(self, cid: str, group: str, a: Operand, b: Operand, ops: list[str]):
        self.cid, self.group, self.a, self.b, self.ops = cid, group, a, b, ops


def read_manifest(data: Path) -> dict[str, int]:
    tris = {}
    with open(data / "MANIFEST.tsv", newline="") as f:
        for row in csv.DictReader(f, delimiter="\t"):
            try:
                tris[row["path"]] = int(row["triangles"])
            except (KeyError, ValueError):
                pass
    return tris


def build_cases(args, data: Path) -> list[Case]:
    rng = random.Random(args.seed)
    pool = [l.strip() for l in open(data / "clean_pool_1k_100k.txt") if l.strip()]
    tris = read_manifest(data)
    cases: list[Case] = []

    # (a) random overlapping pairs from the clean pool (paper Section 5.1)
    for i in range(args.pairs):
        pa, pb = rng.sample(pool, 2)
        ops = []
        for p in (pa, pb):
            t = tuple(rng.uniform(-args.offset, args.offset) for _ in range(3))
            ops.append(Operand(p, colmajor(random_rotation(rng), t), normalize=True))
        cases.append(Case(f"pair{i:03d}", "pairs", ops[0], ops[1], OPS))

    # (b) the paper's own cases whose meshes are local (transforms as published)
    tsv = data / "peer-tests/manifold/ember/cases_with_local_meshes.tsv"
    with open(tsv, newline="") as f:
        rows = list(csv.DictReader(f, delimiter="\t"))
    if args.paper_cases is not None:
        rows = rows[: args.paper_cases]
    for row in rows:
        ma = [float(v) for v in row["transform_a_colmajor_4x4"].split(",")]
        mb = [float(v) for v in row["transform_b_colmajor_4x4"].split(",")]
        cases.append(Case(f"paper{int(row['case_index']):03d}", "paper", Operand(row["path_a"], ma, False),
                          Operand(row["path_b"], mb, False), OPS))

    # (c) scaling series: a mesh against itself rotated by a small angle
    series = []
    for target in args.scaling_sizes:
        # pool meshes for the small end; a midpoint-subdivided pool mesh or a large mesh above 100k
        if target <= 100_000:
            cand = min(pool, key=lambda p: (abs(tris.get(p, 0) - target), p))
            series.append((cand, 0))
        elif target >= 500_000:
            large = sorted(((tris.get(p, 0), p) for p in tris if p.startswith("large/")), key=lambda x: abs(x[0] - target))
            if large:
                series.append((large[0][1], 0))
        else:
            cand = min(pool, key=lambda p: (abs(4 * tris.get(p, 0) - target), p))
            series.append((cand, 1))
    seen = set()
    rot = axis_angle((1.0, 2.0, 3.0), args.scaling_angle)
    ident = colmajor([[1, 0, 0], [0, 1, 0], [0, 0, 1]], (0, 0, 0))
    for path, sub in series:
        if (path, sub) in seen:
            continue
        seen.add((path, sub))
        n = tris.get(path, 0) * (4 ** sub)
        cases.append(Case(f"scale{n // 1000:04d}k", "scaling", Operand(path, ident, True, sub),
                          Operand(path, colmajor(rot, (0, 0, 0)), True, sub), args.scaling_ops))
    return cases


# ---------------------------------------------------------------- processes
def run_process(cmd: list[str], timeout: float, cwd: Path | None = None) -> tuple[str, str, int | None, float, str]:
    """Runs cmd; returns (stdout, stderr, returncode or None on timeout, child peak RSS MiB, status text)."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        p = subprocess.Popen(cmd, stdout=out, stderr=err, cwd=cwd)
        deadline = time.monotonic() + timeout
        status, ru, rc = "", None, None
        while True:
            pid, st, ru = os.wait4(p.pid, os.WNOHANG)
            if pid == p.pid:
                if os.WIFSIGNALED(st):
                    status = f"crashed ({signal.Signals(os.WTERMSIG(st)).name})"
                    rc = -os.WTERMSIG(st)
                else:
                    rc = os.WEXITSTATUS(st)
                    status = "" if rc == 0 else f"exit code {rc}"
                break
            if time.monotonic() > deadline:
                p.kill()
                _, st, ru = os.wait4(p.pid, 0)
                status, rc = f"timeout after {timeout:g} s", None
                break
            time.sleep(0.01)
        p.returncode = rc if rc is not None else -9
        out.seek(0)
        err.seek(0)
        rss = ru.ru_maxrss / 1024.0 if ru else float("nan")
        return out.read().decode(errors="replace"), err.read().decode(errors="replace"), rc, rss, status


def run_tool(base_cmd: list[str], ops: list[str], args, cwd: Path | None = None) -> dict[str, dict]:
    """Runs one tool for all ops; relaunches after a crash for the remaining ops."""
    results: dict[str, dict] = {}
    remaining = list(ops)
    while remaining:
        cmd = base_cmd + ["--ops", ",".join(remaining), "--runs", str(args.runs), "--budget-ms", str(args.budget_ms),
                          "--warmup", str(args.warmup)]
        out, err, rc, rss, status = run_process(cmd, args.timeout, cwd)
        got = []
        for line in out.splitlines():
            line = line.strip()
            if not line.startswith("{"):
                continue
            try:
                r = json.loads(line)
            except json.JSONDecodeError:
                continue
            if r.get("op") in remaining:
                r["rss_mib"] = rss
                results[r["op"]] = r
                got.append(r["op"])
        remaining = [o for o in remaining if o not in got]
        if remaining:
            # the first missing op is the one that died; record it and go on with the rest
            why = status or "no result"
            tail = err.strip().splitlines()[-1:] if err.strip() else []
            if tail:
                why += ": " + tail[0][:200]
            results[remaining[0]] = {"ok": False, "error": why, "rss_mib": rss, "runs": 0}
            remaining = remaining[1:]
    return results


# ---------------------------------------------------------------- output
def rel_diff(a, b):
    if a is None or b is None:
        return None
    d = abs(a - b)
    m = max(abs(a), abs(b))
    if m < 1e-15:
        return 0.0
    return d / m


def machine_info() -> dict[str, str]:
    info = {"cpu": platform.processor() or "unknown", "cores": str(os.cpu_count())}
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        for line in out.splitlines():
            k, _, v = line.partition(":")
            if k.strip() == "Model name":
                info["cpu"] = v.strip()
            if k.strip() == "CPU(s)":
                info["cores"] = v.strip()
    except OSError:
        pass
    info["date"] = datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")
    info["kernel"] = platform.release()
    try:
        info["ember_rev"] = subprocess.run(["git", "-C", str(REPO), "rev-parse", "--short", "HEAD"],
                                           capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(REPO), "status", "--porcelain", "--", "src", "include"],
                               capture_output=True, text=True).stdout.strip()
        if dirty:
            info["ember_rev"] += " (+ uncommitted changes in src/include)"
    except OSError:
        info["ember_rev"] = "unknown"
    try:
        info["cgal"] = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "libcgal-dev"],
                                      capture_output=True, text=True).stdout.strip()
    except OSError:
        info["cgal"] = "unknown"
    try:
        pj = json.load(open(REPO / "bench/peers/node_modules/manifold-3d/package.json"))
        info["manifold"] = pj.get("version", "unknown")
    except OSError:
        info["manifold"] = "unknown"
    try:
        info["node"] = subprocess.run(["node", "--version"], capture_output=True, text=True).stdout.strip()
    except OSError:
        info["node"] = "unknown"
    return info


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", default=str(REPO.parent / "shared/data"))
    ap.add_argument("--bin", default=str(REPO / "build-bench/bin"))
    ap.add_argument("--out", default=str(REPO / "bench-results"))
    ap.add_argument("--quick", action="store_true", help="a few small cases, for a smoke run (~3 min)")
    ap.add_argument("--threads", default=None, help="ember thread counts, comma separated (default 1,<nproc>)")
    ap.add_argument("--runs", type=int, default=5, help="timed runs per case/tool/op; the median is reported")
    ap.add_argument("--budget-ms", type=float, default=None,
                    help="stop repeating a case/tool/op once this much time was spent (at least one run)")
    ap.add_argument("--warmup", type=int, default=1,
                    help="untimed runs before the timed ones, for every tool alike (the first is reported as the "
                         "cold time)")
    ap.add_argument("--timeout", type=float, default=None, help="seconds per runner process")
    ap.add_argument("--docs", default=None, help="also write summary.md to this file (bench.sh: "
                                                 "docs/benchmark-results.md on full runs)")
    ap.add_argument("--instructions-mesh", default="peer-tests/InteractiveAndRobustMeshBooleans/bunny25k.obj",
                    help="mesh (under --data) of the callgrind count: it united with its copy rotated by "
                         "--scaling-angle; '' skips the count")
    ap.add_argument("--pairs", type=int, default=None, help="number of random pool pairs (default 40, quick 3)")
    ap.add_argument("--seed", type=int, default=20220704)
    ap.add_argument("--offset", type=float, default=0.15,
                    help="translations are uniform in [-offset, offset]^3 for unit-size meshes")
    ap.add_argument("--scaling-angle", type=float, default=1.0, help="degrees of the self-rotation")
    ap.add_argument("--scaling-ops", default="union", help="ops of the scaling series (comma separated)")
    ap.add_argument("--tools", default="ember,cgal,manifold")
    ap.add_argument("--ember-modes", default="general,solid,nocheck",
                    help="ember runs: 'general' (defaults: no input assumptions, inputs proven solid when they "
                         "are), 'solid' (--assume-solid: inputs promised closed, outward, free of "
                         "self-intersections, as CGAL and Manifold also require, no proof) and/or 'nocheck' "
                         "(--no-solid-check: the general path for every input)")
    ap.add_argument("--replot", action="store_true",
                    help="only redraw OUT/time_vs_size.png from OUT/results.csv (e.g. after an interrupted run)")
    ap.add_argument("--keep-meshes", action="store_true", help="keep the prepared binary meshes in OUT/meshes")
    args = ap.parse_args()

    if args.replot:
        return replot(Path(args.out).resolve())
    nproc = os.cpu_count() or 1
    if args.threads is None:
        args.threads = sorted({1, nproc})
    else:
        args.threads = [int(t) for t in args.threads.split(",") if t.strip()]
    args.scaling_ops = [o for o in args.scaling_ops.split(",") if o]
    if args.quick:
        args.pairs = 3 if args.pairs is None else args.pairs
        args.paper_cases = 1
        args.scaling_sizes = [5_000, 25_000]
        args.budget_ms = 1000.0 if args.budget_ms is None else args.budget_ms
        args.timeout = 120.0 if args.timeout is None else args.timeout
    else:
        args.pairs = 40 if args.pairs is None else args.pairs
        args.paper_cases = None
        args.scaling_sizes = [5_000, 12_000, 25_000, 50_000, 100_000, 150_000, 300_000, 540_000, 600_000]
        args.budget_ms = 2000.0 if args.budget_ms is None else args.budget_ms
        args.timeout = 300.0 if args.timeout is None else args.timeout
    tools = [t for t in args.tools.split(",") if t]

    data = Path(args.data).resolve()
    bindir = Path(args.bin).resolve()
    outdir = Path(args.out).resolve()
    outdir.mkdir(parents=True, exist_ok=True)
    ember_bench = bindir / "ember_bench"
    cgal_runner = bindir / "cgal_runner"
    manifold_runner = REPO / "bench/peers/manifold_runner.mjs"
    for exe in [ember_bench] + ([cgal_runner] if "cgal" in tools else []):
        if not exe.exists():
            log(f"missing {exe}; build with -DEMBER_BUILD_PEERS=ON (scripts/bench.sh does)")
            return 2
    if "manifold" in tools and not (REPO / "bench/peers/node_modules/manifold-3d").exists():
        log("missing bench/peers/node_modules/manifold-3d (npm install in bench/peers; scripts/bench.sh does)")
        return 2

    cases = build_cases(args, data)
    log(f"{len(cases)} cases, ember threads {args.threads}, runs {args.runs}, budget {args.budget_ms:.0f} ms, "
        f"tools {tools}, output {outdir}")
    meshdir = outdir / "meshes" if args.keep_meshes else Path(tempfile.mkdtemp(prefix="ember-bench-"))
    meshdir.mkdir(parents=True, exist_ok=True)

    rows = []
    modes = [m for m in args.ember_modes.split(",") if m]
    ember_cols = [f"ember_t{t}" for t in args.threads if "general" in modes] + \
                 [f"ember_solid_t{t}" for t in args.threads if "solid" in modes] + \
                 [f"ember_nocheck_t{t}" for t in args.threads if "nocheck" in modes]
    tool_names = [t for t in ember_cols if "ember" in tools] + [t for t in ("cgal", "manifold") if t in tools]
    info = machine_info()
    timed_out: dict[str, str] = {}
    for ci, case in enumerate(cases):
        fa, fb = meshdir / f"{case.cid}_a.bin", meshdir / f"{case.cid}_b.bin"
        prep_err = ""
        ntri = []
        for op_, f in ((case.a, fa), (case.b, fb)):
            cmd = [str(ember_bench), "prepare", str(data / op_.path), str(f),
                   "--matrix", ",".join(repr(float(v)) for v in op_.matrix)]
            if op_.normalize:
                cmd.append("--normalize")
            if op_.subdivide:
                cmd += ["--subdivide", str(op_.subdivide)]
            out, err, rc, _, status = run_process(cmd, 300)
            if rc != 0:
                prep_err = f"prepare {op_.path}: {status} {err.strip()[-200:]}"
                break
            ntri.append(json.loads(out.strip().splitlines()[-1])["triangles"])
        if prep_err:
            log(f"[{ci + 1}/{len(cases)}] {case.cid}: {prep_err}")
            for op in case.ops:
                rows.append({"case": case.cid, "group": case.group, "mesh_a": case.a.label(),
                             "mesh_b": case.b.label(), "op": op, "prepare_error": prep_err})
            continue
        in_tris = sum(ntri)
        log(f"[{ci + 1}/{len(cases)}] {case.cid} ({case.group}) {case.a.label()} x {case.b.label()}: "
            f"{in_tris} triangles")
        res: dict[str, dict[str, dict]] = {}
        commands = {}
        if "ember" in tools:
            for t in args.threads:
                if "general" in modes:
                    commands[f"ember_t{t}"] = ([str(ember_bench), "run", str(fa), str(fb), "--threads", str(t)], None)
                if "solid" in modes:
                    commands[f"ember_solid_t{t}"] = ([str(ember_bench), "run", str(fa), str(fb), "--threads", str(t),
                                                      "--solid"], None)
                if "nocheck" in modes:
                    commands[f"ember_nocheck_t{t}"] = ([str(ember_bench), "run", str(fa), str(fb), "--threads",
                                                        str(t), "--no-detect"], None)
        if "cgal" in tools:
            commands["cgal"] = ([str(cgal_runner), str(fa), str(fb)], None)
        if "manifold" in tools:
            commands["manifold"] = (["node", str(manifold_runner), str(fa), str(fb)], REPO / "bench/peers")
        for name, (cmd, cwd) in commands.items():
            if case.group == "scaling" and name in timed_out:
                # the series grows monotonically: a tool that timed out once is not run on larger steps
                res[name] = {op: {"ok": False, "error": f"skipped: timed out on {timed_out[name]}", "runs": 0}
                             for op in case.ops}
                continue
            res[name] = run_tool(cmd, case.ops, args, cwd=cwd)
            if case.group == "scaling" and any(str(r.get("error", "")).startswith("timeout") for r in res[name].values()):
                timed_out[name] = case.cid
        if not args.keep_meshes:
            fa.unlink(missing_ok=True)
            fb.unlink(missing_ok=True)
        for op in case.ops:
            row = {"case": case.cid, "group": case.group, "mesh_a": case.a.label(), "mesh_b": case.b.label(),
                   "op": op, "in_triangles": in_tris, "prepare_error": ""}
            for tool, r in res.items():
                o = r.get(op, {})
                ok = bool(o.get("ok"))
                row[f"{tool}_ms"] = o.get("median_ms") if ok else None
                row[f"{tool}_runs"] = o.get("runs", 0) if ok else 0
                row[f"{tool}_out_polygons"] = o.get("out_polygons") if ok else None
                row[f"{tool}_volume"] = o.get("out_volume") if ok else None
                row[f"{tool}_rss_mib"] = o.get("rss_mib")
                row[f"{tool}_mtris_per_s"] = (in_tris / o["median_ms"] / 1e3) if ok and o.get("median_ms") else None
                row[f"{tool}_error"] = o.get("error", "") if not ok else ""
                row[f"{tool}_cold_ms"] = o.get("cold_ms") if ok else None
                for ph in profile_tables.PHASES:
                    row[f"{tool}_{ph}_ms"] = o.get(f"{ph}_ms") if ok else None
            ref = ember_cols[0] if ember_cols[0] in res else None
            for e in ember_cols:
                for peer in ("cgal", "manifold"):
                    if e in res and peer in res:
                        a, b = row.get(f"{e}_ms"), row.get(f"{peer}_ms")
                        row[f"ratio_{e}_vs_{peer}"] = (a / b) if a and b else None
            for peer in ("cgal", "manifold"):
                if ref and peer in res:
                    d = rel_diff(row.get(f"{ref}_volume"), row.get(f"{peer}_volume"))
                    row[f"voldiff_vs_{peer}"] = d
            flags = [p for p in ("cgal", "manifold") if (row.get(f"voldiff_vs_{p}") or 0) > 1e-6]
            row["volume_flag"] = ",".join(flags)
            rows.append(row)
            parts = []
            for tool in res:
                v = row.get(f"{tool}_ms")
                parts.append(f"{tool} {fmt(v)} ms" if v is not None else f"{tool} FAILED ({row[f'{tool}_error'][:60]})")
            log(f"    {op:12s} " + ", ".join(parts) + (f"  [volume differs: {row['volume_flag']}]" if flags else ""))
        # keep the files current, so an interrupted run still leaves its results
        write_csv(outdir / "results.csv", rows, tool_names)
        write_summary(outdir / "summary.md", rows, tool_names, args, info, f"{ci + 1} of {len(cases)}")
    if not args.keep_meshes:
        shutil.rmtree(meshdir, ignore_errors=True)
    args.instructions = None
    if args.instructions_mesh and "ember" in tools:
        log(f"callgrind: {args.instructions_mesh} union, 1 thread")
        rot = axis_angle((1.0, 2.0, 3.0), args.scaling_angle)
        args.instructions = profile_tables.count_instructions(ember_bench, data, args.instructions_mesh,
                                                              colmajor(rot, (0, 0, 0)), log)
        if args.instructions:
            log(f"    {args.instructions['per_triangle']:.0f} instructions per input triangle")

    write_csv(outdir / "results.csv", rows, tool_names)
    write_plot(outdir / "time_vs_size.png", rows, tool_names)
    write_summary(outdir / "summary.md", rows, tool_names, args, info, str(len(cases)))
    print((outdir / "summary.md").read_text())
    if args.docs:
        plot = Path(args.docs).with_name("benchmark-time-vs-size.png")
        Path(args.docs).write_text((outdir / "summary.md").read_text().replace(
            "Per-case numbers: results.csv; plot: time_vs_size.png.",
            f"Per-case numbers: results.csv of the run ({outdir}); plot: {plot.name}."))
        if (outdir / "time_vs_size.png").exists():
            shutil.copyfile(outdir / "time_vs_size.png", plot)
        log(f"wrote {args.docs} and {plot}")
    log(f"done: {outdir / 'results.csv'}, {outdir / 'summary.md'}, {outdir / 'time_vs_size.png'}")
    return 0


def replot(outdir: Path) -> int:
    with open(outdir / "results.csv", newline="") as f:
        reader = csv.DictReader(f)
        tools = [c[:-3] for c in reader.fieldnames if c.endswith("_ms")]
        rows = []
        for r in reader:
            row = dict(r)
            row["in_triangles"] = int(r["in_triangles"]) if r.get("in_triangles") else None
            for t in tools:
                row[f"{t}_ms"] = float(r[f"{t}_ms"]) if r.get(f"{t}_ms") else None
            rows.append(row)
    write_plot(outdir / "time_vs_size.png", rows, tools)
    log(f"wrote {outdir / 'time_vs_size.png'}")
    return 0


def write_csv(path: Path, rows: list[dict], tools: list[str]) -> None:
    cols = ["case", "group", "mesh_a", "mesh_b", "op", "in_triangles"]
    for t in tools:
        cols += [f"{t}_ms", f"{t}_runs", f"{t}_mtris_per_s", f"{t}_rss_mib", f"{t}_out_polygons", f"{t}_cold_ms"]
        if t.startswith("ember"):
            cols += [f"{t}_{ph}_ms" for ph in profile_tables.PHASES]
    cols += [c for c in (rows[0].keys() if rows else []) if c.startswith("ratio_")]
    for r in rows:
        for c in r:
            if c.startswith("ratio_") and c not in cols:
                cols.append(c)
    for t in tools:
        cols.append(f"{t}_volume")
    cols += ["voldiff_vs_cgal", "voldiff_vs_manifold", "volume_flag"]
    cols += [f"{t}_error" for t in tools] + ["prepare_error"]
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({c: ("" if r.get(c) is None else (f"{r[c]:.6g}" if isinstance(r.get(c), float) else r[c]))
                        for c in cols})


def write_plot(path: Path, rows: list[dict], tools: list[str]) -> None:
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        log("matplotlib missing: no plot")
        return
    fig, ax = plt.subplots(figsize=(8, 5.5))
    markers = {"pairs": "o", "paper": "s", "scaling": "^"}
    # ember runs in blues/purples, peers in warm colours; one colour per tool.
    ember_colors = ["tab:blue", "tab:cyan", "tab:purple", "tab:pink", "tab:gray", "tab:olive"]
    peer_colors = {"cgal": "tab:orange", "manifold": "tab:green"}
    for i, t in enumerate(tools):
        color = ember_colors[i % len(ember_colors)] if t.startswith("ember") else peer_colors.get(t, "tab:red")
        if t == "cgal":
            color = "tab:orange"
        if t == "manifold":
            color = "tab:green"
        for g, m in markers.items():
            pts = [(r["in_triangles"], r[f"{t}_ms"]) for r in rows
                   if r.get("group") == g and r.get(f"{t}_ms") and r.get("in_triangles")]
            if pts:
                ax.scatter([p[0] for p in pts], [p[1] for p in pts], marker=m, s=18, alpha=0.7, color=color,
                           label=f"{t} ({g})")
        sc = sorted((r["in_triangles"], r[f"{t}_ms"]) for r in rows
                    if r.get("group") == "scaling" and r.get(f"{t}_ms"))
        if sc:
            ax.plot([p[0] for p in sc], [p[1] for p in sc], color=color, linewidth=1)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("input triangles (both operands)")
    ax.set_ylabel("time per Boolean [ms] (median)")
    ax.set_title("ember vs CGAL corefinement (Epick) vs Manifold (WASM)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def write_summary(path: Path, rows: list[dict], tools: list[str], args, info: dict, ncases: str) -> None:
    L = []
    L.append("# ember comparison benchmark\n")
    L.append(f"- date: {info['date']}")
    L.append(f"- machine: {info['cpu']}, {info['cores']} logical CPUs, Linux {info['kernel']}")
    L.append(f"- ember: {info.get('ember_rev', '?')}, threads {args.threads}; CGAL {info['cgal']} (Epick, "
             f"Surface_mesh, corefinement, 1 thread); manifold-3d {info['manifold']} (WASM, node {info['node']}, 1 thread)")
    L.append(f"- cases: {ncases} ({'quick' if args.quick else 'full'} run); seed {args.seed}; "
             f"{args.warmup} untimed warm-up run(s), then the median of up to {args.runs} runs, fewer once "
             f"{args.budget_ms:.0f} ms were spent on one case/tool/op (same for every tool)")
    L.append("- timed region: flat arrays in -> Boolean -> flat arrays out, in each tool's own process; file "
             "I/O excluded. **CGAL's time includes building both Surface_mesh from the arrays and copying the "
             "result back**; Manifold's includes building Mesh/Manifold objects and getMesh(); ember's includes "
             "building ember::Mesh from the arrays.")
    L.append("- ember_t*: defaults, no assumptions about the inputs (any PWN mesh); each closed input is proven "
             "solid or not exactly (the proof's time is included) and solid ones take the early-outs of the "
             "paper's Fig. 11. ember_solid_t*: `--assume-solid` (inputs promised closed, outward, free of "
             "self-intersections: what CGAL and Manifold require; no proof). ember_nocheck_t*: "
             "`--no-solid-check` (the general path for every input).")
    L.append("- peak RSS: ru_maxrss of each runner process (one process per case and tool, all ops); node's "
             "includes the V8/WASM runtime (~50 MiB).\n")

    main_rows = [r for r in rows if r.get("group") in ("pairs", "paper")]
    L.append("## Geometric mean time per Boolean (pool pairs + paper cases)\n")
    L.append("| tool | " + " | ".join(OPS) + " | all ops | ok / failed |")
    L.append("|---|" + "---|" * (len(OPS) + 2))
    for t in tools:
        cells = []
        for op in OPS:
            cells.append(fmt(gmean([r.get(f"{t}_ms") for r in main_rows if r["op"] == op])) + " ms")
        ok = sum(1 for r in main_rows if r.get(f"{t}_ms") is not None)
        fail = sum(1 for r in main_rows if r.get(f"{t}_ms") is None)
        L.append(f"| {t} | " + " | ".join(cells) + f" | {fmt(gmean([r.get(f'{t}_ms') for r in main_rows]))} ms | "
                 f"{ok} / {fail} |")
    L.append("")
    L.append("Means over each tool's successful cases; the ratios below use only cases where both succeeded.\n")
    L.append("## Geometric-mean ratio ember / peer (< 1: ember faster)\n")
    peers = [p for p in ("cgal", "manifold") if p in tools]
    embers = [t for t in tools if t.startswith("ember")]
    L.append("| ember | peer | group | " + " | ".join(OPS) + " | all ops | cases |")
    L.append("|---|---|---|" + "---|" * (len(OPS) + 2))
    for e in embers:
        for p in peers:
            for gname, grows in (("pairs+paper", main_rows), ("scaling", [r for r in rows if r.get("group") == "scaling"])):
                cells = [fmt(gmean([r.get(f"ratio_{e}_vs_{p}") for r in grows if r["op"] == op])) for op in OPS]
                allr = [r.get(f"ratio_{e}_vs_{p}") for r in grows if r.get(f"ratio_{e}_vs_{p}")]
                L.append(f"| {e} | {p} | {gname} | " + " | ".join(cells) + f" | {fmt(gmean(allr))} | {len(allr)} |")
    L.append("")
    L.append("## Throughput (input triangles per second, millions)\n")
    tp_all = main_rows
    L.append("| tool | pairs+paper (total tris / total time) | 5 largest cases of all groups (gmean) |")
    L.append("|---|---|---|")
    largest = sorted({(r["in_triangles"], r["case"]) for r in rows if r.get("in_triangles")}, reverse=True)[:5]
    largest_ids = {c for _, c in largest}
    for t in tools:
        ok = [r for r in tp_all if r.get(f"{t}_ms")]
        tot = sum(r["in_triangles"] for r in ok) / (sum(r[f"{t}_ms"] for r in ok) / 1e3) / 1e6 if ok else None
        big = gmean([r.get(f"{t}_mtris_per_s") for r in rows if r["case"] in largest_ids])
        L.append(f"| {t} | {fmt(tot)} | {fmt(big)} |")
    L.append(f"\nLargest cases: {', '.join(f'{c} ({n} tris)' for n, c in largest)}\n")

    sc = [r for r in rows if r.get("group") == "scaling"]
    if sc:
        L.append("## Scaling series (mesh vs itself rotated by "
                 f"{args.scaling_angle}°, ops {','.join(args.scaling_ops)})\n")
        L.append("| case | mesh | op | input tris | " + " | ".join(f"{t} ms" for t in tools) + " | " +
                 " | ".join(f"{t} RSS MiB" for t in tools) + " |")
        L.append("|---|---|---|---|" + "---|" * (2 * len(tools)))
        for r in sc:
            L.append(f"| {r['case']} | {r['mesh_a']} | {r['op']} | {r.get('in_triangles', '')} | " +
                     " | ".join(fmt(r.get(f"{t}_ms")) for t in tools) + " | " +
                     " | ".join(fmt(r.get(f"{t}_rss_mib")) for t in tools) + " |")
        L.append("")

    L += profile_tables.phase_section(rows, tools)
    L += profile_tables.scaling_section(rows, tools, args.threads)
    L += profile_tables.cold_section(rows, tools)
    L += profile_tables.memory_section(rows, tools)
    L += profile_tables.instructions_section(getattr(args, "instructions", None))
    L += profile_tables.per_case_section(rows, tools)

    fails = [(r, t) for r in rows for t in tools if r.get(f"{t}_error") or r.get("prepare_error")]
    L.append(f"## Failures ({len(fails)})\n")
    if fails:
        L.append("| case | op | tool | error |")
        L.append("|---|---|---|---|")
        for r, t in fails:
            L.append(f"| {r['case']} | {r['op']} | {t} | {(r.get(f'{t}_error') or r.get('prepare_error'))[:160]} |")
    else:
        L.append("none")
    L.append("")
    flagged = [r for r in rows if r.get("volume_flag")]
    L.append("## Volume check (relative difference of signed output volume, ember vs peer)\n")
    for p in peers:
        ds = [r.get(f"voldiff_vs_{p}") for r in rows if r.get(f"voldiff_vs_{p}") is not None]
        if ds:
            ds.sort()
            L.append(f"- vs {p}: {len(ds)} compared, median {fmt(ds[len(ds) // 2])}, max {fmt(ds[-1])}, "
                     f"> 1e-6: {sum(1 for d in ds if d > 1e-6)}")
    if flagged:
        L.append("\n| case | op | mesh a | mesh b | vs cgal | vs manifold |")
        L.append("|---|---|---|---|---|---|")
        for r in flagged:
            L.append(f"| {r['case']} | {r['op']} | {r['mesh_a']} | {r['mesh_b']} | {fmt(r.get('voldiff_vs_cgal'))} | "
                     f"{fmt(r.get('voldiff_vs_manifold'))} |")
    L.append("\nPer-case numbers: results.csv; plot: time_vs_size.png.")
    path.write_text("\n".join(L) + "\n")


if __name__ == "__main__":
    sys.exit(main())
