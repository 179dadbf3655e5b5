#!/usr/bin/python3
"""Measures ember's watertight triangle output (the CLI's default output mode).

What it measures
----------------
A. Benchmark cases: the first N random clean-pool pairs of the comparison benchmark
   (bench/compare/bench.py's build_cases with its default seed, offset and seeded random
   rotations) plus the EMBER paper's cases whose meshes are local
   (peer-tests/manifold/ember/cases_with_local_meshes.tsv), x union / intersection /
   difference. Per case and op:
     - `ember OP a.obj b.obj -o out.obj --stats --threads T` (default, watertight triangles):
       on the written OBJ, welded by vertex index as written (the logic of
       tools/check_mesh.py): triangles, unbalanced undirected edges (directed uses a->b and
       b->a differ: open, T-junction or orientation error), non-manifold edges (balanced but
       used more than once each way), repeated positions; from --stats: fallback_regions,
       rounded_degenerate, time_ms, setup/proof/solve/output ms and the mesh stage's share
       output_ms / time_ms; wall time of the process (includes OBJ read/write);
     - `ember ... --polygons` (the old output: the exact core's convex pieces, T-junctions):
       output_polygons from --stats;
     - Manifold (manifold-3d WASM, bench/peers/manifold_runner.mjs, 1 run): output triangles,
       and the ratio ember triangles / Manifold triangles.
   Operands are prepared exactly like `ember_bench prepare` (read with ember's own reader via
   the Python module, fan-triangulated, optionally normalized to bbox center 0 / largest
   extent 1, the case's column-major matrix applied, every coordinate rounded to float32), then
   written once as OBJ (for the ember CLI; the float32 values are printed exactly) and in the
   benchmark's EMB1 binary format (for manifold_runner.mjs), so both tools get identical input.
B. Degenerate inputs: union of the *_left/_right (and other) pairs of peer-tests/manifold and of
   thingi10k/dirty meshes paired with a box (60% of the mesh's bbox, at its upper corner) or
   with themselves rotated 10 degrees about their bbox center; default options, plus
   --allow-open when an input is open (unbalanced edges after ember's reader). Records exit
   code, error, closedness of the output (meaningful when all inputs were closed),
   fallback_regions, time.
C. Optionally renders three results (a pair union, a paper case, a pair difference) to PNG
   with tools/render_obj.py.

Outputs (in --out, default /tmp/wt-measure): results.csv (part A), degenerate.csv (part B),
summary.md, meshes/ (inputs and outputs; outputs kept for rendering), render_*.png.
A case/op whose ember run exceeds --timeout seconds (default 60) is recorded as skipped.

How to run (from the repository root; needs build/bin/ember, build/python (the ember Python
module, built for Debian's /usr/bin/python3 with numpy) and `npm install` in bench/peers):

    cd bench/peers && npm install --no-audit --no-fund && cd ../..
    /usr/bin/python3 bench/watertight/measure.py --out /tmp/wt-measure --pairs 20 --threads 2 --render

Also per case/op: triangle shape of ember's output and of Manifold's (written by
bench/watertight/manifold_dump.mjs): count of triangles with longest edge^2 / area > 1000 and the
worst value (an equilateral triangle has 2.31).

Options: --only-degenerate, --skip-degenerate, --skip-manifold, --cases pair000,paper016 (filter).
"""
from __future__ import annotations

import argparse
import csv
import importlib.util
import json
import math
import statistics
import struct
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
OPS = ["union", "intersection", "difference"]


def load_module(name: str, path: Path):
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


bench = load_module("ember_compare_bench", REPO / "bench/compare/bench.py")
check_mesh = load_module("ember_check_mesh", REPO / "tools/check_mesh.py")

T0 = time.monotonic()


def log(msg: str) -> None:
    el = time.monotonic() - T0
    print(f"[wt {int(el) // 60:02d}:{int(el) % 60:02d}] {msg}", file=sys.stderr, flush=True)


