#!/usr/bin/env python3
"""Byte-for-byte comparison of two ember CLI builds on real cases.

A refactoring of the core or the mesh stage must not change a single output
byte. This tool makes a fixed, seeded set of cases from ../shared/data (the
EMBER paper's cases that have local meshes, with their transforms, and clean-
pool pairs scaled to a unit box and rotated so that they overlap), runs both
binaries on every case x operation (triangle mesh and --polygons output) and
reports every difference.

    tools/compare_builds.py NEW_BIN REF_BIN [--data ../shared/data] [--work /tmp/ember-cmp]

Reference outputs are cached per REF_BIN path and case under --work, so a
second run only runs NEW_BIN. Exit code 1 if anything differs or fails.

--same-mesh compares triangle-mesh outputs as meshes instead of bytes: the
same vertices (exact decimal text) and the same oriented faces, in any order
and any rotation. For changes that only reorder the output.
"""
from __future__ import annotations

import argparse
import filecmp
import hashlib
import math
import os
import random
import struct
import subprocess
import sys


def read_stl(path):
    data = open(path, "rb").read()
    if len(data) >= 84:
        n = struct.unpack_from("<I", data, 80)[0]
        if 84 + 50 * n == len(data):
            tris = []
            for i in range(n):
                v = struct.unpack_from("<9f", data, 84 + 50 * i + 12)
                tris.append((v[0:3], v[3:6], v[6:9]))
            return tris
    tris, cur = [], []
    for line in data.decode("latin-1").splitlines():
        w = line.split()
        if w and w[0] == "vertex":
            cur.append(tuple(float(x) for x in w[1:4]))
            if len(cur) == 3:
                tris.append(tuple(cur))
                cur = []
    return tris


def read_obj(path):
    verts, tris = [], []
    for line in open(path, encoding="latin-1"):
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            verts.append(tuple(float(x) for x in w[1:4]))
        elif w[0] == "f":
            idx = [int(t.split("/")[0]) for t in w[1:]]
            idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
            for k in range(1, len(idx) - 1):
                tris.append((verts[idx[0]], verts[idx[k]], verts[idx[k + 1]]))
    return tris


def read_off(path):
    words = [w for line in open(path, encoding="latin-1") for w in line.split("#")[0].split()]
    assert words[0].upper().endswith("OFF")
    nv, nf = int(words[1]), int(words[2])
    pos = 4
    verts = []
    for _ in range(nv):
        verts.append(tuple(float(x) for x in words[pos:pos + 3]))
        pos += 3
    tris = []
    for _ in range(nf):
        k = int(words[pos])
        idx = [int(x) for x in words[pos + 1:pos + 1 + k]]
        pos += 1 + k
        for j in range(1, k - 1):
            tris.append((verts[idx[0]], verts[idx[j]], verts[idx[j + 1]]))
    return tris


def read_mesh(path):
    ext = path.lower().rsplit(".", 1)[-1]
    return {"stl": read_stl, "off": read_off, "obj": read_obj}[ext](path)


def write_obj(path, tris, transform):
    index, verts, faces = {}, [], []
    for t in tris:
        f = []
        for p in t:
            q = transform(p)
            if q not in index:
                index[q] = len(verts)
                verts.append(q)
            f.append(index[q] + 1)
        faces.append(f)
    with open(path, "w") as out:
        for v in verts:
            out.write("v %r %r %r\n" % v)
        for f in faces:
            out.write("f %d %d %d\n" % tuple(f))


def colmajor(values):
    m = [float(x) for x in values.split(",")]
    return lambda p: tuple(m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r] for r in range(3))


def rotation(axis, angle):
    n = math.sqrt(sum(a * a for a in axis))
    x, y, z = (a / n for a in axis)
    c, s = math.cos(angle), math.sin(angle)
    return [[c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s],
            [y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s],
            [z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c)]]


def unit_box_rotated(tris, rng):
    pts = [p for t in tris for p in t]
    lo = [min(p[i] for p in pts) for i in range(3)]
    hi = [max(p[i] for p in pts) for i in range(3)]
    scale = 1.0 / max(hi[i] - lo[i] for i in range(3))
    mid = [(lo[i] + hi[i]) / 2 for i in range(3)]
    r = rotation([rng.uniform(-1, 1) for _ in range(3)], rng.uniform(0, 2 * math.pi))
    shift = [rng.uniform(-0.2, 0.2) for _ in range(3)]

    def f(p):
        q = [(p[i] - mid[i]) * scale for i in range(3)]
        return tuple(sum(r[a][b] * q[b] for b in range(3)) + shift[a] for a in range(3))

    return f


