"""Tests of the Python module `ember` (src/python/module.cpp).

Run by ctest (python.module) with PYTHONPATH=build/python:
    PYTHONPATH=build/python /usr/bin/python3 -m unittest discover -s tests/python -v
"""
import math
import os
import tempfile
import threading
import time
import unittest
import warnings
import zipfile

import numpy as np

import ember


def cube(lo=0.0, hi=1.0):
    """An axis-aligned cube with outward triangles."""
    v = np.array([[x, y, z] for z in (lo, hi) for y in (lo, hi) for x in (lo, hi)], dtype=np.float64)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    f = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))], dtype=np.int64)
    return v, f


def volume(mesh):
    v, f = mesh
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


class Booleans(unittest.TestCase):
    def setUp(self):
        self.a = cube(0.0, 2.0)
        self.b = cube(1.0, 3.0)

    def test_operations_have_the_exact_volumes(self):
        self.assertAlmostEqual(volume(ember.union(self.a, self.b)), 15.0, places=12)
        self.assertAlmostEqual(volume(ember.intersection(self.a, self.b)), 1.0, places=12)
        self.assertAlmostEqual(volume(ember.difference(self.a, self.b)), 7.0, places=12)
        self.assertAlmostEqual(volume(ember.xor(self.a, self.b)), 14.0, places=12)

    def test_results_are_float64_vertices_and_int_triangles(self):
        v, f = ember.union(self.a, self.b)
        self.assertEqual(v.dtype, np.float64)
        self.assertEqual(v.shape[1], 3)
        self.assertTrue(np.issubdtype(f.dtype, np.integer))
        self.assertEqual(f.shape[1], 3)
        self.assertTrue((f >= 0).all() and (f < len(v)).all())

    def test_many_operands_and_min_k(self):
        c = cube(0.0, 2.0)
        c = (c[0] + [0.0, 0.0, 1.0], c[1])  # a shifted by z+1
        # pairwise overlaps: a&b 1, a&c 4, b&c 2; all three: 1
        self.assertAlmostEqual(volume(ember.union(self.a, self.b, c)), 8 + 8 + 8 - 1 - 4 - 2 + 1, places=12)
        self.assertAlmostEqual(volume(ember.union(self.a, self.b, c, min_k=2)), 1 + 4 + 2 - 2 * 1, places=12)
        self.assertAlmostEqual(volume(ember.union(self.a, self.b, c, min_k=3)), 1.0, places=12)

    def test_inputs_may_be_lists_int32_and_objects_with_vertices_and_faces(self):
        class Trimeshish:  # what trimesh.Trimesh offers
            def __init__(self, m):
                self.vertices, self.faces = m

        v, f = self.b
        expected = volume(ember.union(self.a, self.b))
        self.assertAlmostEqual(volume(ember.union(Trimeshish(self.a), (v.tolist(), f.astype(np.int32)))), expected)

    def test_provenance_and_stats_on_request(self):
        v, f, prov, stats = ember.union(self.a, self.b, return_provenance=True, return_stats=True, threads=1)
        self.assertEqual(prov.shape, (len(f), 2))
        self.assertEqual(set(prov[:, 0].tolist()), {0, 1})
        self.assertTrue((prov[:, 1] < 12).all())
        self.assertEqual(stats["input_triangles"], 24)
        self.assertEqual(stats["threads"], 1)
        self.assertTrue(stats["solid_path"])  # both boxes proven solid
        self.assertIn("time_ms", stats)
        self.assertEqual(len(ember.union(self.a, self.b, return_stats=True)), 3)

    def test_bad_input_raises_ember_error_with_the_library_message(self):
        v, f = self.b
        with self.assertRaises(ember.Error) as e:
            ember.union(self.a, (v, f + 100))
        self.assertIn("operand 1", str(e.exception))
        self.assertTrue(issubclass(ember.Error, ValueError))
        bad = v.copy()
        bad[0, 0] = math.nan
        with self.assertRaisesRegex(ember.Error, "non-finite"):
            ember.union(self.a, (bad, f))
        with self.assertRaisesRegex(ember.Error, "not closed"):
            ember.union(self.a, (v, f[:-1]))
        with self.assertRaisesRegex(ember.Error, r"shape \(n, 3\)"):
            ember.union(self.a, (v[:, :2], f))
        with self.assertRaisesRegex(ember.Error, "integer"):
            ember.union(self.a, (v, f.astype(np.float64)))
        with self.assertRaises(TypeError):
            ember.union(self.a, 42)
        with self.assertRaises(TypeError):
            ember.union(self.a, self.b, colour="red")
        with self.assertRaises(TypeError):
            ember.difference(self.a, self.b, min_k=2)  # min_k is a union option

    def test_option_values_of_the_wrong_kind_or_range_name_the_argument(self):
        for kwargs, error, words in (
            ({"threads": 2**40}, ValueError, "threads"),
            ({"threads": -1}, ValueError, "threads"),
            ({"threads": "a"}, TypeError, "threads"),
            ({"threads": 1.0}, TypeError, "threads"),
            ({"min_k": 1.5}, TypeError, "min_k"),
            ({"min_k": 3}, ValueError, "min_k"),
            ({"min_k": 0}, ValueError, "min_k"),
            ({"allow_open": "yes"}, TypeError, "allow_open"),
            ({"return_stats": None}, TypeError, "return_stats"),
        ):
            with self.subTest(kwargs=kwargs):
                with self.assertRaises(error) as e:
                    ember.union(self.a, self.b, **kwargs)
                self.assertIn(words, str(e.exception))
                self.assertNotIn("Unable to cast", str(e.exception))
        v, f = ember.union(self.a, self.b, threads=2, min_k=2, allow_open=False)
        self.assertAlmostEqual(volume((v, f)), 1.0)

    def test_uint64_face_index_is_reported_as_given(self):
        v, f = self.b
        big = f.astype(np.uint64)
        big[2, 1] = 2**63 + 7
        with self.assertRaises(ember.Error) as e:
            ember.union(self.a, (v, big))
        self.assertIn(str(2**63 + 7), str(e.exception))
        self.assertIn("face 2", str(e.exception))
        ok = ember.union(self.a, (v, f.astype(np.uint64)))
        self.assertAlmostEqual(volume(ok), 15.0)

    def test_open_input_is_allowed_on_request_with_a_warning(self):
        v, f = self.b
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            ember.union(self.a, (v, f[:-1]), allow_open=True)
        self.assertTrue(any("not closed" in str(w.message) for w in caught))

    def test_the_gil_is_released_while_computing(self):
        # A Python thread keeps running while a long Boolean computes.
        big = [self._sphere(c, 160, 80) for c in (0.0, 0.7, 1.4)]
        ticks = []
        done = threading.Event()

        def ticker():
            while not done.is_set():
                ticks.append(time.perf_counter())
                time.sleep(0.001)

        t = threading.Thread(target=ticker)
        t.start()
        start = time.perf_counter()
        ember.union(*big, detect_solid=False)
        end = time.perf_counter()
        done.set()
        t.join()
        during = [x for x in ticks if start < x < end]
        self.assertGreater(end - start, 0.05, "the Boolean was too quick to tell")
        self.assertGreater(len(during), 5, "no Python thread ran during the Boolean")

    @staticmethod
    def _sphere(cx, nu, nv):
        verts = [[cx, 0.0, 1.0]]
        for j in range(1, nv):
            th = math.pi * j / nv
            for i in range(nu):
                ph = 2 * math.pi * i / nu
                verts.append([cx + math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th)])
        verts.append([cx, 0.0, -1.0])
        faces = []
        ring = lambda j, i: 1 + (j - 1) * nu + (i % nu)
        for i in range(nu):
            faces.append([0, ring(1, i), ring(1, i + 1)])
        for j in range(1, nv - 1):
            for i in range(nu):
                faces.append([ring(j, i), ring(j + 1, i), ring(j + 1, i + 1)])
                faces.append([ring(j, i), ring(j + 1, i + 1), ring(j, i + 1)])
        last = len(verts) - 1
        for i in range(nu):
            faces.append([last, ring(nv - 1, i + 1), ring(nv - 1, i)])
        return np.array(verts), np.array(faces)