# ---------------------------------------------------------------- operands
def prepare(ember, np, path: Path, matrix, normalize: bool):
    """Like `ember_bench prepare`: ember's reader (fan-triangulated), normalize, matrix, float32."""
    v, f = ember.read(str(path))
    v = np.asarray(v, dtype=np.float64)
    f = np.asarray(f, dtype=np.int64)
    if normalize and len(v):
        lo, hi = v.min(axis=0), v.max(axis=0)
        ext = float((hi - lo).max())
        s = 1.0 / ext if ext > 0 else 1.0
        v = (v - 0.5 * (lo + hi)) * s
    M = [float(m) for m in matrix]
    x, y, z = v[:, 0], v[:, 1], v[:, 2]
    out = np.empty_like(v)
    for r in range(3):
        out[:, r] = ((M[r] * x + M[4 + r] * y) + M[8 + r] * z) + M[12 + r]
    return out.astype(np.float32).astype(np.float64), f


def write_obj(path: Path, v, f) -> None:
    with open(path, "w") as o:
        o.write("".join(f"v {a!r} {b!r} {c!r}\n" for a, b, c in v.tolist()))
        o.write("".join("f " + " ".join(str(i + 1) for i in face) + "\n" for face in f.tolist()))


def write_bin(path: Path, v, f, np) -> None:
    with open(path, "wb") as o:
        o.write(b"EMB1" + struct.pack("<QQ", len(v), len(f)))
        o.write(np.ascontiguousarray(v, dtype="<f8").tobytes())
        o.write(np.ascontiguousarray(f, dtype="<u4").tobytes())


# ---------------------------------------------------------------- topology
def topology(faces) -> dict:
    """tools/check_mesh.py's report, returned as numbers (weld by vertex index as written)."""
    edges, unbalanced, nonmanifold = check_mesh.edge_counts(faces)
    return {"faces": len(faces), "triangles": sum(len(fc) - 2 for fc in faces),
            "non_triangles": sum(1 for fc in faces if len(fc) != 3), "edges": edges,
            "unbalanced": unbalanced, "nonmanifold": nonmanifold, "closed": unbalanced == 0}


SLIVER_ASPECT = 1000.0  # longest edge^2 / area; 4/sqrt(3) = 2.31 for an equilateral triangle


