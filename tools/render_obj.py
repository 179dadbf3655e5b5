#!/usr/bin/env python3
"""Render an OBJ polygon mesh to PNG with flat shading (for looking at results).

Usage: tools/render_obj.py mesh.obj out.png [--elev 25 --azim 35]
Needs python3-matplotlib (Debian package).
"""
import argparse
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from mpl_toolkits.mplot3d.art3d import Poly3DCollection


def read_obj(path):
    verts, faces = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                verts.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "f":
                faces.append([int(p.split("/")[0]) - 1 for p in parts[1:]])
    return verts, faces


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("obj")
    ap.add_argument("png")
    ap.add_argument("--elev", type=float, default=25)
    ap.add_argument("--azim", type=float, default=35)
    a = ap.parse_args()
    verts, faces = read_obj(a.obj)
    if not faces:
        sys.exit("empty mesh")
    polys, shades = [], []
    light = (0.4, 0.3, 0.87)
    for f in faces:
        p = [verts[i] for i in f]
        ax, ay, az = p[0]
        nx = ny = nz = 0.0
        for (bx, by, bz), (cx, cy, cz) in zip(p[1:], p[2:]):
            ux, uy, uz = bx - ax, by - ay, bz - az
            vx, vy, vz = cx - ax, cy - ay, cz - az
            nx += uy * vz - uz * vy
            ny += uz * vx - ux * vz
            nz += ux * vy - uy * vx
        n = (nx * nx + ny * ny + nz * nz) ** 0.5 or 1.0
        lam = max(0.0, (nx * light[0] + ny * light[1] + nz * light[2]) / n)
        polys.append(p)
        shades.append((0.25 + 0.7 * lam, 0.35 + 0.5 * lam, 0.55 + 0.4 * lam))
    fig = plt.figure(figsize=(7, 7), dpi=110)
    axs = fig.add_subplot(111, projection="3d")
    axs.add_collection3d(Poly3DCollection(polys, facecolors=shades, edgecolors=(0, 0, 0, 0.15), linewidths=0.1))
    xs, ys, zs = zip(*verts)
    c = [(max(v) + min(v)) / 2 for v in (xs, ys, zs)]
    r = max(max(v) - min(v) for v in (xs, ys, zs)) / 2
    axs.set_xlim(c[0] - r, c[0] + r)
    axs.set_ylim(c[1] - r, c[1] + r)
    axs.set_zlim(c[2] - r, c[2] + r)
    axs.view_init(a.elev, a.azim)
    axs.set_axis_off()
    fig.savefig(a.png, bbox_inches="tight")


if __name__ == "__main__":
    main()
