"""The example of docs/python.md; ctest runs it (docs.python_example).

    PYTHONPATH=build/python /usr/bin/python3 docs/examples/python_example.py [DIR]
"""
import os
import sys

import numpy as np

import ember

out = sys.argv[1] if len(sys.argv) > 1 else "."
os.makedirs(out, exist_ok=True)

# A mesh is a (vertices float (n, 3), faces int (m, 3)) pair, or any object
# with .vertices and .faces such as a trimesh.Trimesh.
corners = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=np.float64)
quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
faces = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))])
box = (corners * 2.0, faces)               # [0, 2]^3
shifted = (corners * 2.0 + 1.0, faces)     # [1, 3]^3

vertices, triangles = ember.difference(box, shifted)
print("difference:", len(triangles), "triangles")

# Provenance (operand, face) per output triangle and statistics, on request.
v, f, provenance, stats = ember.union(box, shifted, return_provenance=True, return_stats=True, threads=0)
print("union:", len(f), "triangles from operands", sorted(set(provenance[:, 0].tolist())), "in", round(stats["time_ms"], 2), "ms")

# Any format by extension: .obj .stl .off .ply .3mf
ember.write(os.path.join(out, "union.3mf"), (v, f))
again = ember.read(os.path.join(out, "union.3mf"))
print("read back:", again[0].shape, again[1].shape)

# Bad input raises ember.Error (a ValueError) with the library's message.
try:
    ember.union(box, (corners, faces[:-1]))
except ember.Error as e:
    print("error:", e)