def quality(verts, faces, np) -> dict:
    """Triangle shape: how many triangles have longest edge^2 / area > SLIVER_ASPECT, and the worst."""
    tris = [fc for fc in faces if len(fc) == 3]
    if not tris:
        return {"slivers": 0, "max_aspect": None}
    V = np.asarray(verts, dtype=np.float64)
    t = V[np.asarray(tris)]
    area = np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1) / 2
    L2 = np.stack([((t[:, (i + 1) % 3] - t[:, i]) ** 2).sum(axis=1) for i in range(3)], 1).max(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        asp = np.where(area > 0, L2 / area, np.inf)
    return {"slivers": int((asp > SLIVER_ASPECT).sum()), "max_aspect": float(asp.max()),
            "zero_area": int((area == 0).sum())}


def check_obj(path: Path, np=None) -> dict:
    verts, faces = check_mesh.read(str(path))
    t = topology(faces)
    t["vertices"] = len(verts)
    t["repeated_positions"] = len(verts) - len(set(verts))
    if np is not None:
        t.update(quality(verts, faces, np))
    return t


# ---------------------------------------------------------------- runs
def parse_stats(err: str) -> dict:
    for line in reversed(err.strip().splitlines()):
        line = line.strip()
        if line.startswith("{"):
            try:
                return json.loads(line)
            except json.JSONDecodeError:
                pass
    return {}


def run_ember(exe: Path, op: str, inputs: list[Path], out: Path, threads: int, timeout: float,
              extra: list[str] | None = None) -> dict:
    cmd = [str(exe), op] + [str(p) for p in inputs] + ["-o", str(out), "--stats", "--threads", str(threads)]
    cmd += extra or []
    t = time.monotonic()
    sout, serr, rc, rss, status = bench.run_process(cmd, timeout)
    wall = time.monotonic() - t
    st = parse_stats(serr)
    errline = ""
    if rc != 0:
        lines = [l for l in serr.strip().splitlines() if not l.strip().startswith("{")]
        errline = (status + ": " + (lines[-1] if lines else "")).strip()[:300]
    return {"rc": rc, "status": status, "wall_s": wall, "rss_mib": rss, "stats": st, "error": errline,
            "cmd": " ".join(cmd)}


def run_manifold(fa: Path, fb: Path, timeout: float) -> dict[str, dict]:
    runner = REPO / "bench/peers/manifold_runner.mjs"
    ns = argparse.Namespace(runs=1, budget_ms=0.0, timeout=timeout)
    return bench.run_tool(["node", str(runner), str(fa), str(fb)], OPS, ns, cwd=REPO / "bench/peers")


def fnum(x, d=4):
    if x is None or x == "":
        return ""
    if isinstance(x, float):
        return f"{x:.{d}g}"
    return str(x)


# ---------------------------------------------------------------- part A
CSV_COLS = ["case", "group", "mesh_a", "mesh_b", "op", "in_triangles", "ember_rc", "ember_error",
            "ember_triangles", "ember_vertices", "non_triangles", "closed", "unbalanced_edges",
            "nonmanifold_edges", "repeated_positions", "fallback_regions", "rounded_degenerate",
            "tjunctions_resolved", "collinear_removed", "regions", "time_ms", "setup_ms", "proof_ms",
            "solve_ms", "output_ms", "weld_ms", "tjunction_ms", "regions_ms", "triangulate_ms", "output_share",
            "ember_wall_s", "polygons_rc", "ember_polygons",
            "polygons_time_ms", "polygons_output_ms", "manifold_triangles", "manifold_ms", "manifold_error",
            "ratio_ember_vs_manifold", "ratio_polygons_vs_manifold", "ember_slivers", "ember_max_aspect",
            "ember_zero_area", "manifold_slivers", "manifold_max_aspect", "manifold_closed", "ember_obj"]


def part_a(args, ember, np, outdir: Path) -> list[dict]:
    data = Path(args.data)
    bargs = argparse.Namespace(seed=args.seed, pairs=args.pairs, offset=args.offset, paper_cases=None,
                               scaling_sizes=[], scaling_angle=1.0, scaling_ops=["union"])
    cases = [c for c in bench.build_cases(bargs, data) if c.group in ("pairs", "paper")]
    if args.cases:
        keep = set(args.cases.split(","))
        cases = [c for c in cases if c.cid in keep]
    meshdir = outdir / "meshes"
    meshdir.mkdir(parents=True, exist_ok=True)
    rows: list[dict] = []
    csv_path = outdir / "results.csv"
    for ci, case in enumerate(cases):
        files = []
        ntri = 0
        for tag, opnd in (("a", case.a), ("b", case.b)):
            v, f = prepare(ember, np, data / opnd.path, opnd.matrix, opnd.normalize)
            fo, fb = meshdir / f"{case.cid}_{tag}.obj", meshdir / f"{case.cid}_{tag}.bin"
            write_obj(fo, v, f)
            write_bin(fb, v, f, np)
            files.append((fo, fb))
            ntri += len(f)
        log(f"[{ci + 1}/{len(cases)}] {case.cid} ({case.group}) {case.a.path} x {case.b.path}: {ntri} triangles")
        man = {}
        if not args.skip_manifold:
            man = run_manifold(files[0][1], files[1][1], 3 * args.timeout)
        for op in OPS:
            row = {"case": case.cid, "group": case.group, "mesh_a": case.a.path, "mesh_b": case.b.path, "op": op,
                   "in_triangles": ntri}
            out = meshdir / f"{case.cid}_{op}.obj"
            r = run_ember(Path(args.bin), op, [files[0][0], files[1][0]], out, args.threads, args.timeout)
            st = r["stats"]
            row["ember_rc"] = r["rc"] if r["rc"] is not None else "timeout"
            row["ember_error"] = r["error"]
            row["ember_wall_s"] = r["wall_s"]
            for k in ("fallback_regions", "rounded_degenerate", "tjunctions_resolved", "collinear_removed",
                      "regions", "time_ms", "setup_ms", "proof_ms", "solve_ms", "output_ms", "weld_ms",
                      "tjunction_ms", "regions_ms", "triangulate_ms"):
                row[k] = st.get(k)
            if st.get("time_ms") and st.get("output_ms") is not None:
                row["output_share"] = st["output_ms"] / st["time_ms"]
            if r["rc"] == 0 and out.exists():
                t = check_obj(out, np)
                row.update({"ember_slivers": t["slivers"], "ember_max_aspect": t["max_aspect"],
                            "ember_zero_area": t["zero_area"]})
                row.update({"ember_triangles": t["triangles"], "ember_vertices": t["vertices"],
                            "non_triangles": t["non_triangles"], "closed": t["closed"],
                            "unbalanced_edges": t["unbalanced"], "nonmanifold_edges": t["nonmanifold"],
                            "repeated_positions": t["repeated_positions"], "ember_obj": str(out)})
            # the old output (--polygons): only its polygon count is kept
            if not args.skip_polygons and r["rc"] == 0:
                pout = meshdir / f"{case.cid}_{op}_polygons.obj"
                p = run_ember(Path(args.bin), op, [files[0][0], files[1][0]], pout, args.threads, args.timeout,
                              ["--polygons"])
                row["polygons_rc"] = p["rc"] if p["rc"] is not None else "timeout"
                row["ember_polygons"] = p["stats"].get("output_polygons")
                row["polygons_time_ms"] = p["stats"].get("time_ms")
                row["polygons_output_ms"] = p["stats"].get("output_ms")
                pout.unlink(missing_ok=True)
            m = man.get(op, {})
            if m:
                if m.get("ok"):
                    row["manifold_triangles"] = m.get("out_polygons")
                    row["manifold_ms"] = m.get("median_ms")
                else:
                    row["manifold_error"] = m.get("error", "")[:300]
            if m.get("ok") and not args.skip_manifold_quality:
                # Manifold's result mesh itself, for the triangle-shape comparison
                mo = meshdir / f"{case.cid}_{op}_manifold.obj"
                sout, serr, rc, _, status = bench.run_process(
                    ["node", str(REPO / "bench/watertight/manifold_dump.mjs"), str(files[0][1]), str(files[1][1]), op,
                     str(mo)], args.timeout, REPO / "bench/peers")
                if rc == 0 and mo.exists():
                    q = check_obj(mo, np)
                    row.update({"manifold_slivers": q["slivers"], "manifold_max_aspect": q["max_aspect"],
                                "manifold_closed": q["closed"]})
                    mo.unlink(missing_ok=True)
                else:
                    log(f"      manifold_dump failed: {status} {serr.strip()[-200:]}")
            et, mt = row.get("ember_triangles"), row.get("manifold_triangles")
            if et and mt:
                row["ratio_ember_vs_manifold"] = et / mt
            if row.get("ember_polygons") and mt:
                row["ratio_polygons_vs_manifold"] = row["ember_polygons"] / mt
            rows.append(row)
            log(f"    {op:12s} rc={row['ember_rc']} tris={row.get('ember_triangles')} closed={row.get('closed')} "
                f"unbal={row.get('unbalanced_edges')} nm={row.get('nonmanifold_edges')} "
                f"fallback={row.get('fallback_regions')} time={fnum(row.get('time_ms'))} ms "
                f"share={fnum(row.get('output_share'), 3)} polys={row.get('ember_polygons')} "
                f"manifold={row.get('manifold_triangles') or row.get('manifold_error', '')[:60]} "
                f"slivers ember/manifold={row.get('ember_slivers')}/{row.get('manifold_slivers')}")
            if r["rc"] != 0:
                log(f"      ember error: {r['error']}")
            write_rows(csv_path, rows, CSV_COLS)
        # inputs are cheap to regenerate; outputs are kept for rendering
        for fo, fb in files:
            fb.unlink(missing_ok=True)
    return rows


def write_rows(path: Path, rows: list[dict], cols: list[str]) -> None:
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({c: ("" if r.get(c) is None else (f"{r[c]:.6g}" if isinstance(r[c], float) else r[c]))
                        for c in cols})


# ---------------------------------------------------------------- part B
DEGEN_PAIRS = [
    ("peer-tests/manifold/Cray_left.obj", "peer-tests/manifold/Cray_right.obj"),
    ("peer-tests/manifold/Generic_Twin_7081.1.t0_left.obj", "peer-tests/manifold/Generic_Twin_7081.1.t0_right.obj"),
    ("peer-tests/manifold/Generic_Twin_7863.1.t0_left.obj", "peer-tests/manifold/Generic_Twin_7863.1.t0_right.obj"),
    ("peer-tests/manifold/Havocglass8_left.obj", "peer-tests/manifold/Havocglass8_right.obj"),
    ("peer-tests/manifold/self_intersectA.obj", "peer-tests/manifold/self_intersectB.obj"),
    ("peer-tests/manifold/hull-body.obj", "peer-tests/manifold/hull-mask.obj"),
    ("peer-tests/manifold/Offset1.obj", "peer-tests/manifold/Offset2.obj"),
    ("peer-tests/manifold/Offset3.obj", "peer-tests/manifold/Offset4.obj"),
    ("peer-tests/manifold/boxNotManifold.obj", "rot"),
    ("peer-tests/manifold/openscad-nonmanifold-crash.obj", "rot"),
    ("thingi10k/dirty/1004825.stl", "box"),
    ("thingi10k/dirty/375236.stl", "rot"),
    ("thingi10k/dirty/37863.stl", "box"),
    ("thingi10k/dirty/40921.stl", "rot"),
    ("thingi10k/dirty/449816.stl", "box"),
    ("thingi10k/dirty/61457.stl", "rot"),
    ("thingi10k/dirty/100072.stl", "box"),
    ("thingi10k/dirty/138201.stl", "rot"),
    ("thingi10k/dirty/741531.stl", "box"),
    ("thingi10k/dirty/96590.stl", "rot"),
]
DEGEN_COLS = ["case", "mesh_a", "mesh_b", "in_triangles", "inputs_closed", "allow_open", "rc", "error", "closed",
              "unbalanced_edges", "nonmanifold_edges", "triangles", "fallback_regions", "rounded_degenerate",
              "time_ms", "output_ms", "wall_s", "solid_check"]


def part_b(args, ember, np, outdir: Path) -> list[dict]:
    data = Path(args.data)
    d = outdir / "degenerate"
    d.mkdir(parents=True, exist_ok=True)
    rows = []
    rot = bench.axis_angle((1.0, 2.0, 3.0), 10.0)
    for i, (pa, pb) in enumerate(DEGEN_PAIRS):
        v, f = ember.read(str(data / pa))
        v, f = np.asarray(v, dtype=np.float64), np.asarray(f, dtype=np.int64)
        if pb in ("rot", "box"):
            lo, hi = v.min(axis=0), v.max(axis=0)
            c, e = 0.5 * (lo + hi), hi - lo
            if pb == "rot":
                R = np.array(rot)
                vb, fb = (v - c) @ R.T + c, f
                label = "itself rotated 10 deg about bbox center"
            else:
                corners = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=np.float64)
                vb = c + corners * (0.6 * e)  # box [c, c + 0.6 e]: overlaps the upper corner of the bbox
                quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
                fb = np.array([t for a, b, cc, dd in quads for t in ((a, b, cc), (a, cc, dd))], dtype=np.int64)
                label = "box 0.6 x bbox at its upper corner"
            fa_path = data / pa
            fb_path = d / f"deg{i:02d}_b.obj"
            write_obj(fb_path, vb, fb)
            ta, tb = topology(f.tolist()), topology(fb.tolist())
            name_b = label
        else:
            fa_path, fb_path = data / pa, data / pb
            v2, f2 = ember.read(str(data / pb))
            ta, tb = topology(np.asarray(f).tolist()), topology(np.asarray(f2).tolist())
            name_b = pb
        closed_in = ta["closed"] and tb["closed"]
        extra = [] if closed_in else ["--allow-open"]
        out = d / f"deg{i:02d}_union.obj"
        r = run_ember(Path(args.bin), "union", [fa_path, fb_path], out, args.threads, args.timeout, extra)
        st = r["stats"]
        row = {"case": f"deg{i:02d}", "mesh_a": pa, "mesh_b": name_b, "in_triangles": ta["triangles"] + tb["triangles"],
               "inputs_closed": closed_in, "allow_open": not closed_in,
               "rc": r["rc"] if r["rc"] is not None else "timeout", "error": r["error"], "wall_s": r["wall_s"],
               "fallback_regions": st.get("fallback_regions"), "rounded_degenerate": st.get("rounded_degenerate"),
               "time_ms": st.get("time_ms"), "output_ms": st.get("output_ms"),
               "solid_check": st.get("solid_check", "")}
        if r["rc"] == 0 and out.exists():
            t = check_obj(out)
            row.update({"closed": t["closed"], "unbalanced_edges": t["unbalanced"],
                        "nonmanifold_edges": t["nonmanifold"], "triangles": t["triangles"]})
        rows.append(row)
        log(f"degenerate {row['case']} {pa} + {name_b}: inputs_closed={closed_in} rc={row['rc']} "
            f"closed={row.get('closed')} unbal={row.get('unbalanced_edges')} fallback={row.get('fallback_regions')} "
            f"time={fnum(row.get('time_ms'))} ms {row['error'][:120]}")
        write_rows(outdir / "degenerate.csv", rows, DEGEN_COLS)
    return rows


