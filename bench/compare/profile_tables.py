"""The profile figures of the comparison benchmark (bench.py): per-phase
times, thread scaling, cold (first-run) times, peak RSS per input triangle and
instructions per input triangle (callgrind). Each function returns markdown
lines for summary.md; `count_instructions` runs the callgrind measurement."""
from __future__ import annotations

import math
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

PHASES = ["setup", "proof", "solve", "output"]
# callgrind collects inside this function (its full signature: see count_instructions).
BOOLEAN_SYMBOL = ("ember::boolean(std::span<ember::Mesh const, 18446744073709551615ul>, ember::Operation, "
                  "ember::BooleanOptions const&)")


def gmean(xs):
    """Geometric mean of the positive finite values, None if there are none."""
    xs = [x for x in xs if x is not None and x > 0 and math.isfinite(x)]
    return math.exp(sum(math.log(x) for x in xs) / len(xs)) if xs else None


def fmt(x, digits=3):
    """Table cell: '–' for missing, integers and values >= 1000 without decimals."""
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "–"
    if isinstance(x, int):
        return str(x)
    if abs(x) >= 1000:
        return f"{x:.0f}"
    return f"{x:.{digits}g}"


def phase_section(rows: list[dict], tools: list[str]) -> list[str]:
    """Sum of each phase's median over the pairs and paper cases, per ember run."""
    main = [r for r in rows if r.get("group") in ("pairs", "paper")]
    embers = [t for t in tools if t.startswith("ember") and any(r.get(f"{t}_setup_ms") is not None for r in main)]
    if not embers:
        return []
    L = ["## Time per phase (pool pairs + paper cases; sum of the per-case medians)\n",
         "setup = validation, quantization, grid triangles, closedness; proof = exact solid check; "
         "solve = the solid path or the subdivision and leaves (the general path builds the root soup first, docs/design.md \"The root soup only where it is read\"; the solid path's direct route makes the triangle mesh there too, docs/design.md \"Direct route\"); output = mesh stage (weld, T-junctions, regions, triangulation). "
         "At more than one thread the defaults start the solid path alongside the proof (docs/design.md, "
         "\"Pipeline\"): proof then runs until the proof ends, solve is what remains; read the two together.\n",
         "| ember | " + " | ".join(f"{p} s (share)" for p in PHASES) + " | total s | cases |",
         "|---|" + "---|" * (len(PHASES) + 2)]
    for t in embers:
        ok = [r for r in main if r.get(f"{t}_setup_ms") is not None]
        sums = {p: sum(r[f"{t}_{p}_ms"] for r in ok) / 1e3 for p in PHASES}
        total = sum(sums.values())
        cells = [f"{fmt(sums[p])} ({sums[p] / total:.0%})" if total else "–" for p in PHASES]
        L.append(f"| {t} | " + " | ".join(cells) + f" | {fmt(total)} | {len(ok)} |")
    L.append("")
    return L


def scaling_section(rows: list[dict], tools: list[str], threads: list[int]) -> list[str]:
    """Speed-up from the fewest to the most threads, overall and per phase."""
    if len(threads) < 2:
        return []
    lo, hi = min(threads), max(threads)
    L = [f"## Thread scaling ({lo} -> {hi} threads)\n",
         "Speed-up = time at the fewer threads / time at the more (sums over the cases where both ran). "
         "Per phase, from the phase medians. A phase whose speed-up stays near 1 is serial. proof+solve: "
         "the two together (at more than one thread the defaults overlap them, see above).\n",
         "| ember | geomean per case | sum, 10 largest cases | " + " | ".join(f"{p}" for p in PHASES) +
         " | proof+solve |",
         "|---|---|---|" + "---|" * (len(PHASES) + 1)]
    largest = {c for _, c in sorted({(r["in_triangles"], r["case"]) for r in rows if r.get("in_triangles")},
                                     reverse=True)[:10]}
    for prefix in ("ember", "ember_solid", "ember_nocheck"):
        a, b = f"{prefix}_t{lo}", f"{prefix}_t{hi}"
        if a not in tools or b not in tools:
            continue
        both = [r for r in rows if r.get(f"{a}_ms") and r.get(f"{b}_ms")]
        if not both:
            continue
        per_case = gmean([r[f"{a}_ms"] / r[f"{b}_ms"] for r in both])
        big = [r for r in both if r["case"] in largest]
        big_ratio = sum(r[f"{a}_ms"] for r in big) / sum(r[f"{b}_ms"] for r in big) if big else None
        cells = []
        for group in [[p] for p in PHASES] + [["proof", "solve"]]:
            pa = sum(r.get(f"{a}_{p}_ms") or 0 for r in both for p in group)
            pb = sum(r.get(f"{b}_{p}_ms") or 0 for r in both for p in group)
            cells.append(fmt(pa / pb) if pb > 0 else "–")
        L.append(f"| {prefix} | {fmt(per_case)} | {fmt(big_ratio)} | " + " | ".join(cells) + " |")
    L.append("")
    return L


def cold_section(rows: list[dict], tools: list[str]) -> list[str]:
    """First (untimed warm-up) run vs the median of the timed runs."""
    main = [r for r in rows if r.get("group") in ("pairs", "paper")]
    with_cold = [t for t in tools if any(r.get(f"{t}_cold_ms") for r in main)]
    if not with_cold:
        return []
    L = ["## First run vs repeated runs (pool pairs + paper cases, geomean)\n",
         "The tables above time repeated runs in one process (after one untimed warm-up). The warm-up "
         "run is the one-shot cost: for the first operation of each process it includes the first touch "
         "of all memory and the thread pool's start.\n",
         "| tool | first run (geomean) | repeated runs (geomean) | first / repeated |", "|---|---|---|---|"]
    for t in with_cold:
        ok = [r for r in main if r.get(f"{t}_cold_ms") and r.get(f"{t}_ms")]
        c, w = gmean([r[f"{t}_cold_ms"] for r in ok]), gmean([r[f"{t}_ms"] for r in ok])
        L.append(f"| {t} | {fmt(c)} ms | {fmt(w)} ms | {fmt(c / w if c and w else None)} |")
    L.append("")
    return L


