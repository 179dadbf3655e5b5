#!/usr/bin/env python3
"""Topology report of an OBJ/OFF triangle or polygon mesh: faces, vertices,
edges whose directed uses do not balance (open / T-junction / orientation
errors), non-manifold edges, and repeated positions. Usage: check_mesh.py FILE..."""
import sys
from collections import Counter


def read(path):
    verts, faces = [], []
    with open(path) as f:
        if path.endswith(".off"):
            toks = f.read().split()
            nv, nf = int(toks[1]), int(toks[2])
            i = 4
            for _ in range(nv):
                verts.append(tuple(map(float, toks[i:i + 3]))); i += 3
            for _ in range(nf):
                k = int(toks[i]); faces.append([int(t) for t in toks[i + 1:i + 1 + k]]); i += 1 + k
            return verts, faces
        for line in f:
            p = line.split()
            if not p:
                continue
            if p[0] == "v":
                verts.append(tuple(map(float, p[1:4])))
            elif p[0] == "f":
                faces.append([int(t.split("/")[0]) - 1 for t in p[1:]])
    return verts, faces


def edge_counts(faces):
    """(undirected edges, unbalanced, non-manifold) of polygon faces given as
    vertex-index lists: an edge is unbalanced when its uses a->b and b->a differ
    in number, non-manifold when balanced with more than one use each way."""
    directed = Counter()
    for f in faces:
        for i in range(len(f)):
            directed[(f[i], f[(i + 1) % len(f)])] += 1
    unbalanced = nonmanifold = 0
    seen = set()
    for (a, b) in directed:
        key = (min(a, b), max(a, b))
        if key in seen:
            continue
        seen.add(key)
        fwd, bwd = directed.get((a, b), 0), directed.get((b, a), 0)
        if fwd != bwd:
            unbalanced += 1
        elif fwd > 1:
            nonmanifold += 1
    return len(seen), unbalanced, nonmanifold


def report(path):
    verts, faces = read(path)
    edges, unbalanced, nonmanifold = edge_counts(faces)
    dup = len(verts) - len(set(verts))
    tris = sum(len(f) - 2 for f in faces)
    closed = unbalanced == 0
    print(f"{path}: faces={len(faces)} triangles={tris} vertices={len(verts)} edges={edges} "
          f"unbalanced={unbalanced} nonmanifold={nonmanifold} repeated_positions={dup} "
          f"{'CLOSED' if closed else 'OPEN'}")
    return closed


if __name__ == "__main__":
    ok = all([report(p) for p in sys.argv[1:]])
    sys.exit(0 if ok else 1)