# ---------------------------------------------------------------- summary / render
def summarize(rows: list[dict], drows: list[dict], outdir: Path, args) -> None:
    L = ["# ember watertight triangle output: measurement\n",
         f"- ember: {args.bin}, --threads {args.threads}; pairs: first {args.pairs} of bench.py (seed {args.seed})\n"]
    if rows:
        L.append("| case | op | ember tris | manifold tris | ratio | --polygons | closed | unbalanced | non-manifold "
                 "| fallback | rounded | time ms | output ms | share |")
        L.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            L.append(f"| {r['case']} | {r['op']} | {fnum(r.get('ember_triangles'))} | "
                     f"{fnum(r.get('manifold_triangles')) or ('fail' if r.get('manifold_error') else '')} | "
                     f"{fnum(r.get('ratio_ember_vs_manifold'), 3)} | {fnum(r.get('ember_polygons'))} | "
                     f"{fnum(r.get('closed')) if r.get('ember_rc') == 0 else 'FAIL ' + str(r.get('ember_rc'))} | "
                     f"{fnum(r.get('unbalanced_edges'))} | {fnum(r.get('nonmanifold_edges'))} | "
                     f"{fnum(r.get('fallback_regions'))} | {fnum(r.get('rounded_degenerate'))} | "
                     f"{fnum(r.get('time_ms'))} | {fnum(r.get('output_ms'))} | {fnum(r.get('output_share'), 3)} |")
        ok = [r for r in rows if r.get("ember_rc") == 0]
        closed = sum(1 for r in ok if r.get("closed"))
        nm = sum(1 for r in ok if r.get("nonmanifold_edges"))
        ratios = [r["ratio_ember_vs_manifold"] for r in rows if r.get("ratio_ember_vs_manifold")]
        pratios = [r["ratio_polygons_vs_manifold"] for r in rows if r.get("ratio_polygons_vs_manifold")]
        shares = sorted(r["output_share"] for r in ok if r.get("output_share") is not None)
        L.append("")
        L.append(f"- ember succeeded: {len(ok)} / {len(rows)}; closed (0 unbalanced edges): {closed} / {len(ok)}; "
                 f"with non-manifold edges: {nm}")
        L.append(f"- fallback_regions > 0: {sum(1 for r in ok if r.get('fallback_regions'))}; "
                 f"rounded_degenerate > 0: {sum(1 for r in ok if r.get('rounded_degenerate'))}")
        if ratios:
            L.append(f"- geomean ember triangles / Manifold triangles: {bench.gmean(ratios):.4g} over {len(ratios)} "
                     f"(min {min(ratios):.3g}, max {max(ratios):.3g}); --polygons polygons / Manifold triangles: "
                     f"{fnum(bench.gmean(pratios))} over {len(pratios)}")
        both = [r for r in ok if r.get("manifold_slivers") is not None and r.get("ember_slivers") is not None]
        if both:
            L.append(f"- triangles with longest edge^2/area > {SLIVER_ASPECT:g}: ember {sum(r['ember_slivers'] for r in both)}"
                     f" vs Manifold {sum(r['manifold_slivers'] for r in both)} (summed over {len(both)} case/ops); "
                     f"ember more in {sum(1 for r in both if r['ember_slivers'] > r['manifold_slivers'])}, "
                     f"fewer in {sum(1 for r in both if r['ember_slivers'] < r['manifold_slivers'])}")
        if shares:
            L.append(f"- output_ms / time_ms: median {statistics.median(shares):.3g}, max {shares[-1]:.3g}, "
                     f"min {shares[0]:.3g}")
            steps = {k: sum(r.get(k) or 0 for r in ok) for k in ("weld_ms", "tjunction_ms", "regions_ms",
                                                                  "triangulate_ms", "output_ms", "time_ms")}
            L.append("- summed over the runs: " + ", ".join(f"{k} {v:.0f}" for k, v in steps.items()))
    if drows:
        L.append("\n## Degenerate inputs (union)\n")
        L.append("| case | a | b | inputs closed | --allow-open | rc | closed | unbalanced | non-manifold | fallback | "
                 "time ms | error |")
        L.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in drows:
            L.append(f"| {r['case']} | {r['mesh_a']} | {r['mesh_b']} | {r['inputs_closed']} | {r['allow_open']} | "
                     f"{r['rc']} | {fnum(r.get('closed'))} | {fnum(r.get('unbalanced_edges'))} | "
                     f"{fnum(r.get('nonmanifold_edges'))} | {fnum(r.get('fallback_regions'))} | "
                     f"{fnum(r.get('time_ms'))} | {r.get('error', '')[:100]} |")
    (outdir / "summary.md").write_text("\n".join(L) + "\n")