def memory_section(rows: list[dict], tools: list[str]) -> list[str]:
    """Peak RSS of the runner process divided by the case's input triangles."""
    L = ["## Peak RSS per input triangle (bytes; runner process peak / input triangles)\n",
         "Includes the process's baseline (runtime, input arrays; node's V8/WASM runtime ~50 MiB), so small "
         "cases overstate it; the largest case is the figure to read.\n"]
    cases = {}
    for r in rows:
        if r.get("in_triangles"):
            cases.setdefault(r["case"], r)
    if not cases:
        return []
    big = max(cases.values(), key=lambda r: r["in_triangles"])
    L.append(f"| tool | median over cases | largest case ({big['case']}, {big['in_triangles']} tris) |")
    L.append("|---|---|---|")
    for t in tools:
        per = sorted(r[f"{t}_rss_mib"] * 2**20 / r["in_triangles"] for r in cases.values()
                     if r.get(f"{t}_rss_mib") and math.isfinite(r[f"{t}_rss_mib"]) and r.get(f"{t}_ms"))
        med = per[len(per) // 2] if per else None
        b = big.get(f"{t}_rss_mib")
        bb = b * 2**20 / big["in_triangles"] if b and math.isfinite(b) and big.get(f"{t}_ms") else None
        L.append(f"| {t} | {fmt(med)} | {fmt(bb)} |")
    L.append("")
    return L


def count_instructions(ember_bench: Path, data: Path, mesh: str, matrix_b: list[float], log) -> dict | None:
    """Instructions inside ember::boolean (callgrind, 1 thread, defaults) for
    `mesh` (normalized) united with its copy under matrix_b. None without valgrind."""
    if not shutil.which("valgrind"):
        log("valgrind missing: no instruction count")
        return None
    tmp = Path(tempfile.mkdtemp(prefix="ember-callgrind-"))
    try:
        ident = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0]
        tris = 0
        for name, m in (("a", ident), ("b", matrix_b)):
            out = subprocess.run([str(ember_bench), "prepare", str(data / mesh), str(tmp / f"{name}.bin"),
                                  "--normalize", "--matrix", ",".join(repr(float(v)) for v in m)],
                                 capture_output=True, text=True, check=True).stdout
            tris += int(re.search(r'"triangles":(\d+)', out).group(1))
        cg = tmp / "callgrind.out"
        # The full signature, not "ember::boolean(*": that pattern also matches
        # boolean's own lambdas (ember::boolean(...)::{lambda()#1}), and entering
        # one toggles collection off again, which hid the set-up until 2026-11-23.
        subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={cg}", f"--toggle-collect={BOOLEAN_SYMBOL}",
                        str(ember_bench), "run", str(tmp / "a.bin"), str(tmp / "b.bin"), "--ops", "union", "--runs", "1",
                        "--threads", "1"], capture_output=True, text=True, check=True, timeout=1800)
        total = None
        for line in cg.read_text(errors="replace").splitlines():
            if line.startswith("summary:") or line.startswith("totals:"):
                total = int(line.split()[1])
        if not total:
            return None
        return {"mesh": mesh, "triangles": tris, "instructions": total, "per_triangle": total / tris}
    except (subprocess.CalledProcessError, subprocess.TimeoutExpired, AttributeError) as e:
        log(f"instruction count failed: {e}")
        return None
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def instructions_section(result: dict | None) -> list[str]:
    if not result:
        return ["## Instructions per input triangle\n", "not measured (skipped with --instructions-mesh '', valgrind missing, or the run failed)\n"]
    return ["## Instructions per input triangle (callgrind)\n",
            f"{result['mesh']} (normalized) ∪ its copy rotated 1° about (1, 2, 3), {result['triangles']} input "
            f"triangles, defaults (solid proof on), 1 thread, instructions inside `ember::boolean`: "
            f"**{result['instructions'] / 1e6:.0f} M = {result['per_triangle']:.0f} per input triangle** "
            "(target: at most 5,000).\n"]


def per_case_section(rows: list[dict], tools: list[str]) -> list[str]:
    """Every case and operation: the default ember run at the most threads vs the peers."""
    embers = [t for t in tools if re.fullmatch(r"ember_t\d+", t)]
    if not embers:
        return []
    e = max(embers, key=lambda t: int(t[len("ember_t"):]))
    peers = [p for p in ("cgal", "manifold") if p in tools]
    L = [f"## Per case ({e}: defaults; ratio < 1: ember faster)\n",
         "| case | op | input tris | " + " | ".join(f"{t} ms" for t in [e] + peers) + " | " +
         " | ".join(f"{e} / {p}" for p in peers) + " |",
         "|---|---|---|" + "---|" * (1 + 2 * len(peers))]
    for r in rows:
        if not r.get("in_triangles"):
            continue
        L.append(f"| {r['case']} | {r['op']} | {r['in_triangles']} | " +
                 " | ".join(fmt(r.get(f"{t}_ms")) for t in [e] + peers) + " | " +
                 " | ".join(fmt(r.get(f"ratio_{e}_vs_{p}")) for p in peers) + " |")
    L.append("")
    return L
