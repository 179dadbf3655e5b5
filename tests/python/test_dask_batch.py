"""tools/dask_batch.py: a folder of meshes as Dask tasks (python.module runs it).

Needs python3-distributed (scripts/setup.sh installs it); skipped, visibly, without it.
"""
import importlib.util
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

import ember

REPO = Path(__file__).resolve().parents[2]
HAVE_DASK = importlib.util.find_spec("distributed") is not None


def cube(lo, hi):
    v = np.array([[x, y, z] for z in (lo, hi) for y in (lo, hi) for x in (lo, hi)], dtype=np.float64)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return v, np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))], dtype=np.int64)


@unittest.skipUnless(HAVE_DASK, "python3-distributed is not installed: Dask batch not tested")
class DaskBatch(unittest.TestCase):
    def run_batch(self, *extra):
        with tempfile.TemporaryDirectory() as tmp:
            folder, out = Path(tmp) / "in", Path(tmp) / "out"
            folder.mkdir()
            ember.write(folder / "a.obj", cube(0.0, 2.0))
            ember.write(folder / "b.stl", cube(1.0, 3.0))
            ember.write(folder / "c.ply", cube(0.0, 1.0))
            (folder / "d.obj").write_text("not a mesh\n")
            r = subprocess.run([sys.executable, str(REPO / "tools" / "dask_batch.py"), str(folder), str(out), *extra],
                               capture_output=True, text=True, env=dict(os.environ), timeout=300)
            self.assertEqual(r.returncode, 0, r.stderr)
            summary = (out / "summary.md").read_text()
            # Two tasks: a+b succeeds, c+d fails on the broken file without stopping the batch.
            self.assertIn("| 2 | 1 | 1 |", summary)
            self.assertIn("d.obj:1: unknown OBJ statement", summary)
            v, f = ember.read(out / "a+b.ply")
            self.assertGreater(len(f), 0)
            self.assertEqual(sorted(p.name for p in out.iterdir()), ["a+b.ply", "summary.md"])

    def test_local_cluster_collects_failures_and_writes_results(self):
        self.run_batch("--workers", "2")

    def test_plain_loop_gives_the_same_results(self):
        self.run_batch("--serial")


if __name__ == "__main__":
    unittest.main()