def render(rows: list[dict], outdir: Path) -> None:
    ok = [r for r in rows if r.get("ember_rc") == 0 and r.get("ember_obj")]
    picks = []
    pu = [r for r in ok if r["group"] == "pairs" and r["op"] == "union" and 3000 <= (r["ember_triangles"] or 0) <= 60000]
    pp = [r for r in ok if r["group"] == "paper" and r["op"] in ("union", "intersection")
          and 500 <= (r["ember_triangles"] or 0) <= 60000]
    pd = [r for r in ok if r["group"] == "pairs" and r["op"] == "difference" and 3000 <= (r["ember_triangles"] or 0) <= 60000]
    for name, cand in (("pair_union", pu), ("paper", pp), ("pair_difference", pd)):
        if cand:
            picks.append((name, cand[0]))
    for name, r in picks:
        png = outdir / f"render_{name}_{r['case']}_{r['op']}.png"
        log(f"render {r['ember_obj']} -> {png}")
        subprocess.run(["/usr/bin/python3", str(REPO / "tools/render_obj.py"), r["ember_obj"], str(png)], check=False)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", default=str(REPO.parent / "shared/data"))
    ap.add_argument("--bin", default=str(REPO / "build/bin/ember"))
    ap.add_argument("--pymod", default=str(REPO / "build/python"), help="folder with the ember Python module")
    ap.add_argument("--out", default="/tmp/wt-measure")
    ap.add_argument("--pairs", type=int, default=20)
    ap.add_argument("--seed", type=int, default=20220704, help="bench.py's default seed")
    ap.add_argument("--offset", type=float, default=0.15, help="bench.py's default offset")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds per ember run (longer: skipped)")
    ap.add_argument("--cases", default="", help="comma-separated case ids to keep (default all)")
    ap.add_argument("--skip-manifold", action="store_true")
    ap.add_argument("--skip-polygons", action="store_true")
    ap.add_argument("--skip-manifold-quality", action="store_true",
                    help="do not write Manifold's result (bench/watertight/manifold_dump.mjs) to compare slivers")
    ap.add_argument("--skip-degenerate", action="store_true")
    ap.add_argument("--only-degenerate", action="store_true")
    ap.add_argument("--render", action="store_true")
    args = ap.parse_args()
    sys.path.insert(0, args.pymod)
    import numpy as np
    import ember
    outdir = Path(args.out)
    outdir.mkdir(parents=True, exist_ok=True)
    if not args.skip_manifold and not args.only_degenerate and \
            not (REPO / "bench/peers/node_modules/manifold-3d").exists():
        log("missing bench/peers/node_modules/manifold-3d: run npm install in bench/peers (or --skip-manifold)")
        return 2
    rows = [] if args.only_degenerate else part_a(args, ember, np, outdir)
    drows = [] if args.skip_degenerate else part_b(args, ember, np, outdir)
    summarize(rows, drows, outdir, args)
    if args.render and rows:
        render(rows, outdir)
    log(f"done: {outdir / 'results.csv'}, {outdir / 'degenerate.csv'}, {outdir / 'summary.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