def make_cases(data, work, pool_pairs, seed):
    os.makedirs(work, exist_ok=True)
    cases = []
    tsv = os.path.join(data, "peer-tests/manifold/ember/cases_with_local_meshes.tsv")
    for line in open(tsv).read().splitlines()[1:]:
        idx, _, _, pa, pb, ta, tb = line.split("\t")
        name = "ember%s" % idx
        for side, p, t in (("a", pa, ta), ("b", pb, tb)):
            out = os.path.join(work, "%s_%s.obj" % (name, side))
            if not os.path.exists(out):
                write_obj(out, read_mesh(os.path.join(data, p)), colmajor(t))
        cases.append(name)
    pool = [p for p in open(os.path.join(data, "clean_pool_1k_100k.txt")).read().split()
            if p.lower().rsplit(".", 1)[-1] in ("stl", "off", "obj")]
    rng = random.Random(seed)
    for i in range(pool_pairs):
        name = "pool%02d" % i
        pa, pb = rng.sample(pool, 2)
        for side, p in (("a", pa), ("b", pb)):
            out = os.path.join(work, "%s_%s.obj" % (name, side))
            tris = read_mesh(os.path.join(data, p))
            f = unit_box_rotated(tris, rng)
            if not os.path.exists(out):
                write_obj(out, tris, f)
        cases.append(name)
    return cases


def canonical_mesh(path):
    """Sorted oriented faces as tuples of vertex text, each rotated to start
    at its smallest vertex; None if the file is not a mesh (a failure)."""
    verts, faces = [], []
    for line in open(path):
        if line.startswith("v "):
            verts.append(tuple(line.split()[1:4]))
        elif line.startswith("f "):
            f = [verts[int(t.split("/")[0]) - 1] for t in line.split()[1:]]
            k = f.index(min(f))
            faces.append(tuple(f[k:] + f[:k]))
    if not faces and not verts:
        return None
    return sorted(faces), sorted(verts)


def same_output(ref, new, as_mesh):
    if filecmp.cmp(ref, new, shallow=False):
        return True
    if not as_mesh:
        return False
    a, b = canonical_mesh(ref), canonical_mesh(new)
    return a is not None and a == b


def run(binary, op, a, b, out, extra):
    cmd = [binary, op, a, b, "-o", out, "--quiet", "--threads", "2"] + extra
    r = subprocess.run(cmd, capture_output=True, text=True)
    return r.returncode, r.stderr.strip()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("new")
    ap.add_argument("ref")
    ap.add_argument("--data", default=os.path.join(os.path.dirname(__file__), "../../shared/data"))
    ap.add_argument("--work", default="/tmp/ember-cmp")
    ap.add_argument("--pool-pairs", type=int, default=14)
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--ops", default="union,intersection,difference")
    ap.add_argument("--same-mesh", action="store_true", help="compare triangle meshes up to face order and rotation")
    args = ap.parse_args()
    if not os.path.isdir(args.data):
        sys.exit("no data folder at %s (pass --data)" % args.data)
    cases = make_cases(args.data, os.path.join(args.work, "cases"), args.pool_pairs, args.seed)
    ref_dir = os.path.join(args.work, "ref-" + hashlib.sha1(os.path.abspath(args.ref).encode()).hexdigest()[:10])
    new_dir = os.path.join(args.work, "new")
    os.makedirs(ref_dir, exist_ok=True)
    os.makedirs(new_dir, exist_ok=True)
    bad = 0
    for case in cases:
        a = os.path.join(args.work, "cases", case + "_a.obj")
        b = os.path.join(args.work, "cases", case + "_b.obj")
        for op in args.ops.split(","):
            for mode, extra in (("mesh", []), ("polygons", ["--polygons"])):
                name = "%s_%s_%s.obj" % (case, op, mode)
                ref_out, new_out = os.path.join(ref_dir, name), os.path.join(new_dir, name)
                if not os.path.exists(ref_out):
                    rc, err = run(args.ref, op, a, b, ref_out, extra)
                    if rc != 0:
                        open(ref_out, "w").write("FAILED rc=%d %s\n" % (rc, err))
                rc, err = run(args.new, op, a, b, new_out, extra)
                if rc != 0:
                    open(new_out, "w").write("FAILED rc=%d %s\n" % (rc, err))
                same = same_output(ref_out, new_out, args.same_mesh and mode == "mesh")
                bad += not same
                print("%-8s %-40s" % ("same" if same else "DIFFERS", name), flush=True)
    print("%d of %d outputs differ" % (bad, len(cases) * len(args.ops.split(",")) * 2))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