class Files(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.mesh = cube(0.0, 1.0)

    def tearDown(self):
        self.dir.cleanup()

    def path(self, name):
        return os.path.join(self.dir.name, name)

    def test_paths_may_be_path_like(self):
        import pathlib

        p = pathlib.Path(self.dir.name) / "cube.ply"
        ember.write(p, self.mesh)
        v, f = ember.read(p)
        self.assertEqual(f.shape, (12, 3))
        self.assertEqual(len(ember.read_all(p)), 1)
        v2, _ = ember.read(os.fsencode(str(p)))  # bytes paths too
        self.assertTrue(np.array_equal(v, v2))
        with self.assertRaises(TypeError):
            ember.read(42)

    def test_write_refuses_non_finite_coordinates(self):
        v, f = self.mesh
        bad = v.copy()
        bad[3, 1] = math.nan
        for ext in ("obj", "stl", "off", "ply", "3mf"):
            with self.subTest(ext=ext):
                p = self.path("bad." + ext)
                with self.assertRaisesRegex(ember.Error, "vertex 3.*non-finite"):
                    ember.write(p, (bad, f))
                self.assertFalse(os.path.exists(p))

    def test_every_format_round_trips(self):
        for ext in ("obj", "stl", "off", "ply", "3mf"):
            p = self.path("cube." + ext)
            ember.write(p, self.mesh)
            v, f = ember.read(p)
            self.assertEqual(f.shape, (12, 3), ext)
            self.assertAlmostEqual(volume((v, f)), 1.0, places=12, msg=ext)
            self.assertEqual(len(ember.read_all(p)), 1)

    def test_provenance_is_written_to_ply_as_face_properties(self):
        shifted = (self.mesh[0] + 0.5, self.mesh[1])
        v, f, prov = ember.union(self.mesh, shifted, return_provenance=True)
        p = self.path("u.ply")
        ember.write(p, (v, f), provenance=prov)
        data = open(p, "rb").read()
        self.assertIn(b"property uint operand\nproperty uint source_face\n", data)
        body = data.index(b"end_header\n") + 11 + len(v) * 24
        self.assertEqual(len(data), body + len(f) * 21)
        for i in range(len(f)):
            rec = data[body + i * 21: body + (i + 1) * 21]
            self.assertEqual(int.from_bytes(rec[13:17], "little"), prov[i][0])
            self.assertEqual(int.from_bytes(rec[17:21], "little"), prov[i][1])
        v2, f2 = ember.read(p)
        self.assertEqual(f2.shape, f.shape)
        with self.assertRaises(ember.Error):
            ember.write(p, (v, f), provenance=prov[:1])
        with self.assertRaises(ember.Error):
            ember.write(p, (v, f), provenance=[[0, -1]] * len(f))

    def test_read_all_gives_each_3mf_object_with_transforms_applied(self):
        # A 3MF made by hand (test data only): object 1 is a unit tetrahedron,
        # object 2 a components object that holds it shifted by x+10; the
        # build places object 1 as is and object 2 shifted again by y+5.
        model = """<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
 <resources>
  <object id="1" type="model"><mesh>
   <vertices><vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/><vertex x="0" y="0" z="1"/></vertices>
   <triangles><triangle v1="0" v2="2" v3="1"/><triangle v1="0" v2="1" v3="3"/><triangle v1="0" v2="3" v3="2"/><triangle v1="1" v2="2" v3="3"/></triangles>
  </mesh></object>
  <object id="2" type="model"><components><component objectid="1" transform="1 0 0 0 1 0 0 0 1 10 0 0"/></components></object>
 </resources>
 <build><item objectid="1"/><item objectid="2" transform="1 0 0 0 1 0 0 0 1 0 5 0"/></build>
</model>"""
        p = self.path("two.3mf")
        with zipfile.ZipFile(p, "w") as z:
            z.writestr("[Content_Types].xml", '<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types"><Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/><Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>')
            z.writestr("_rels/.rels", '<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>')
            z.writestr("3D/3dmodel.model", model)
        meshes = ember.read_all(p)
        self.assertEqual(len(meshes), 2)
        np.testing.assert_array_equal(meshes[0][0].min(axis=0), [0, 0, 0])
        np.testing.assert_array_equal(meshes[1][0].min(axis=0), [10, 5, 0])
        self.assertAlmostEqual(volume(meshes[1]), 1.0 / 6.0, places=12)
        with self.assertRaisesRegex(ember.Error, "2 objects"):
            ember.read(p)

    def test_file_errors_name_the_file(self):
        with self.assertRaisesRegex(ember.Error, "nope.obj"):
            ember.read(self.path("nope.obj"))
        with self.assertRaisesRegex(ember.Error, "unknown mesh file extension"):
            ember.write(self.path("x.xyz"), self.mesh)
        with open(self.path("junk.3mf"), "wb") as f:
            f.write(b"junk")
        with self.assertRaisesRegex(ember.Error, "not a readable 3MF"):
            ember.read(self.path("junk.3mf"))


def box(lo, hi):
    """An axis-aligned box from corner lo to corner hi."""
    v, f = cube(0.0, 1.0)
    return v * (np.array(hi, dtype=np.float64) - np.array(lo, dtype=np.float64)) + np.array(lo, dtype=np.float64), f


class Expressions(unittest.TestCase):
    """ember.Csg: any CSG expression as one Boolean (boxes: exact volumes)."""

    def setUp(self):
        self.a = box((0, 0, 0), (2, 2, 2))
        self.b = box((1, 1, 1), (3, 3, 3))
        self.c = box((1, 1, -1), (2, 2, 4))
        self.d = box((0, 0, 1.5), (3, 3, 4))

    def test_expressions_have_the_exact_volumes(self):
        a, b, c, d = (ember.Csg(m) for m in (self.a, self.b, self.c, self.d))
        self.assertEqual(volume((a | b).evaluate()), 15.0)
        self.assertEqual(volume(((a | b) - c).evaluate()), 12.0)
        self.assertEqual(volume((((a | b) - c) & d).evaluate()), 6.0)
        self.assertEqual(volume(ember.evaluate((a ^ b) | (c - d))), 15.5)
        self.assertEqual(volume(ember.at_least(2, a, b, self.c).evaluate()), 3.0)  # pairwise overlaps: [1,2]^2 x [0,3]

    def test_a_mesh_used_twice_is_one_operand(self):
        a, b = ember.Csg(self.a), ember.Csg(self.b)
        e = (a | b) - (a & b)
        self.assertEqual(len(e.operands), 2)
        self.assertEqual(repr(e), "ember.Csg((#0 | #1) - (#0 & #1))")
        v, f, stats = e.evaluate(return_stats=True, threads=2)
        self.assertEqual(stats["input_triangles"], 24)
        self.assertEqual(volume((v, f)), 14.0)

    def test_provenance_names_the_distinct_meshes(self):
        # A column off the boxes' planes, so every operand's faces reach the result.
        column = box((0.5, 0.5, -1), (1.5, 1.5, 4))
        a, b, c = (ember.Csg(m) for m in (self.a, self.b, column))
        v, f, prov = ((a | b) - c).evaluate(return_provenance=True)
        self.assertEqual(set(prov[:, 0].tolist()), {0, 1, 2})

    def test_threads_do_not_change_the_result(self):
        a, b, c = (ember.Csg(m) for m in (self.a, self.b, self.c))
        e = (a ^ b) - c
        one, two = e.evaluate(threads=1), e.evaluate(threads=2)
        self.assertTrue(np.array_equal(one[0], two[0]) and np.array_equal(one[1], two[1]))

    def test_layers_come_from_one_call_and_stack_up(self):
        layers = ember.layers(self.a, self.b, self.c, self.d, threads=2)
        self.assertEqual(len(layers), 4)
        for k, layer in enumerate(layers, start=1):
            self.assertEqual(volume(layer), volume(ember.union(self.a, self.b, self.c, self.d, min_k=k)))
        self.assertEqual(sum(volume(layer) for layer in layers), 8 + 8 + 5 + 22.5)
        v, f, stats = ember.layers(self.a, self.b, return_stats=True)[1]
        self.assertEqual(volume((v, f)), 1.0)
        with self.assertRaises(TypeError):
            ember.layers(self.a, self.b, min_k=2)

    def test_misuse_raises_errors_that_name_the_argument(self):
        a, b = ember.Csg(self.a), ember.Csg(self.b)
        with self.assertRaises(TypeError):
            (a | b).evaluate(min_k=2)
        with self.assertRaises(ValueError):
            ember.at_least(3, a, b)
        with self.assertRaises(ember.Error):
            ember.Csg((np.zeros((3, 3)), np.array([[0, 1, 5]])))


if __name__ == "__main__":
    unittest.main()
