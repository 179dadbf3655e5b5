#!/usr/bin/env python3
"""Checks the include structure of src/ and include/ (run by the test suite).

1. No include cycles: the graph of quoted includes ("core/...", "ember/...")
   between the project's own headers has no strongly connected component of
   more than one file (and no file includes itself).
2. Headers match sources: every .cpp under src/ first includes its own header
   (the .hpp of the same name beside it) or, for a file that implements part
   of the installed API, a header under include/ember/. A main() file of a
   program (src/cli/main.cpp, src/python/module.cpp) is exempt.
3. The installed headers (include/ember/) include nothing from src/.

    tools/check_includes.py [REPO]

Prints what it checked; exit status 1 with every violation listed.
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
PROGRAMS = {"src/cli/main.cpp", "src/python/module.cpp"}


def resolve(repo: Path, name: str) -> Path | None:
    for base in (repo / "src", repo / "include"):
        p = base / name
        if p.is_file():
            return p
    return None


def includes(path: Path) -> list[str]:
    return INCLUDE.findall(path.read_text(encoding="utf-8"))


def cycles(graph: dict[Path, list[Path]]) -> list[list[Path]]:
    """Strongly connected components of more than one node, or with a self edge (Tarjan, iterative)."""
    index: dict[Path, int] = {}
    low: dict[Path, int] = {}
    on_stack: set[Path] = set()
    stack: list[Path] = []
    found: list[list[Path]] = []
    counter = 0
    for start in graph:
        if start in index:
            continue
        work = [(start, iter(graph[start]))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, it = work[-1]
            advanced = False
            for nxt in it:
                if nxt not in index:
                    index[nxt] = low[nxt] = counter
                    counter += 1
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, iter(graph[nxt])))
                    advanced = True
                    break
                if nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                comp = []
                while True:
                    x = stack.pop()
                    on_stack.discard(x)
                    comp.append(x)
                    if x == node:
                        break
                if len(comp) > 1 or node in graph[node]:
                    found.append(sorted(comp))
    return found


def main() -> int:
    repo = Path(sys.argv[1]).resolve() if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent
    files = sorted(p for d in ("src", "include") for p in (repo / d).rglob("*") if p.suffix in (".hpp", ".cpp"))
    problems: list[str] = []
    graph: dict[Path, list[Path]] = {}
    for f in files:
        targets = []
        for name in includes(f):
            p = resolve(repo, name)
            if p is None:
                if f.suffix == ".hpp" or not name.endswith(".hpp"):
                    continue  # a system or generated header
                continue
            targets.append(p)
        graph[f] = targets
    rel = lambda p: str(p.relative_to(repo))
    for comp in cycles(graph):
        problems.append("include cycle: " + " -> ".join(rel(p) for p in comp))
    for f in files:
        r = rel(f)
        if f.suffix != ".cpp" or not r.startswith("src/") or r in PROGRAMS:
            continue
        names = includes(f)
        own = f.with_suffix(".hpp")
        first = resolve(repo, names[0]) if names else None
        if first == own or (first is not None and rel(first).startswith("include/ember/")):
            continue
        problems.append(f"{r}: its first include should be its own header ({rel(own)}) or the API header it implements")
    for f in files:
        if rel(f).startswith("include/"):
            for name in includes(f):
                p = resolve(repo, name)
                if p is not None and rel(p).startswith("src/"):
                    problems.append(f"{rel(f)}: installed header includes {rel(p)}, which is not installed")
    print(f"check_includes: {len(files)} files, {sum(len(v) for v in graph.values())} project includes")
    for p in problems:
        print("  " + p)
    print("check_includes: " + ("FAILED" if problems else "no include cycles; every source starts with its header"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
