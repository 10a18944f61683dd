"""Tests of the isocurv Python module (run by CTest as python.module, with Debian's python3).

A sphere sampled into numpy arrays of every voxel type is the oracle (k1 = k2 = H = 1/R), the
module's results are compared with the command line's files, and bad arguments must raise
TypeError or ValueError naming the argument, bad files isocurv.Error.
"""
import filecmp
import os
import pathlib
import subprocess
import tempfile
import threading
import unittest
import warnings

import numpy as np

import isocurv

EXE = None  # set below from BUILD
BUILD = os.environ.get("ISOCURV_BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
TORUS = os.path.join(BUILD, "datasets", "torus.vdb")
EXE = os.path.join(BUILD, "app", "isocurv")
HAVE_CLI = os.path.exists(TORUS) and os.access(EXE, os.X_OK)
RADIUS = 12.0


def ball(dtype, scale=10.0):
    """A solid ball of radius RADIUS voxels as a CT-like density: 255 at the centre falling by
    `scale` per voxel, so the isovalue 255 - scale * RADIUS is the sphere of radius RADIUS."""
    z, y, x = np.mgrid[0:36, 0:34, 0:32].astype(np.float64)
    r = np.sqrt((x - 15.5) ** 2 + (y - 16.5) ** 2 + (z - 17.5) ** 2)
    return np.clip(255.0 - scale * r, 0, 255).astype(dtype)


class Volumes(unittest.TestCase):
    def test_from_array_every_voxel_type_gives_the_sphere(self):
        for dtype in (np.uint8, np.int8, np.uint16, np.int16, np.uint32, np.int32, np.float32, np.float64):
            a = ball(dtype) if dtype != np.int8 else (ball(np.int16) // 2).astype(np.int8)
            iso = 255 - 10 * RADIUS if dtype != np.int8 else (255 - 10 * RADIUS) / 2
            v = isocurv.from_array(a, spacing=(1, 1, 1))
            self.assertEqual(v.shape, a.shape)
            mesh = isocurv.extract(v, iso)
            arrays = isocurv.curvature(mesh, volume=v)
            h = np.median(arrays["H"])
            self.assertAlmostEqual(h, 1 / RADIUS, delta=0.05 / RADIUS, msg=str(dtype))
            self.assertEqual(arrays["k1"].shape, (len(mesh.vertices),))
            self.assertEqual(arrays["dir1"].shape, (len(mesh.vertices), 3))
            self.assertEqual(arrays["dcurv"].shape, (len(mesh.vertices), 4))
            self.assertTrue(np.all(arrays["k1"] >= arrays["k2"]))

    def test_spacing_and_origin_place_the_surface_in_world_space(self):
        v = isocurv.from_array(ball(np.float32), spacing=(2, 2, 2), origin=(100, 0, -5))
        mesh = isocurv.extract(v, 255 - 10 * RADIUS)
        centre = mesh.vertices.mean(axis=0)
        np.testing.assert_allclose(centre, [100 + 2 * 15.5, 2 * 16.5, -5 + 2 * 17.5], atol=0.1)
        h = np.median(isocurv.curvature(mesh, v)["H"])
        self.assertAlmostEqual(h, 1 / (2 * RADIUS), delta=0.05 / RADIUS)

    def test_inside_below_flips_the_object(self):
        a = ball(np.float32)
        above = isocurv.curvature(isocurv.extract(isocurv.from_array(a), 135))["H"]
        below = isocurv.curvature(isocurv.extract(isocurv.from_array(-a, inside="below"), -135))["H"]
        self.assertGreater(np.median(above), 0)
        self.assertGreater(np.median(below), 0)

    def test_bad_arrays_raise_type_or_value_errors_naming_the_argument(self):
        with self.assertRaisesRegex(ValueError, "array"):
            isocurv.from_array(np.zeros((4, 4)))
        with self.assertRaisesRegex(ValueError, "contiguous"):
            isocurv.from_array(np.zeros((4, 4, 8))[:, :, ::2])
        with self.assertRaisesRegex(TypeError, "array"):
            isocurv.from_array(np.zeros((4, 4, 4), dtype=np.complex64))
        with self.assertRaisesRegex(TypeError, "array"):
            isocurv.from_array(np.zeros((4, 4, 4), dtype=">f4"))
        with self.assertRaisesRegex(ValueError, "spacing"):
            isocurv.from_array(np.zeros((4, 4, 4), np.float32), spacing=(1, 0, 1))
        with self.assertRaisesRegex(ValueError, "inside"):
            isocurv.from_array(np.zeros((4, 4, 4), np.float32), inside="left")
        v = isocurv.from_array(ball(np.float32))
        with self.assertRaisesRegex(ValueError, "device"):
            isocurv.extract(v, 100, device="gpu9")
        with self.assertRaisesRegex(ValueError, "snap"):
            isocurv.extract(v, 100, snap=2)

    def test_bad_files_raise_isocurv_error_with_the_one_line_message(self):
        with self.assertRaises(isocurv.Error) as e:
            isocurv.load("/nonexistent/ct.nrrd")
        self.assertIn("/nonexistent/ct.nrrd", str(e.exception))
        self.assertNotIn("\n", str(e.exception))
        with tempfile.TemporaryDirectory() as d:
            bad = os.path.join(d, "bad.vdb")
            with open(bad, "wb") as f:
                f.write(b"not a vdb")
            with self.assertRaises(isocurv.Error):
                isocurv.load(bad)
            with self.assertRaises(isocurv.Error):
                isocurv.read_mesh(os.path.join(d, "missing.ply"))

    def test_a_zarr_store_loads_and_its_errors_name_the_arguments(self):
        # A Zarr v2 store of one uncompressed chunk, x fastest (C order of z, y, x).
        data = np.zeros((6, 7, 8), dtype="<u2")
        data[2:4, 2:5, 3:6] = 1000
        with tempfile.TemporaryDirectory() as d:
            store = os.path.join(d, "ball.zarr")
            os.makedirs(store)
            with open(os.path.join(store, ".zarray"), "w") as f:
                f.write('{"zarr_format": 2, "shape": [6, 7, 8], "chunks": [6, 7, 8], '
                        '"dtype": "<u2", "compressor": null, "fill_value": 0, "order": "C", '
                        '"filters": null}')
            with open(os.path.join(store, "0.0.0"), "wb") as f:
                f.write(data.tobytes())
            v = isocurv.load(store)
            self.assertEqual(v.to_numpy().shape, (6, 7, 8))
            self.assertEqual(float(v.to_numpy().max()), 1000.0)
            with self.assertRaises(isocurv.Error) as e:
                isocurv.load(store, channel=1)
            self.assertIn("channel", str(e.exception))
            self.assertNotIn("--channel", str(e.exception))


class Meshes(unittest.TestCase):
    def test_vertices_and_triangles_are_views_without_a_copy(self):
        mesh = isocurv.extract(isocurv.from_array(ball(np.uint8)), 135)
        vtx, tri = mesh.vertices, mesh.triangles
        self.assertEqual((vtx.dtype, vtx.shape[1]), (np.float32, 3))
        self.assertEqual((tri.dtype, tri.shape[1]), (np.uint32, 3))
        self.assertFalse(vtx.flags["OWNDATA"])
        self.assertTrue(np.shares_memory(vtx, mesh.vertices))  # the same memory each time
        del mesh  # the views keep the mesh alive
        self.assertTrue(np.isfinite(vtx).all())
        self.assertLess(int(tri.max()), len(vtx))

    def test_check_reports_a_closed_sphere(self):
        mesh = isocurv.extract(isocurv.from_array(ball(np.float32)), 135)
        c = isocurv.check(mesh)
        self.assertTrue(c["watertight"])
        self.assertEqual(c["duplicate_vertices"], 0)
        self.assertEqual(c["euler_characteristic"], 2)
        self.assertEqual(c["genus"], 0)
        self.assertGreater(c["closed_signed_volume"], 0)
        opened = isocurv.Mesh(mesh.vertices, mesh.triangles[1:])
        self.assertFalse(isocurv.check(opened)["watertight"])
        self.assertIsNone(isocurv.check(opened)["genus"])

    def test_mesh_from_arrays_checks_shapes_and_indices(self):
        with self.assertRaisesRegex(ValueError, "vertices"):
            isocurv.Mesh(np.zeros((3, 2)), np.zeros((1, 3), int))
        with self.assertRaisesRegex(ValueError, "triangles"):
            isocurv.Mesh(np.zeros((3, 3)), np.array([[0, 1, 3]]))
        with self.assertRaisesRegex(TypeError, "vertices"):
            isocurv.Mesh("abc", np.zeros((1, 3), int))

    def test_write_and_read_back_every_array(self):
        v = isocurv.from_array(ball(np.uint16))
        mesh = isocurv.extract(v, 135)
        arrays = isocurv.curvature(mesh, v)
        with tempfile.TemporaryDirectory() as d:
            for name, compress in (("a.vtp", "lz4"), ("b.vtp", "zlib:9"), ("c.ply", "none")):
                path = os.path.join(d, name)
                isocurv.write_mesh(path, mesh, arrays, compress=compress)
                back, back_arrays = isocurv.read_mesh(path)
                np.testing.assert_array_equal(back.vertices, mesh.vertices)
                np.testing.assert_array_equal(back.triangles, mesh.triangles)
                for key in ("k1", "k2", "H", "K", "dir1", "dcurv", "AO"):
                    np.testing.assert_array_equal(back_arrays[key], arrays[key], err_msg=name + " " + key)
            with self.assertRaisesRegex(ValueError, "k1"):
                isocurv.write_mesh(os.path.join(d, "x.vtp"), mesh, {"k1": arrays["k1"][:-1]})
            with self.assertRaisesRegex(ValueError, "curv"):
                isocurv.write_mesh(os.path.join(d, "x.vtp"), mesh, {"curv": arrays["k1"][:-1]})
            with self.assertRaises(isocurv.Error):
                isocurv.write_mesh(os.path.join(d, "x.vtp"), mesh, compress="gzip")
            # Other scalar arrays (the volume estimator's Scale, features' arrays) go along.
            isocurv.write_mesh(os.path.join(d, "e.vtp"), mesh, {"curv": arrays["k1"], "Scale": arrays["Scale"]})
            _, extra = isocurv.read_mesh(os.path.join(d, "e.vtp"))
            np.testing.assert_array_equal(extra["curv"], arrays["k1"])
            np.testing.assert_array_equal(extra["Scale"], arrays["Scale"])
            self.assertEqual(sorted(os.listdir(d)), ["a.vtp", "b.vtp", "c.ply", "e.vtp"])
            # Library messages name this module's arguments, not the command line's flags.
            with self.assertRaisesRegex(isocurv.Error, "^compress 'gzip'"):
                isocurv.write_mesh(os.path.join(d, "x.vtp"), mesh, compress="gzip")
            # .obj keeps the geometry and Normals: the rest is named, not dropped silently.
            with self.assertWarnsRegex(UserWarning, "not written: .*k1"):
                isocurv.write_mesh(os.path.join(d, "g.obj"), mesh, arrays)
            with warnings.catch_warnings():
                warnings.simplefilter("error")
                isocurv.write_mesh(os.path.join(d, "h.obj"), mesh, {"Normals": arrays["Normals"]})

    @unittest.skipUnless(os.path.exists(TORUS), "bundled datasets not built")
    def test_same_mesh_and_curvature_as_the_command_line(self):
        exe = os.path.join(BUILD, "app", "isocurv")
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "torus.vtp")
            subprocess.run([exe, "curvature", TORUS, "-o", out, "--quiet"], check=True)
            cli_mesh, cli_arrays = isocurv.read_mesh(out)
        v = isocurv.load(TORUS)
        mesh = isocurv.extract(v)
        arrays = isocurv.curvature(mesh, v)
        np.testing.assert_array_equal(mesh.vertices, cli_mesh.vertices)
        np.testing.assert_array_equal(mesh.triangles, cli_mesh.triangles)
        for key in ("k1", "k2", "H", "K", "Normals", "AO"):
            np.testing.assert_array_equal(arrays[key], cli_arrays[key], err_msg=key)

    def test_reference_device_agrees_to_float_precision(self):
        v = isocurv.from_array(ball(np.float32))
        ours = isocurv.curvature(isocurv.extract(v, 135), v)
        mesh_ref = isocurv.extract(v, 135, device="reference")
        ref = isocurv.curvature(mesh_ref, v, device="reference")
        self.assertEqual(len(ref["H"]), len(ours["H"]))
        self.assertAlmostEqual(float(np.median(ref["H"])), float(np.median(ours["H"])), places=4)

    def test_threads_may_call_concurrently(self):
        v = isocurv.from_array(ball(np.float32))
        expected = isocurv.curvature(isocurv.extract(v, 135), v)["H"]
        results = []

        def work():
            results.append(isocurv.curvature(isocurv.extract(v, 135), v)["H"])

        threads = [threading.Thread(target=work) for _ in range(3)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        self.assertEqual(len(results), 3)
        for r in results:
            np.testing.assert_array_equal(r, expected)


class Estimators(unittest.TestCase):
    """curvature(estimator=, scale=, normals=, iso=) follow the CLI's --estimator rules."""

    def setUp(self):
        self.v = isocurv.from_array(ball(np.float32))
        self.mesh = isocurv.extract(self.v, 255 - 10 * RADIUS)

    def test_names_are_the_clis(self):
        names = isocurv.estimator_names()
        self.assertEqual(names[:2], ["rusinkiewicz", "volume"])
        self.assertIn("batagelo", names)

    def test_default_is_volume_with_a_volume_else_rusinkiewicz(self):
        a = isocurv.curvature(self.mesh, self.v)
        b = isocurv.curvature(self.mesh, self.v, estimator="volume")
        self.assertIsInstance(a, dict)
        self.assertEqual(sorted(a), sorted(b))
        for key in a:
            np.testing.assert_array_equal(a[key], b[key], err_msg=key)
        self.assertEqual(a.report["estimator"], "volume")
        self.assertEqual(a["Scale"].shape, (len(self.mesh.vertices),))
        self.assertGreater(a.report["parameters"]["ao_scale"], 0)
        # Asking for normals means a mesh estimator: Rusinkiewicz's, as the CLI does.
        n = isocurv.curvature(self.mesh, self.v, normals="volume")
        self.assertEqual(n.report["estimator"], "rusinkiewicz")
        self.assertEqual(n.report["normals"], "volume")
        self.assertEqual(n.report["normal_fallbacks"]["opposed"], 0)
        alone = isocurv.curvature(self.mesh)
        self.assertEqual((alone.report["estimator"], alone.report["normals"]), ("rusinkiewicz", "mesh"))

    def test_volume_estimator_on_a_sphere(self):
        self.assertEqual(self.mesh.isovalue, 255 - 10 * RADIUS)
        for dtype, tol in ((np.float32, 0.02), (np.uint8, 0.05)):
            v = isocurv.from_array(ball(dtype))
            mesh = isocurv.extract(v, 255 - 10 * RADIUS)
            a = isocurv.curvature(mesh, v, estimator="volume")
            for q in (1, 50, 99):
                self.assertAlmostEqual(np.percentile(a["H"], q) * RADIUS, 1, delta=tol, msg=str(dtype))
                self.assertAlmostEqual(np.percentile(a["K"], q) * RADIUS**2, 1, delta=2 * tol, msg=str(dtype))
            r = a.report
            self.assertEqual((r["estimator"], r["chosen"]["scale"], r["unreliable"]), ("volume", "auto", 0))
            self.assertGreater(r["parameters"]["scale"], 0.5)
            self.assertEqual(r["normals"], "volume estimator")
            self.assertEqual(a["Unreliable"].shape, (len(mesh.vertices),))
        given = isocurv.curvature(self.mesh, self.v, estimator="volume", scale=1.5)
        self.assertEqual(given.report["parameters"]["scale"], 1.5)
        self.assertEqual(given.report["chosen"]["scale"], "given")
        self.assertAlmostEqual(np.median(given["H"]) * RADIUS, 1, delta=0.03)
        auto = isocurv.curvature(self.mesh, self.v, estimator="volume", scale="auto")
        self.assertEqual(auto.report["chosen"]["scale"], "auto")
        # A mesh without an isovalue (not from extract) takes iso=.
        bare = isocurv.Mesh(self.mesh.vertices, self.mesh.triangles)
        self.assertIsNone(bare.isovalue)
        with_iso = isocurv.curvature(bare, self.v, estimator="volume", iso=255 - 10 * RADIUS)
        np.testing.assert_array_equal(with_iso["H"], auto["H"])

    def test_every_mesh_estimator_gives_the_sphere(self):
        for name in isocurv.estimator_names():
            if name == "volume":
                continue
            a = isocurv.curvature(self.mesh, estimator=name)
            self.assertEqual(a.report["estimator"], name)
            self.assertAlmostEqual(np.median(a["H"]) * RADIUS, 1, delta=0.05, msg=name)
            self.assertEqual(a.report["unreliable"], int(a["Unreliable"].sum()) if "Unreliable" in a else 0)
        area = isocurv.curvature(self.mesh, estimator="batagelo", normals="face-average")
        self.assertEqual(area.report["normals"], "face-average")
        self.assertFalse(np.array_equal(area["H"], isocurv.curvature(self.mesh, estimator="batagelo")["H"]))

    def test_ao_method_is_the_clis_and_follows_its_rules(self):
        m, v = self.mesh, self.v
        griffin = isocurv.curvature(m)
        np.testing.assert_array_equal(isocurv.curvature(m, ao_method="griffin")["AO"], griffin["AO"])
        for method in ("griffin-exact", "hattori", "prantl"):
            a = isocurv.curvature(m, ao_method=method)
            self.assertFalse(np.array_equal(a["AO"], griffin["AO"]), msg=method)
            np.testing.assert_array_equal(a["H"], griffin["H"], err_msg=method)
        # the cavity (inside below): concave, where hattori's two means differ
        cavity = isocurv.extract(isocurv.from_array(ball(np.float32), inside="below"), 135)
        half = isocurv.curvature(cavity, ao_method="hattori", hattori_half=True)
        self.assertFalse(np.array_equal(half["AO"], isocurv.curvature(cavity, ao_method="hattori")["AO"]))
        ray = isocurv.curvature(m, v, ao_method="raycast")
        self.assertTrue(((ray["AO"] >= 0) & (ray["AO"] <= 1)).all())
        with self.assertRaisesRegex(ValueError, "^ao_method: the ray casts .* need the volume argument"):
            isocurv.curvature(m, ao_method="raycast")
        with self.assertRaisesRegex(ValueError, "^hattori_half: applies to ao_method='hattori' only"):
            isocurv.curvature(m, hattori_half=True)
        with self.assertRaisesRegex(ValueError, "^ao_method: expected one of 'griffin', .*, not 'guess'"):
            isocurv.curvature(m, ao_method="guess")
        with self.assertRaisesRegex(TypeError, "^ao_method"):
            isocurv.curvature(m, ao_method=1)

    def test_bad_combinations_raise_value_errors_naming_the_argument(self):
        m, v = self.mesh, self.v
        with self.assertRaisesRegex(ValueError, "^scale: applies to estimator='volume' only$"):
            isocurv.curvature(m, v, estimator="rusinkiewicz", scale=1.0)
        with self.assertRaisesRegex(ValueError, "^estimator: 'volume' needs the volume argument"):
            isocurv.curvature(m, estimator="volume")
        with self.assertRaisesRegex(ValueError, "^normals: applies to the mesh estimators"):
            isocurv.curvature(m, v, estimator="volume", normals="mesh")
        with self.assertRaisesRegex(ValueError, "^estimator: expected one of rusinkiewicz, volume, .*'vtk'"):
            isocurv.curvature(m, estimator="vtk")
        with self.assertRaisesRegex(TypeError, "^estimator"):
            isocurv.curvature(m, estimator=3)
        for bad in (-1.0, 0, float("nan"), "big"):
            with self.assertRaisesRegex(ValueError, "^scale: a positive number"):
                isocurv.curvature(m, v, estimator="volume", scale=bad)
        with self.assertRaisesRegex(ValueError, "^normals: expected"):
            isocurv.curvature(m, normals="gradient")
        with self.assertRaisesRegex(ValueError, "^iso: estimator='volume' needs the mesh's isovalue"):
            isocurv.curvature(isocurv.Mesh(m.vertices, m.triangles), v, estimator="volume")
        with self.assertRaisesRegex(ValueError, "^iso: applies to estimator='volume' only"):
            isocurv.curvature(m, v, estimator="rusinkiewicz", iso=135)
        with self.assertRaisesRegex(ValueError, "^ao_scale: a positive number"):
            isocurv.curvature(m, ao_scale=-1)
        with self.assertRaisesRegex(TypeError, "^ao_scale"):
            isocurv.curvature(m, ao_scale="wide")


class Topologies(unittest.TestCase):
    """isocurv.Topology: prepared once, bit-identical to a cold curvature() of each frame."""

    def setUp(self):
        self.mesh = isocurv.extract(isocurv.from_array(ball(np.float32)), 135)
        p = self.mesh.vertices.astype(np.float64)
        centre = p.mean(axis=0)
        self.frames = [
            self.mesh.vertices.copy(),
            (centre + (p - centre) * [1.5, 1.0, 0.7]).astype(np.float32),  # an ellipsoid
            (p + 0.3 * np.sin(p[:, [1, 2, 0]] / 3)).astype(np.float64),  # float64: converted
        ]

    def test_frames_are_bit_identical_to_cold_calls(self):
        topo = isocurv.Topology(self.mesh)
        self.assertEqual((topo.vertex_count, topo.triangle_count), (len(self.mesh.vertices), len(self.mesh.triangles)))
        for estimator in ("rusinkiewicz", "batagelo", "prantl3", "prantl2"):
            for normals in (None, "area"):
                for i, frame in enumerate(self.frames):
                    warm = topo.curvature(frame, estimator=estimator, normals=normals)
                    cold = isocurv.curvature(isocurv.Mesh(frame, self.mesh.triangles), estimator=estimator, normals=normals)
                    msg = "%s %s frame %d" % (estimator, normals, i)
                    self.assertEqual(sorted(warm), sorted(cold), msg)
                    for key in cold:
                        np.testing.assert_array_equal(warm[key], cold[key], err_msg=msg + " " + key)
                    self.assertEqual(warm.report["estimator"], cold.report["estimator"])
                    self.assertEqual(warm.report["parameters"], cold.report["parameters"])
                    self.assertEqual(warm.report["unreliable"], cold.report["unreliable"])
        # The frames differ: the ellipsoid's H spreads where the sphere's does not.
        h = [np.ptp(topo.curvature(f)["H"]) for f in self.frames[:2]]
        self.assertGreater(h[1], 3 * h[0])

    def test_threads_may_share_a_topology(self):
        topo = isocurv.Topology(self.mesh)
        cold = [isocurv.curvature(isocurv.Mesh(f, self.mesh.triangles))["H"] for f in self.frames]
        results = {}

        def work(i):
            for _ in range(3):
                results.setdefault(i, []).append(topo.curvature(self.frames[i])["H"])

        threads = [threading.Thread(target=work, args=(i,)) for i in range(len(self.frames))]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for i, hs in results.items():
            self.assertEqual(len(hs), 3)
            for h in hs:
                np.testing.assert_array_equal(h, cold[i], err_msg="frame %d" % i)

    def test_bad_arguments(self):
        topo = isocurv.Topology(self.mesh)
        with self.assertRaisesRegex(ValueError, "^positions: expected shape"):
            topo.curvature(self.frames[0][1:])
        with self.assertRaisesRegex(TypeError, "^positions"):
            topo.curvature("abc")
        with self.assertRaisesRegex(ValueError, "^estimator: Topology runs"):
            topo.curvature(self.frames[0], estimator="quadric")
        with self.assertRaisesRegex(ValueError, "^normals"):
            topo.curvature(self.frames[0], normals="volume")
        with self.assertRaisesRegex(ValueError, "^device"):
            isocurv.Topology(self.mesh, device="reference")
        with self.assertRaisesRegex(ValueError, "^mesh: has no triangles"):
            isocurv.Topology(isocurv.Mesh(np.zeros((3, 3)), np.zeros((0, 3), int)))
        bad = self.frames[0].copy()
        bad[0, 0] = np.nan
        with self.assertRaises(isocurv.Error):
            topo.curvature(bad)


class Arguments(unittest.TestCase):
    """Paths as str or pathlib.Path, wrong types naming the argument, the CLI's isovalue rule."""

    def setUp(self):
        self.v = isocurv.from_array(ball(np.float32))
        self.mesh = isocurv.extract(self.v, 135)

    def test_pathlib_paths_are_accepted_everywhere(self):
        with tempfile.TemporaryDirectory() as d:
            d = pathlib.Path(d)
            arrays = isocurv.curvature(self.mesh, self.v)
            isocurv.write_mesh(d / "m.vtp", self.mesh, arrays)
            back, back_arrays = isocurv.read_mesh(d / "m.vtp")
            np.testing.assert_array_equal(back.vertices, self.mesh.vertices)
            np.testing.assert_array_equal(back_arrays["H"], arrays["H"])
            isocurv.lines(self.mesh, arrays=arrays, output=d / "l.vtp")
            isocurv.lines(self.mesh, arrays=arrays, output=d / "l.svg")
            isocurv.screen(self.v, iso=135, size=(32, 24), raw=d / "s.vti")
            self.assertEqual(sorted(os.listdir(d)), ["l.svg", "l.vtp", "m.vtp", "s.vti"])
            if os.path.exists(TORUS):
                self.assertEqual(isocurv.load(pathlib.Path(TORUS)).shape, isocurv.load(TORUS).shape)
            with self.assertRaises(isocurv.Error):
                isocurv.load(d / "missing.nrrd")
        with self.assertRaisesRegex(TypeError, "^path: expected a file name"):
            isocurv.load(3)
        with self.assertRaisesRegex(TypeError, "^path: expected a file name"):
            isocurv.read_mesh(None)
        with self.assertRaisesRegex(TypeError, "^output: expected a file name"):
            isocurv.lines(self.mesh, output=1.5)

    def test_a_wrong_type_names_the_argument(self):
        m, v = self.mesh, self.v
        with self.assertRaisesRegex(TypeError, r"^volume: expected an isocurv\.Volume .*, not str$"):
            isocurv.extract("ct.nrrd")
        with self.assertRaisesRegex(TypeError, r"^volume: expected an isocurv\.Volume"):
            isocurv.curvature(m, "ct.nrrd")
        with self.assertRaisesRegex(TypeError, r"^volume: expected an isocurv\.Volume"):
            isocurv.curvature(m, volume=m)
        with self.assertRaisesRegex(TypeError, r"^mesh: expected an isocurv\.Mesh .*, not isocurv\.Volume$"):
            isocurv.curvature(v)
        with self.assertRaisesRegex(TypeError, r"^mesh: expected an isocurv\.Mesh"):
            isocurv.write_mesh("x.vtp", v)
        with self.assertRaisesRegex(TypeError, r"^mesh: expected an isocurv\.Mesh"):
            isocurv.check(None)
        with self.assertRaisesRegex(TypeError, r"^mesh: expected an isocurv\.Mesh"):
            isocurv.Topology(v)
        with self.assertRaisesRegex(TypeError, r"^mesh: expected an isocurv\.Mesh"):
            isocurv.features(v, radius=2)
        with self.assertRaisesRegex(TypeError, r"^volume_or_mesh: expected an isocurv\.Volume"):
            isocurv.screen("ct.nrrd")
        with self.assertRaisesRegex(TypeError, "^iso: expected a number"):
            isocurv.extract(v, iso="high")
        # Plain-typed arguments get pybind11's message, whose signature names each argument.
        with self.assertRaisesRegex(TypeError, r"cap: bool"):
            isocurv.extract(v, 135, cap="yes")
        # The signatures show the types.
        self.assertIn("volume: isocurv.Volume", isocurv.extract.__doc__)
        self.assertIn("mesh: isocurv.Mesh, volume: isocurv.Volume = None", isocurv.curvature.__doc__)
        self.assertIn("path: str | os.PathLike", isocurv.load.__doc__)

    def test_extract_refuses_an_isovalue_outside_the_range_as_the_cli_does(self):
        lo, hi = self.v.value_range
        self.assertEqual((lo, "%g" % hi), (0, "246.34"))
        with self.assertRaisesRegex(ValueError, r"^iso: isovalue 300 is outside the value range \[0, 246.34\]$"):
            isocurv.extract(self.v, 300)
        with self.assertRaisesRegex(ValueError, r"^iso: isovalue -1 is outside the value range"):
            isocurv.extract(self.v, -1)
        with self.assertRaisesRegex(ValueError, r"^iso: isovalue 246.34 equals the maximum value, so there is no surface"):
            isocurv.extract(self.v, hi)
        self.assertGreater(len(isocurv.extract(self.v, lo).vertices), 0)  # every voxel above 0 is inside
        below = isocurv.from_array(-ball(np.float32), inside="below")
        with self.assertRaisesRegex(ValueError, r"^iso: isovalue -246.34 equals the minimum value"):
            isocurv.extract(below, below.value_range[0])

    @unittest.skipUnless(HAVE_CLI, "command line or bundled datasets not built")
    def test_extract_message_is_the_command_lines(self):
        v = isocurv.load(TORUS)
        for iso in ("5", repr(v.value_range[1])):
            cli = subprocess.run([EXE, "extract", TORUS, "--iso", iso, "-o", os.devnull + ".vtp"],
                                 capture_output=True, text=True)
            self.assertEqual(cli.returncode, 1)
            with self.assertRaises(ValueError) as e:
                isocurv.extract(v, float(iso))
            message = str(e.exception)
            self.assertTrue(message.startswith("iso: "), message)
            self.assertEqual(cli.stderr.strip(), "isocurv: " + TORUS + ": " + message[len("iso: "):])

    def test_curvature_refuses_a_mesh_outside_the_volume(self):
        moved = isocurv.from_array(ball(np.float32), origin=(40, 0, 0))
        with self.assertRaisesRegex(ValueError, r"^mesh: does not lie in the volume: its bounding box .* voxels beyond"):
            isocurv.curvature(self.mesh, moved)
        with self.assertRaisesRegex(ValueError, r"^mesh: does not lie in the volume"):
            isocurv.curvature(self.mesh, moved, normals="volume")
        with self.assertRaisesRegex(ValueError, r"^mesh: does not lie in the volume"):
            isocurv.features(self.mesh, moved, radius=2)
        coarse = isocurv.from_array(ball(np.float32), spacing=(0.5, 0.5, 0.5))
        with self.assertRaisesRegex(ValueError, r"^mesh: does not lie in the volume"):
            isocurv.curvature(self.mesh, coarse)
        # Within a voxel is fine: a small shift, or a capped mesh on the volume's box.
        near = isocurv.from_array(ball(np.float32), origin=(0.5, -0.5, 0))
        isocurv.curvature(self.mesh, near)
        capped = isocurv.extract(self.v, 20, cap=True)
        self.assertGreater(isocurv.check(capped)["area"], 0)
        isocurv.curvature(capped, self.v, cap=True)


class VolumeArrays(unittest.TestCase):
    def test_to_numpy_gives_the_voxels_z_y_x_as_float32(self):
        for dtype in (np.uint8, np.int16, np.float32, np.float64):
            a = ball(dtype)
            v = isocurv.from_array(a, spacing=(1, 2, 3), origin=(5, 6, 7))
            out = v.to_numpy()
            self.assertEqual(out.dtype, np.float32)
            self.assertEqual(out.shape, a.shape)
            self.assertEqual(out.shape, v.shape)
            np.testing.assert_array_equal(out, a.astype(np.float32), err_msg=str(dtype))
        # Not symmetric in its axes: [z, y, x] is the order, not [x, y, z].
        ramp = np.arange(3 * 4 * 5, dtype=np.uint16).reshape(3, 4, 5)
        np.testing.assert_array_equal(isocurv.from_array(ramp).to_numpy(), ramp)
        out = isocurv.from_array(ramp).to_numpy()
        out[0, 0, 0] = 99  # a copy
        self.assertEqual(isocurv.from_array(ramp).to_numpy()[0, 0, 0], 0)

    @unittest.skipUnless(os.path.exists(TORUS), "bundled datasets not built")
    def test_to_numpy_of_a_loaded_file(self):
        v = isocurv.load(TORUS)
        a = v.to_numpy()
        self.assertEqual(a.shape, v.shape)
        # A sparse level set: its active voxels' range, and the background (+-) elsewhere.
        self.assertLessEqual(float(a.min()), v.value_range[0])
        self.assertGreaterEqual(float(a.max()), v.value_range[1])
        # The array's own volume has the same surface.
        again = isocurv.extract(isocurv.from_array(a, spacing=v.spacing, origin=v.origin, inside=v.inside), 0.0)
        direct = isocurv.extract(v, 0.0)
        np.testing.assert_array_equal(again.vertices, direct.vertices)
        self.assertEqual(len(again.triangles), len(direct.triangles))


class Unmeasured(unittest.TestCase):
    def test_unreliable_marks_unmeasured_vertices_with_zeros_not_nan(self):
        # A small ball, and one extra triangle out in the flat zero region where the volume's
        # gradient vanishes: the volume estimator cannot measure its three vertices.
        v = isocurv.from_array(ball(np.float32, scale=20))
        mesh = isocurv.extract(v, 135)
        n = len(mesh.vertices)
        odd = isocurv.Mesh(np.vstack([mesh.vertices, [[2, 2, 2], [3, 2, 2], [2, 3, 2]]]),
                           np.vstack([mesh.triangles, [[n, n + 1, n + 2]]]))
        a = isocurv.curvature(odd, v, estimator="volume", scale=1.0, iso=135)
        self.assertEqual(a["Unreliable"].dtype, np.uint8)
        self.assertEqual(a["Unreliable"].shape, (n + 3,))
        np.testing.assert_array_equal(np.nonzero(a["Unreliable"])[0], [n, n + 1, n + 2])
        self.assertEqual(a.report["unreliable"], 3)
        for key in ("H", "K", "k1", "k2", "dir1", "dcurv", "Normals", "AO"):
            self.assertTrue(np.isfinite(a[key]).all(), key)  # a mask, never NaN
        np.testing.assert_array_equal(a["H"][n:], 0)
        measured = a["Unreliable"] == 0
        self.assertAlmostEqual(float(np.median(a["H"][measured])) * 6, 1, delta=0.05)


class Measure(unittest.TestCase):
    def test_the_ball_and_the_command_line(self):
        v = isocurv.from_array(ball(np.float32))
        mesh = isocurv.extract(v, 255 - 10 * RADIUS)
        m = isocurv.measure(mesh, v)
        self.assertEqual(m["area"].shape, (1,))
        self.assertEqual(m["box"].shape, (1, 6))
        self.assertEqual(int(m["euler_characteristic"][0]), 2)
        self.assertEqual(int(m["genus"][0]), 0)
        self.assertEqual(int(m["closed"][0]), 1)
        # the ball of radius 12 voxels: area and volume within 1%, integral of H within 2%
        self.assertAlmostEqual(float(m["area"][0]) / (4 * np.pi * RADIUS**2), 1, delta=0.01)
        self.assertAlmostEqual(float(m["volume"][0]) / (4 / 3 * np.pi * RADIUS**3), 1, delta=0.01)
        self.assertAlmostEqual(float(m["integral_H"][0]) / (4 * np.pi * RADIUS), 1, delta=0.02)
        self.assertLess(abs(float(m["gauss_bonnet_gap"][0])), 0.02)
        # Given arrays are used as they are: H = 1 everywhere integrates to the measured area
        # (the same patches carry both), and that is what the estimated arrays give too.
        arrays = isocurv.curvature(mesh, v)
        arrays["H"] = np.ones_like(arrays["H"])
        given = isocurv.measure(mesh, arrays=arrays)
        self.assertAlmostEqual(float(given["integral_H"][0]), float(given["area"][0]), places=6)
        self.assertAlmostEqual(float(given["area"][0]) / float(m["area"][0]), 1, delta=1e-3)
        with self.assertRaises(TypeError):
            isocurv.measure("not a mesh")
        with self.assertRaises(ValueError):
            isocurv.measure(mesh, arrays={"H": arrays["H"]})

    @unittest.skipUnless(HAVE_CLI, "needs the built CLI and the bundled torus")
    def test_same_as_the_command_line(self):
        import json
        out = subprocess.run([EXE, "measure", TORUS, "--json", "--quiet"], capture_output=True, text=True, check=True)
        cli = json.loads(out.stdout)["objects"][0]
        v = isocurv.load(TORUS)
        m = isocurv.measure(isocurv.extract(v), v)
        for key in ("area", "volume", "integral_H", "integral_K"):
            self.assertAlmostEqual(float(m[key][0]), cli[key], delta=1e-6 * max(1, abs(cli[key])), msg=key)
        self.assertEqual(int(m["euler_characteristic"][0]), cli["euler_characteristic"])

    def test_labels_each_measure_as_the_object_alone(self):
        n = 40
        z, y, x = np.mgrid[0:n, 0:n, 0:n]
        labels = np.zeros((n, n, n), np.uint8)
        labels[(x - 14) ** 2 + (y - 20) ** 2 + (z - 20) ** 2 < 81] = 4
        labels[((x - 27) ** 2 + (y - 20) ** 2 + (z - 20) ** 2 < 81) & (labels == 0)] = 9  # touching
        v = isocurv.from_array(labels)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            m = isocurv.measure_labels(v, [9, 4, 77])
        self.assertTrue(any("77" in str(w.message) for w in caught))
        self.assertEqual(list(m["label"]), [9, 4])
        self.assertEqual(list(m["euler_characteristic"]), [2, 2])
        self.assertEqual(list(m["closed"]), [1, 1])
        for k, value in enumerate([9, 4]):
            alone = isocurv.from_array((labels == value).astype(np.uint8))
            a = isocurv.measure(isocurv.extract(alone, 0.5), alone)
            for key in ("area", "volume", "integral_H", "integral_K"):
                self.assertAlmostEqual(float(m[key][k]), float(a[key][0]),
                                       delta=1e-4 * abs(float(a[key][0])) + 1e-9, msg=key)
        self.assertEqual(list(isocurv.measure_labels(v)["label"]), [4, 9])
        # numpy integers are labels too; out-of-range ones are a ValueError, not a cast error.
        self.assertEqual(list(isocurv.measure_labels(v, [np.int64(9), np.uint8(4)])["label"]), [9, 4])
        self.assertEqual(list(isocurv.measure_labels(v, np.int32(4))["label"]), [4])
        for bad in (2 ** 70, -(2 ** 70), 2 ** 24):
            with self.assertRaisesRegex(ValueError, "labels: label .* is beyond"):
                isocurv.measure_labels(v, [bad])
        with self.assertRaisesRegex(TypeError, "labels"):
            isocurv.measure_labels(v, [4.0])
        with self.assertRaises(isocurv.Error):
            isocurv.measure_labels(isocurv.from_array(labels.astype(np.float32)))
        with self.assertRaises(ValueError):
            isocurv.measure_labels(v, [5])
        with self.assertRaises(TypeError):
            isocurv.measure_labels(v, "4")

    def test_a_label_that_fills_the_box_is_left_out_with_a_warning(self):
        full = isocurv.from_array(np.full((12, 12, 12), 3, np.uint8))
        with self.assertWarnsRegex(UserWarning, "label 3 has no surface"):
            m = isocurv.measure_labels(full)
        self.assertEqual(len(m["label"]), 0)


def two_touching_balls():
    """A 40^3 uint8 label map: label 4 a ball of radius 9 voxels, label 9 a ball beside it that
    takes the voxels 4 leaves (the two touch)."""
    n = 40
    z, y, x = np.mgrid[0:n, 0:n, 0:n]
    labels = np.zeros((n, n, n), np.uint8)
    labels[(x - 14) ** 2 + (y - 20) ** 2 + (z - 20) ** 2 < 81] = 4
    labels[((x - 27) ** 2 + (y - 20) ** 2 + (z - 20) ** 2 < 81) & (labels == 0)] = 9
    return labels


def sorted_rows(points):
    """The order that sorts the rows of (n, 3) `points` (by x, then y, then z)."""
    return np.lexsort(points.T[::-1])


class LabelSurfaces(unittest.TestCase):
    def setUp(self):
        self.labels = two_touching_balls()
        self.v = isocurv.from_array(self.labels)

    def test_extract_labels_gives_each_labels_own_surface_with_a_label_array(self):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            mesh, arrays = isocurv.extract_labels(self.v, [9, 4, 77])
        self.assertTrue(any("no voxel holds label 77" in str(w.message) for w in caught))
        self.assertEqual(sorted(arrays), ["Label"])
        label = arrays["Label"]
        self.assertEqual((label.dtype, label.shape), (np.float32, (len(mesh.vertices),)))
        self.assertIsNone(mesh.isovalue)  # 0.5 of each label's indicator, not a level of the map
        # In the order asked: label 9's vertices first, then 4's; each triangle within one label.
        self.assertEqual(float(label[0]), 9)
        self.assertEqual(float(label[-1]), 4)
        self.assertEqual(sorted(np.unique(label)), [4, 9])
        tri_labels = label[mesh.triangles]
        self.assertTrue((tri_labels == tri_labels[:, :1]).all())
        for value in (9, 4):
            # The label's surface is its indicator's alone (touching labels each closed).
            alone = isocurv.extract(isocurv.from_array((self.labels == value).astype(np.uint8)), 0.5)
            mine = mesh.vertices[label == value]
            self.assertEqual(len(mine), len(alone.vertices), value)
            np.testing.assert_array_equal(mine[sorted_rows(mine)], alone.vertices[sorted_rows(alone.vertices)])
            part = mesh.triangles[tri_labels[:, 0] == value]
            self.assertEqual(len(part), len(alone.triangles), value)
            self.assertEqual(isocurv.check(isocurv.Mesh(mesh.vertices, part))["euler_characteristic"], 2)
        # None: every label, ascending; numpy integers are labels too.
        every, every_arrays = isocurv.extract_labels(self.v)
        self.assertEqual(list(np.unique(every_arrays["Label"])), [4, 9])
        self.assertEqual(float(every_arrays["Label"][0]), 4)
        one, one_arrays = isocurv.extract_labels(self.v, np.int32(9))
        np.testing.assert_array_equal(one.vertices, mesh.vertices[label == 9])
        self.assertTrue((one_arrays["Label"] == 9).all())

    def test_curvature_labels_estimates_each_label_on_its_own_indicator(self):
        mesh, arrays = isocurv.curvature_labels(self.v)
        extracted, _ = isocurv.extract_labels(self.v)
        np.testing.assert_array_equal(mesh.vertices, extracted.vertices)
        np.testing.assert_array_equal(mesh.triangles, extracted.triangles)
        self.assertIsInstance(arrays, isocurv.CurvatureArrays)
        for key in ("H", "K", "k1", "k2", "Normals", "Scale", "Label"):
            self.assertIn(key, arrays)
        self.assertEqual(arrays.report["estimator"], "volume")
        self.assertEqual(arrays.report["labels"], [4, 9])
        self.assertEqual(len(arrays.report["label_reports"]), 2)
        self.assertEqual(arrays.report["unreliable"], int(arrays["Unreliable"].sum()))
        self.assertEqual(arrays.report["unreliable"],
                         sum(r["unreliable"] for r in arrays.report["label_reports"]))
        for value in (4, 9):
            alone_v = isocurv.from_array((self.labels == value).astype(np.uint8))
            alone = isocurv.extract(alone_v, 0.5)
            expected = isocurv.curvature(alone, alone_v)
            sel = arrays["Label"] == value
            mine, theirs = sorted_rows(mesh.vertices[sel]), sorted_rows(alone.vertices)
            # The same estimate on the label's cut-out as on the whole indicator (to float rounding).
            np.testing.assert_allclose(arrays["H"][sel][mine], expected["H"][theirs], atol=1e-5, err_msg=str(value))
            self.assertAlmostEqual(float(np.median(arrays["H"][sel])) * 9, 1, delta=0.1)
        # Each label sees only itself: the map's own surface at 0.5 wraps both balls in one, with
        # a saddle-shaped neck where they touch (a 5th percentile of H below 0 there).
        self.assertGreater(float(np.percentile(arrays["H"], 5)), 0)
        rus, rus_arrays = isocurv.curvature_labels(self.v, [9], estimator="rusinkiewicz")
        self.assertEqual(rus_arrays.report["estimator"], "rusinkiewicz")
        self.assertNotIn("Scale", rus_arrays)

    def test_bad_arguments_raise_naming_the_python_argument(self):
        v = self.v
        for function in (isocurv.extract_labels, isocurv.curvature_labels):
            with self.assertRaisesRegex(ValueError, r"^labels: none of the labels given is in the volume \(it holds 2 labels, from 4 to 9\)"):
                function(v, [5])
            for bad in (2 ** 70, 2 ** 24):
                with self.assertRaisesRegex(ValueError, "^labels: label .* is beyond"):
                    function(v, [bad])
            with self.assertRaisesRegex(ValueError, "^labels: label 4 is given twice"):
                function(v, [4, 4])
            with self.assertRaisesRegex(ValueError, "^labels: empty"):
                function(v, [])
            with self.assertRaisesRegex(TypeError, "^labels"):
                function(v, "4")
            with self.assertRaisesRegex(TypeError, "^labels"):
                function(v, [4.0])
            with self.assertRaisesRegex(TypeError, "^volume"):
                function("labels.nrrd")
            with self.assertRaisesRegex(ValueError, "^device"):
                function(v, device="gpu9")
            with self.assertRaises(isocurv.Error):  # a float volume is no label map
                function(isocurv.from_array(self.labels.astype(np.float32)))
            with self.assertRaisesRegex(ValueError, r"^volume: holds no label"):
                function(isocurv.from_array(np.zeros((8, 8, 8), np.uint8)))
            full = isocurv.from_array(np.full((12, 12, 12), 3, np.uint8))
            with self.assertWarnsRegex(UserWarning, "label 3 has no surface"):
                with self.assertRaisesRegex(ValueError, "^labels: no label has a surface"):
                    function(full)
        with self.assertRaisesRegex(ValueError, "^scale: "):
            isocurv.curvature_labels(v, scale=-1)
        with self.assertRaisesRegex(ValueError, "^scale: applies to estimator='volume' only"):
            isocurv.curvature_labels(v, estimator="rusinkiewicz", scale=2)
        with self.assertRaisesRegex(ValueError, "^estimator: expected one of"):
            isocurv.curvature_labels(v, estimator="nope")
        with self.assertRaises(TypeError):  # curvature_labels' options are keywords only
            isocurv.curvature_labels(v, None, "volume")

    @unittest.skipUnless(os.access(EXE, os.X_OK), "needs the built command line")
    def test_same_files_as_the_command_line_bit_for_bit(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "two.nrrd")
            with open(path, "wb") as f:  # anisotropic spacing: the margin follows the smallest
                f.write(b"NRRD0004\ntype: uint8\ndimension: 3\nsizes: 40 40 40\nspacings: 1 1 1.5\n"
                        b"encoding: raw\n\n" + self.labels.tobytes())
            v = isocurv.load(path)
            runs = (("extract", [], isocurv.extract_labels, {}),
                    ("curvature", [], isocurv.curvature_labels, {}),
                    ("curvature", ["--scale", "3"], isocurv.curvature_labels, {"scale": 3}),
                    ("curvature", ["--estimator", "rusinkiewicz"], isocurv.curvature_labels,
                     {"estimator": "rusinkiewicz"}))
            for command, flags, function, kw in runs:
                out = os.path.join(d, "cli.vtp")
                subprocess.run([EXE, command, path, "--label", "9,4", "-o", out, "--quiet"] + flags, check=True)
                cli_mesh, cli_arrays = isocurv.read_mesh(out)
                mesh, arrays = function(v, [9, 4], **kw)
                what = " ".join([command] + flags)
                np.testing.assert_array_equal(mesh.vertices, cli_mesh.vertices, err_msg=what)
                np.testing.assert_array_equal(mesh.triangles, cli_mesh.triangles, err_msg=what)
                self.assertEqual(sorted(arrays), sorted(cli_arrays), what)
                for key in arrays:
                    np.testing.assert_array_equal(arrays[key], cli_arrays[key], err_msg=what + ": " + key)


class Features(unittest.TestCase):
    def setUp(self):
        self.v = isocurv.from_array(ball(np.float32))
        self.mesh = isocurv.extract(self.v, 255 - 10 * RADIUS)

    def test_the_sphere(self):
        f = isocurv.features(self.mesh, self.v, radius=3)
        self.assertIsInstance(f, dict)
        self.assertEqual(sorted(f), ["FeatureBoundary", "H_ii", "K_ii", "LBE", "NSV", "SI_ii", "Vr"])
        n = len(self.mesh.vertices)
        for key in f:
            self.assertEqual(f[key].shape, (n,), key)
        self.assertEqual(f["FeatureBoundary"].dtype, np.uint8)
        self.assertEqual(f["H_ii"].dtype, np.float32)
        self.assertAlmostEqual(float(np.median(f["H_ii"])) * RADIUS, 1, delta=0.05)
        self.assertAlmostEqual(float(np.median(f["LBE"])) * RADIUS**2, 1, delta=0.1)
        self.assertEqual(f.report["radii"], [{"as_given": "3", "world": 3.0}])
        self.assertEqual(f.report["neighbourhoods"], "sampled")
        # A mesh alone: the exact neighbourhoods and the surface form of H_ii; no Vr.
        alone = isocurv.features(self.mesh, radius=["2%", 3.5], features="LBE,H_ii")
        self.assertEqual(sorted(alone), ["FeatureBoundary", "H_ii_r2%", "H_ii_r3.5", "LBE_r2%", "LBE_r3.5"])
        self.assertEqual(alone.report["neighbourhoods"], "exact")
        self.assertAlmostEqual(float(np.median(alone["H_ii_r3.5"])) * RADIUS, 1, delta=0.1)
        # Given curvature arrays are used as they are.
        arrays = isocurv.curvature(self.mesh)
        again = isocurv.features(self.mesh, radius=3, features=["LBE"], arrays=arrays)
        np.testing.assert_array_equal(again["LBE"], isocurv.features(self.mesh, radius=3, features=["LBE"])["LBE"])
        # They write along with the curvature arrays.
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "f.vtp")
            isocurv.write_mesh(path, self.mesh, {**arrays, **again})
            _, back = isocurv.read_mesh(path)
            np.testing.assert_array_equal(back["LBE"], again["LBE"])

    def test_bad_arguments(self):
        m, v = self.mesh, self.v
        with self.assertRaisesRegex(TypeError, "radius"):
            isocurv.features(m, v)  # radius is required
        for bad in (0, -1, "x", "4,", float("nan")):
            with self.assertRaisesRegex(ValueError, "^radius: "):
                isocurv.features(m, v, radius=bad)
        with self.assertRaisesRegex(ValueError, "^features: unknown feature 'curv'"):
            isocurv.features(m, v, radius=2, features="LBE,curv")
        with self.assertRaisesRegex(ValueError, "^features: Vr needs the volume"):
            isocurv.features(m, radius=2, features="Vr")
        with self.assertRaisesRegex(ValueError, "^samples: sampled neighbourhoods"):
            isocurv.features(m, radius=2, samples=64)
        with self.assertRaisesRegex(ValueError, "^samples: 0"):
            isocurv.features(m, v, radius=2, samples=8)
        with self.assertRaisesRegex(ValueError, "^adaptive: applies to sampled"):
            isocurv.features(m, v, radius=2, samples=0, adaptive=True)
        with self.assertRaisesRegex(ValueError, "^arrays: lacks Area"):
            isocurv.features(m, radius=2, arrays={"Normals": isocurv.curvature(m)["Normals"]})
        with self.assertRaisesRegex(ValueError, "^iso: features with a volume needs the mesh's isovalue"):
            isocurv.features(isocurv.Mesh(m.vertices, m.triangles), v, radius=2)

    @unittest.skipUnless(HAVE_CLI, "command line or bundled datasets not built")
    def test_same_arrays_as_the_command_line(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "f.vtp")
            subprocess.run([EXE, "features", TORUS, "--radius", "5%,0.2", "-o", out, "--quiet"], check=True)
            _, cli = isocurv.read_mesh(out)
        v = isocurv.load(TORUS)
        f = isocurv.features(isocurv.extract(v), v, radius="5%,0.2")
        self.assertEqual(len(f), 13)
        for key in f:
            np.testing.assert_array_equal(f[key], cli[key], err_msg=key)


class Lines(unittest.TestCase):
    def setUp(self):
        self.v = isocurv.from_array(ball(np.float32))
        self.mesh = isocurv.extract(self.v, 255 - 10 * RADIUS)

    def test_polylines_points_and_types(self):
        out = isocurv.lines(self.mesh, self.v, lines="contours", view="+z")
        self.assertEqual(out["type_names"], ["contours", "suggestive", "ridges", "valleys"])
        points, offsets = out["points"], out["offsets"]
        self.assertEqual(points.dtype, np.float32)
        self.assertEqual(points.shape[1], 3)
        self.assertEqual(offsets[-1], len(points))
        self.assertEqual(len(out["polylines"]), len(out["type"]))
        self.assertEqual(len(offsets), len(out["type"]) + 1)
        np.testing.assert_array_equal(out["type"], 0)
        for i, line in enumerate(out["polylines"]):
            np.testing.assert_array_equal(line, points[offsets[i]:offsets[i + 1]])
        # The sphere's occluding contour seen along z: a circle of radius ~R around the centre's z
        # axis (a perspective camera sees a little less than the equator).
        everything = np.vstack(out["polylines"])
        r = np.hypot(everything[:, 0] - 15.5, everything[:, 1] - 16.5)
        self.assertAlmostEqual(float(np.median(r)) / RADIUS, 1, delta=0.05)
        self.assertAlmostEqual(out["length"]["contours"] / (2 * np.pi * RADIUS), 1, delta=0.05)
        self.assertEqual(sorted(out["camera"]), ["focal_point", "ortho", "parallel_scale", "position", "view_angle", "view_up"])
        # No triangle hides the contour; the visible lines are nearly all of it.
        seen = isocurv.lines(self.mesh, self.v, lines="contours", view="+z", visible=True)
        self.assertGreater(seen["length"]["contours"], 0.9 * out["length"]["contours"])

    def test_bad_arguments(self):
        m = self.mesh
        with self.assertRaisesRegex(ValueError, "^lines: unknown line type 'edges'"):
            isocurv.lines(m, lines="contours,edges")
        with self.assertRaisesRegex(ValueError, "^view: unknown view"):
            isocurv.lines(m, view="front")
        with self.assertRaisesRegex(ValueError, "^size: "):
            isocurv.lines(m, size=(8, 8))
        with self.assertRaisesRegex(ValueError, "^output: lines writes .vtp"):
            isocurv.lines(m, output="lines.png")
        with self.assertRaisesRegex(TypeError, "^visible: expected True"):
            isocurv.lines(m, visible="yes")
        with self.assertRaisesRegex(ValueError, "^visible: an .svg drawing"):
            isocurv.lines(m, output="lines.svg", visible=False)
        with self.assertRaisesRegex(ValueError, "^suggestive_angle: "):
            isocurv.lines(m, suggestive_angle=90)
        with self.assertRaisesRegex(ValueError, "^arrays: lacks k1"):
            isocurv.lines(m, arrays={"Normals": isocurv.curvature(m)["Normals"]})

    @unittest.skipUnless(HAVE_CLI, "command line or bundled datasets not built")
    def test_same_files_as_the_command_line(self):
        v = isocurv.load(TORUS)
        mesh = isocurv.extract(v)
        with tempfile.TemporaryDirectory() as d:
            for name, extra in (("a.vtp", []), ("b.svg", ["--view", "+x", "--lines", "all"])):
                cli, ours = os.path.join(d, "cli_" + name), os.path.join(d, name)
                subprocess.run([EXE, "lines", TORUS, "-o", cli, "--quiet"] + extra, check=True)
                kw = {"view": "+x", "lines": "all"} if extra else {}
                out = isocurv.lines(mesh, v, output=ours, **kw)
                self.assertTrue(filecmp.cmp(cli, ours, shallow=False), name)
                self.assertGreater(len(out["polylines"]), 0)


class Screen(unittest.TestCase):
    def test_ray_cast_sphere(self):
        v = isocurv.from_array(ball(np.float32))
        s = isocurv.screen(v, iso=255 - 10 * RADIUS, size=(120, 90))
        self.assertEqual(sorted(s), ["H", "K", "Step", "Valid"])
        self.assertEqual(s["H"].shape, (90, 120))  # [rows, columns]
        self.assertEqual((s["H"].dtype, s["Valid"].dtype), (np.float32, np.uint8))
        valid = s["Valid"] == 1
        self.assertGreater(valid.sum(), 500)
        self.assertEqual(s.report["estimated_pixels"], int(valid.sum()))
        self.assertAlmostEqual(float(np.median(s["H"][valid])) * RADIUS, 1, delta=0.01)
        self.assertAlmostEqual(float(np.median(s["K"][valid])) * RADIUS**2, 1, delta=0.02)
        self.assertFalse(valid[0, 0])  # the corners are background, H = 0 there
        self.assertEqual(s["H"][0, 0], 0)
        self.assertEqual(s.report["producer"], "ray cast")
        mellado = isocurv.screen(v, iso=255 - 10 * RADIUS, size=(120, 90), estimator="mellado")
        self.assertNotIn("K", mellado)
        self.assertAlmostEqual(float(np.median(mellado["H"][mellado["Valid"] == 1])) * RADIUS, 1, delta=0.02)
        none = isocurv.screen(v, iso=1000, size=(32, 32))
        self.assertTrue(none.report["empty"])
        self.assertEqual(int(none["Valid"].sum()), 0)

    def test_row_zero_is_the_top(self):
        # Seen from +x (z up): a large ball above a small one; the large one's H is the smaller.
        z, y, x = np.mgrid[0:64, 0:24, 0:24].astype(np.float64)
        big = 10 - np.sqrt((x - 11.5) ** 2 + (y - 11.5) ** 2 + (z - 44) ** 2)
        small = 5 - np.sqrt((x - 11.5) ** 2 + (y - 11.5) ** 2 + (z - 12) ** 2)
        v = isocurv.from_array(np.maximum(big, small).astype(np.float32))
        s = isocurv.screen(v, iso=0, view="+x", size=(64, 128))
        valid = s["Valid"] == 1
        top, bottom = s["H"][:64][valid[:64]], s["H"][64:][valid[64:]]
        self.assertAlmostEqual(float(np.median(top)) * 10, 1, delta=0.05)
        self.assertAlmostEqual(float(np.median(bottom)) * 5, 1, delta=0.05)

    def test_a_mesh_is_rasterised(self):
        v = isocurv.from_array(ball(np.float32))
        mesh = isocurv.extract(v, 255 - 10 * RADIUS)
        s = isocurv.screen(mesh, size=(120, 90), view="+y")
        self.assertEqual(s.report["producer"], "rasterised mesh")
        valid = s["Valid"] == 1
        self.assertGreater(valid.sum(), 500)
        self.assertGreater(float(np.median(s["H"][valid])), 0)

    def test_bad_arguments(self):
        v = isocurv.from_array(ball(np.float32))
        mesh = isocurv.extract(v, 135)
        with self.assertRaisesRegex(ValueError, "^estimator: expected 'prantl' or 'mellado'"):
            isocurv.screen(v, estimator="rusinkiewicz")
        with self.assertRaisesRegex(ValueError, "^iso: applies to a volume"):
            isocurv.screen(mesh, iso=135)
        with self.assertRaisesRegex(ValueError, "^smooth: "):
            isocurv.screen(v, smooth=7)
        with self.assertRaisesRegex(ValueError, "^edges: "):
            isocurv.screen(v, edges=4)
        with self.assertRaisesRegex(ValueError, "^raw: writes a .vti"):
            isocurv.screen(v, raw="x.png")
        with self.assertRaisesRegex(ValueError, "^size: "):
            isocurv.screen(v, size=(9000, 10))


if __name__ == "__main__":
    unittest.main()
