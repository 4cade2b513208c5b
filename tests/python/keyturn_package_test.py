#!/usr/bin/env python3
"""The keyturn package as a numpy and Open3D user meets it (issue 33): clouds through the buffer
protocol, saved and pickled; depth PNGs with the camera file the CLI reads; Open3D clouds in and
out; an N × 3 array's kind said, and a warning when a frame's grid was lost; reads without writes;
Python's own exceptions; negative indexing; training from Python; type stubs that match the module.
The numbers are compared with the CLI or with the same view given another way, never hard-coded.

Run by ctest (tests/CMakeLists.txt) with PYTHONPATH at the built package, KEYTURN the CLI,
KEYTURN_SOURCE the repository and KEYTURN_WORK a scratch folder. Open3D (python3-open3d) is
needed for the Open3D tests: without it they are skipped (exit 77), and under CI=true that fails."""
import ast
import csv
import io
import json
import os
import pickle
import re
import shutil
import subprocess
import sys
import unittest
import warnings
from pathlib import Path

import numpy as np

import keyturn

try:
    import open3d as o3d
except ImportError:  # an optional dependency of the package
    o3d = None

KT = os.environ["KEYTURN"]
SOURCE = Path(os.environ["KEYTURN_SOURCE"])
WORK = Path(os.environ["KEYTURN_WORK"])
FRAME = SOURCE / "data/frames/mosd_learn0.pcd"            # a real Kinect frame, 480 × 640, NaN holes
DEPTH = SOURCE / "data/frames/mosd_learn0_depth.png"      # the same frame as a 16-bit depth PNG
CAMERA = SOURCE / "data/frames/kinect.json"               # its intrinsics, the file `describe --camera` reads
CROP = SOURCE / "tests/data/real/mosd/crop/learn0_o2.pcd"  # a real segmented object cloud
MODEL = SOURCE / "data/models/sim-objects"
CI = os.environ.get("CI") == "true"


def cli(*args):
    return subprocess.run([KT, *map(str, args)], capture_output=True, text=True, check=True)


def cli_row(*args):
    rows = list(csv.reader(io.StringIO(cli("describe", "-q", *args).stdout)))
    return dict(zip(rows[0], rows[1]))


def assert_as_cli(case, d, theirs, what):
    """A Description against the CLI's CSV row: K and every bin, as the CSV writes them (%g)."""
    case.assertEqual(str(d.K), theirs["keypoints"], what)
    bins = [v for k, v in theirs.items() if re.fullmatch(r"[a-z0-9_]+_[0-9]+", k)]
    case.assertEqual(["%.6g" % v for v in d.feature_vector], bins, what)


def needs_open3d(test):
    if o3d is not None:
        return test
    if CI:
        def fail(self):
            self.fail("python3-open3d is not installed (scripts/install-deps.sh installs it); CI=true: no skip")
        return fail
    return unittest.skip("python3-open3d is not installed")(test)


def same_description(case, a, b, what):
    case.assertEqual(a.K, b.K, what)
    case.assertEqual(a.filter["input_kind"], b.filter["input_kind"], what)
    np.testing.assert_array_equal(a.feature_vector, b.feature_vector, err_msg=what)


class Work:
    made = False

    @classmethod
    def make(cls):
        if not cls.made:
            shutil.rmtree(WORK, ignore_errors=True)
            WORK.mkdir(parents=True)
            cli("render", SOURCE / "data/objects/mug__ycb_025_mug.ply", "--angles", "40", "--out", WORK / "mug.pcd")
            cls.made = True
        return WORK


class BufferAndPickle(unittest.TestCase):
    def test_numpy_sees_the_points_without_a_copy(self):
        c = keyturn.load_cloud(FRAME)
        a = np.asarray(c)
        self.assertEqual(a.shape, (480, 640, 3))
        self.assertEqual(a.dtype, np.float32)
        self.assertFalse(a.flags.writeable)
        np.testing.assert_array_equal(a, c.points)  # NaN where the frame has holes, as .points
        self.assertTrue(np.shares_memory(a, np.asarray(c)))  # the cloud's own memory
        crop = keyturn.load_cloud(CROP)
        self.assertEqual(np.asarray(crop).shape, (len(crop), 3))
        np.testing.assert_array_equal(np.asarray(crop), crop.points)
        self.assertEqual(np.asarray(keyturn.Cloud(np.zeros((0, 3)))).shape, (0, 3))

    def test_clouds_and_classifications_pickle(self):
        c = keyturn.load_cloud(Work.make() / "mug.pcd")
        back = pickle.loads(pickle.dumps(c))
        self.assertIsInstance(back, keyturn.Cloud)
        self.assertEqual((back.width, back.height, back.organized), (c.width, c.height, True))
        np.testing.assert_array_equal(back.points, c.points)
        np.testing.assert_array_equal(back.amplitude, c.amplitude)
        np.testing.assert_array_equal(back.confidence, c.confidence)
        same_description(self, keyturn.describe(back, features="kpd2"), keyturn.describe(c, features="kpd2"), "pickled")
        r = keyturn.Model(MODEL).classify(c)
        r2 = pickle.loads(pickle.dumps(r))
        self.assertEqual(r2, r)
        self.assertEqual((r2.cls, r2.probabilities, r2.keypoints), (r.cls, r.probabilities, r.keypoints))


class SaveAndDepth(unittest.TestCase):
    def test_save_cloud_pcd_and_ply_read_back(self):
        work = Work.make()
        c = keyturn.load_cloud(work / "mug.pcd")
        for name, encoding in (("a.pcd", "binary_compressed"), ("b.pcd", "ascii"), ("c.ply", "binary_compressed")):
            keyturn.save_cloud(work / name, c, encoding)
            back = keyturn.load_cloud(work / name)
            if encoding == "ascii":  # text: the numbers to the digits it writes
                self.assertEqual((back.width, back.height), (c.width, c.height), name)
                np.testing.assert_allclose(back.points, c.points, rtol=1e-5, atol=1e-6)
            elif name.endswith(".pcd"):  # PCD keeps the grid; PLY is a list of points
                self.assertEqual((back.width, back.height), (c.width, c.height), name)
                np.testing.assert_array_equal(back.points, c.points)
                np.testing.assert_array_equal(back.amplitude, c.amplitude)
                # The CLI describes the saved file as the module describes the cloud.
                assert_as_cli(self, keyturn.describe(c, features="kpd2"), cli_row(work / name, "--features", "kpd2"),
                              name)
            else:
                valid = np.isfinite(c.points).all(axis=2)
                np.testing.assert_array_equal(back.points, c.points[valid])
        # An array (and an organized one) saves too.
        keyturn.save_cloud(work / "arr.pcd", c.points)
        self.assertEqual(keyturn.load_cloud(work / "arr.pcd").points.shape, (144, 176, 3))
        with self.assertRaises(ValueError) as e:
            keyturn.save_cloud(work / "x.xyz", c)
        self.assertIn(".pcd or .ply", str(e.exception))
        with self.assertRaises(ValueError):
            keyturn.save_cloud(work / "x.pcd", c, "zip")

    def test_depth_png_with_the_cli_camera_file(self):
        c = keyturn.load_cloud(DEPTH, camera=CAMERA)
        self.assertEqual(c.points.shape, (480, 640, 3))
        theirs = cli_row(DEPTH, "--camera", CAMERA)
        assert_as_cli(self, keyturn.describe(c), theirs, "depth PNG")
        # The same intrinsics given as numbers (and as Open3D's camera) read the same cloud.
        k = json.loads(CAMERA.read_text())
        given = [(k["fx"], k["fy"], k["cx"], k["cy"]), {n: k[n] for n in ("fx", "fy", "cx", "cy")}]
        if o3d is not None:
            given.append(o3d.camera.PinholeCameraIntrinsic(640, 480, k["fx"], k["fy"], k["cx"], k["cy"]))
        for intrinsics in given:
            np.testing.assert_array_equal(keyturn.load_cloud(DEPTH, intrinsics=intrinsics).points, c.points)
        np.testing.assert_allclose(keyturn.load_cloud(DEPTH, intrinsics=given[0], depth_scale=0.002).points,
                                   2 * c.points, rtol=1e-6)
        with self.assertRaises(keyturn.Error) as e:  # no camera: refused, naming the file
            keyturn.load_cloud(DEPTH)
        self.assertIn(str(DEPTH), str(e.exception))
        with self.assertRaises(ValueError):
            keyturn.load_cloud(DEPTH, intrinsics=(1, 2, 3))
        with self.assertRaises(FileNotFoundError):
            keyturn.load_cloud(DEPTH, camera=WORK / "no-camera.json")


class InputKind(unittest.TestCase):
    def test_flattened_frame_warns_and_shape_restores_it(self):
        c = keyturn.load_cloud(FRAME)
        by_file = keyturn.describe(FRAME, features="kpd2")
        rows = c.points.reshape(-1, 3)  # the frame as N × 3, NaN rows kept (Open3D's remove_nan_points=False)
        with self.assertWarns(keyturn.OrganizedShapeLostWarning) as w:
            lost = keyturn.describe(rows, features="kpd2")
        self.assertIn("shape=(H, W)", str(w.warning))
        self.assertEqual(lost.filter["input_kind"], "segmented-cloud")
        same_description(self, keyturn.describe(rows, features="kpd2", shape=(480, 640)), by_file, "shape")
        same_description(self, keyturn.describe(rows, features="kpd2", kind="frame", shape=(480, 640)), by_file,
                         "frame")
        # Its valid points only (Open3D's default) still span a scene: the warning again.
        valid = rows[np.isfinite(rows).all(axis=1)]
        with self.assertWarns(keyturn.OrganizedShapeLostWarning):
            keyturn.describe(valid, features="kpd2")
        with self.assertRaises(ValueError) as e:
            keyturn.describe(valid, kind="frame")
        self.assertIn("shape=(H, W)", str(e.exception))
        with self.assertRaises(ValueError):
            keyturn.describe(rows, shape=(481, 640))
        with self.assertRaises(ValueError):
            keyturn.describe(rows, kind="organized")

    def test_said_segmented_or_a_real_crop_does_not_warn(self):
        c = keyturn.load_cloud(FRAME)
        valid = c.points[np.isfinite(c.points).all(axis=2)]
        crop = keyturn.load_cloud(CROP).points
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            a = keyturn.describe(valid, features="kpd2", kind="segmented")
            keyturn.describe(crop, features="kpd2")
            keyturn.describe(FRAME, features="kpd2")
            # kind='segmented' drops an organized array's grid: the numbers of its valid rows.
            same_description(self, keyturn.describe(c, features="kpd2", kind="segmented"), a, "segmented")


class Open3d(unittest.TestCase):
    @needs_open3d
    def test_open3d_round_trip(self):
        # Read with Open3D, describe, convert back.
        pcd = o3d.io.read_point_cloud(str(CROP))
        by_file = keyturn.describe(CROP, features="kpd2")
        d = keyturn.describe(pcd, features="kpd2")
        same_description(self, d, by_file, "legacy")
        tpcd = o3d.t.io.read_point_cloud(str(CROP))
        same_description(self, keyturn.describe(tpcd, features="kpd2"), by_file, "tensor")
        self.assertEqual(keyturn.Model(MODEL).classify(pcd), keyturn.Model(MODEL).classify(CROP))
        back = keyturn.to_open3d(keyturn.from_open3d(pcd))
        self.assertIsInstance(back, o3d.geometry.PointCloud)
        np.testing.assert_array_equal(np.asarray(back.points), np.asarray(pcd.points))
        kp = keyturn.to_open3d(d.keypoints)
        self.assertEqual(len(kp.points), d.K)
        # A frame read by Open3D with its NaN rows, given its grid back, is the frame.
        frame = o3d.io.read_point_cloud(str(FRAME), remove_nan_points=False)
        self.assertEqual(len(frame.points), 480 * 640)
        same_description(self, keyturn.describe(frame, features="kpd2", shape=(480, 640)),
                         keyturn.describe(FRAME, features="kpd2"), "frame")
        with self.assertWarns(keyturn.OrganizedShapeLostWarning):
            keyturn.describe(frame, features="kpd2")

    @needs_open3d
    def test_tensor_clouds_carry_amplitude_and_confidence(self):
        c = keyturn.load_cloud(Work.make() / "mug.pcd")
        t = keyturn.to_open3d(c, tensor=True)
        self.assertIsInstance(t, o3d.t.geometry.PointCloud)
        valid = np.isfinite(c.points).all(axis=2)
        np.testing.assert_array_equal(t.point.positions.numpy(), c.points[valid])
        np.testing.assert_array_equal(t.point["amplitude"].numpy().ravel(), c.amplitude[valid])
        back = keyturn.Cloud(t)
        np.testing.assert_array_equal(back.confidence, c.confidence[valid])
        # Saved from Open3D's cloud, read by Open3D.
        keyturn.save_cloud(WORK / "from-o3d.ply", t)
        self.assertEqual(len(o3d.io.read_point_cloud(str(WORK / "from-o3d.ply")).points), int(valid.sum()))
        with self.assertRaises(TypeError):
            keyturn.describe(o3d.geometry.TriangleMesh())


class DatasetReads(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        work = Work.make()
        cls.ds_path = work / "ds"
        if not cls.ds_path.exists():
            objects = work / "objects.csv"
            objects.write_text("class,instance,mesh\n"
                               f"mug,ycb_025_mug,{SOURCE}/data/objects/mug__ycb_025_mug.ply\n"
                               f"bottle,ycb_006_mustard_bottle,{SOURCE}/data/objects/bottle__ycb_006_mustard_bottle.ply\n")
            cli("simulate", "--objects", objects, "--elevations", "30", "--step", "60", "-q", "--out", cls.ds_path)

    def listing(self):
        return sorted(str(p.relative_to(self.ds_path)) for p in self.ds_path.rglob("*"))

    def test_features_write_nothing_unless_asked(self):
        shutil.rmtree(self.ds_path / ".keyturn", ignore_errors=True)
        before = self.listing()
        ds = keyturn.Dataset(self.ds_path)
        f = ds.features("kpd2+kpa3")
        self.assertIsNone(f.cache)
        self.assertEqual(self.listing(), before)  # a read: nothing written into the dataset
        g = ds.features("kpd2+kpa3", cache=True)  # asked: the cache the CLI reads
        self.assertTrue(Path(g.cache).exists())
        np.testing.assert_array_equal(f.x, g.x)
        self.assertEqual(f.ids, g.ids)
        h = ds.features("kpd2+kpa3")  # now read from the cache, still without writing
        stamp = os.stat(g.cache).st_mtime_ns
        self.assertEqual(h.cache, g.cache)
        np.testing.assert_array_equal(h.x, g.x)
        self.assertEqual(os.stat(g.cache).st_mtime_ns, stamp)

    def test_negative_indexing(self):
        ds = keyturn.Dataset(self.ds_path)
        self.assertEqual(ds[-1].id, ds.views[-1].id)
        self.assertEqual(ds[-len(ds)].id, ds[0].id)
        self.assertEqual([v.id for v in ds], [v.id for v in ds.views])
        with self.assertRaises(IndexError):
            ds[-len(ds) - 1]
        with self.assertRaises(IndexError):
            ds[len(ds)]

    def test_train_in_python_as_the_cli(self):
        ds = keyturn.Dataset(self.ds_path)
        model_dir = WORK / "cli-model"
        cli("train", self.ds_path, "--features", "kpd2+kpa3", "--rounds", "10", "-q", "--out", model_dir)
        ours = keyturn.train(ds.features("kpd2+kpa3"), rounds=10)
        theirs = keyturn.Model(model_dir)
        self.assertEqual(ours.classes, theirs.classes)
        for v in ds.views[::3]:
            self.assertEqual(ours.classify(v.path), theirs.classify(v.path), v.id)
        # Saved, the CLI applies it.
        ours.save(WORK / "py-model")
        out = json.loads(cli("classify", WORK / "py-model", ds[1].path, "--json", "-q").stdout)
        self.assertEqual(out[0]["class"], ours.classify(ds[1].path).cls)
        # On part of the views, and on views from anywhere (features_of).
        part = keyturn.train(ds.features("kpd2+kpa3"), rows=[0, 1, 2, -1], rounds=5)
        self.assertEqual(sorted(part.classes), ["ycb_006_mustard_bottle", "ycb_025_mug"])
        paths = [v.path for v in ds.views]
        f = keyturn.features_of(paths, [v.instance for v in ds.views], "kpd2+kpa3")
        np.testing.assert_array_equal(f.x, ds.features("kpd2+kpa3").x)
        with self.assertRaises(ValueError):
            keyturn.train(f, classifier="svm")
        with self.assertRaises(ValueError):
            keyturn.features_of(paths, ["a"])


class Reconstruct(unittest.TestCase):
    """keyturn.reconstruct (issue 50) against keyturn reconstruct on one simulated turn of the table:
    the same model, numpy arrays Open3D takes, the CLI's folder when asked, the CLI's one-line errors."""

    @classmethod
    def setUpClass(cls):
        cls.ds = WORK / "turn"
        shutil.rmtree(cls.ds, ignore_errors=True)
        cli("capture", "--class", "mug", "--instance", "sim", "--step", "45", "--range", "360", "--settle", "0.005",
            "-q", "--out", cls.ds)
        cli("reconstruct", cls.ds, "--poisson-depth", "7", "-q", "--out", WORK / "cli-rec")
        cls.r = keyturn.reconstruct(cls.ds, poisson_depth=7, out=WORK / "py-rec")

    @staticmethod
    def ply_counts(path):
        header = Path(path).read_bytes().split(b"end_header", 1)[0].decode()
        return {l.split()[1]: int(l.split()[2]) for l in header.splitlines() if l.startswith("element")}

    def test_arrays(self):
        r = self.r
        self.assertEqual(r.vertices.dtype, np.float32)
        self.assertEqual(r.vertices.shape[1], 3)
        self.assertEqual(r.triangles.dtype, np.int32)
        self.assertEqual(r.triangles.shape[1], 3)
        self.assertGreater(len(r.triangles), 1000)
        self.assertTrue(0 <= r.triangles.min() and r.triangles.max() < len(r.vertices))
        self.assertEqual(r.points.shape, r.normals.shape)
        np.testing.assert_allclose(np.linalg.norm(r.normals, axis=1), 1, atol=1e-3)
        self.assertEqual(r.poses.shape, (8, 4, 4))
        for pose in r.poses:
            np.testing.assert_allclose(pose[:3, :3].T @ pose[:3, :3], np.eye(3), atol=1e-6)
        self.assertEqual(len(r.views), 8)
        self.assertEqual(r.model, "turntable")
        self.assertTrue(r.report["refined"])
        # The built-in mug is 117 × 93 × 81 mm (its mesh); its model, seen from 30°, of that order.
        extent = r.vertices.max(axis=0) - r.vertices.min(axis=0)
        self.assertTrue(((extent > 0.05) & (extent < 0.2)).all(), extent)

    def test_as_the_cli(self):
        ours, theirs = self.ply_counts(WORK / "py-rec/mesh.ply"), self.ply_counts(WORK / "cli-rec/mesh.ply")
        self.assertEqual(ours, {"vertex": len(self.r.vertices), "face": len(self.r.triangles)})
        self.assertEqual(self.ply_counts(WORK / "py-rec/cloud.ply")["vertex"], len(self.r.points))
        # The same library on the same views: the same model up to OpenMP's order of sums.
        self.assertAlmostEqual(ours["vertex"] / theirs["vertex"], 1, delta=0.02)
        cli_report = json.loads((WORK / "cli-rec/report.json").read_text())
        self.assertEqual(self.r.report["model"], cli_report["model"])
        self.assertAlmostEqual(self.r.report["residual_median_after_m"], cli_report["residual_median_after_m"], delta=2e-5)
        self.r.save(WORK / "py-rec-again")
        self.assertEqual(self.ply_counts(WORK / "py-rec-again/mesh.ply"), ours)
        self.assertIn("turntable poses refined", self.r.summary)

    def test_options(self):
        kept = keyturn.reconstruct(self.ds, refine=False, poisson_depth=6, elevations=[30], surface="poisson")
        self.assertFalse(kept.report["refined"])
        self.assertEqual(len(kept.views), 8)
        self.assertEqual((kept.surface, kept.report["mesh"]["method"]), ("poisson", "poisson"))
        self.assertEqual(self.r.surface, "tsdf")  # auto: the simulated SR4000's frames are depth frames
        # free_tilt: the support no longer holds the tilt, so the report says no camera was levelled.
        free = keyturn.reconstruct(self.ds, free_tilt=True, surface="poisson", poisson_depth=6)
        self.assertIsNone(free.report["axes"][0]["levelled_by_support_deg"])
        self.assertIsNotNone(self.r.report["axes"][0]["levelled_by_support_deg"])
        with self.assertRaisesRegex(keyturn.Error, "no views|elevation"):
            keyturn.reconstruct(self.ds, elevations=[45])

    def test_errors(self):
        (WORK / "plain").mkdir(exist_ok=True)
        with self.assertRaisesRegex(keyturn.Error, "no poses"):
            keyturn.reconstruct(WORK / "plain")
        with self.assertRaises(FileNotFoundError):
            keyturn.reconstruct(WORK / "nothing-here")
        with self.assertRaises(ValueError):
            keyturn.reconstruct(self.ds, poisson_depth=3)
        with self.assertRaisesRegex(ValueError, "surface must be"):
            keyturn.reconstruct(self.ds, surface="marching")

    @needs_open3d
    def test_open3d(self):
        mesh = keyturn.to_open3d(self.r)
        self.assertEqual(len(mesh.vertices), len(self.r.vertices))
        self.assertEqual(len(mesh.triangles), len(self.r.triangles))
        self.assertTrue(mesh.has_vertex_normals())
        t = keyturn.to_open3d(self.r, tensor=True)
        self.assertEqual(t.vertex["positions"].shape[0], len(self.r.vertices))
        self.assertEqual(len(keyturn.to_open3d(self.r.points).points), len(self.r.points))


class Stubs(unittest.TestCase):
    """keyturn/__init__.pyi against the module: the same public names, members and keywords."""

    @classmethod
    def setUpClass(cls):
        cls.tree = ast.parse((Path(keyturn.__file__).parent / "__init__.pyi").read_text())
        cls.stub = {n.name: n for n in cls.tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}

    def test_shipped_with_py_typed(self):
        self.assertTrue((Path(keyturn.__file__).parent / "py.typed").exists())

    def test_public_names(self):
        public = {n for n in self.stub if not n.startswith("_")}
        self.assertEqual(public, set(keyturn.__all__) - {"__version__"})

    def test_members_and_keywords(self):
        for name, node in self.stub.items():
            if name.startswith("_"):
                continue
            obj = getattr(keyturn, name)
            if isinstance(node, ast.FunctionDef):
                self.assertEqual(self.stub_args(node), self.runtime_args(obj), name)
                continue
            if issubclass(obj, BaseException):
                continue
            members = {m.name: m for m in node.body if isinstance(m, ast.FunctionDef)}
            have = {m for m in dir(obj) if not m.startswith("_")}
            self.assertEqual({m for m in members if not m.startswith("_")}, have, name)
            for m, fn in members.items():
                if m.startswith("__") and m not in ("__init__",):
                    continue
                if not any(isinstance(d, ast.Name) and d.id == "property" for d in fn.decorator_list):
                    self.assertEqual(self.stub_args(fn)[1:], self.runtime_args(getattr(obj, m))[1:], f"{name}.{m}")

    @staticmethod
    def stub_args(fn):
        a = fn.args
        names = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs]
        return names + (["**"] if a.kwarg else [])

    @staticmethod
    def runtime_args(obj):
        """The keywords of pybind11's signature line (or Python's own for a Python function)."""
        import inspect
        try:
            return [p.name if p.kind != p.VAR_KEYWORD else "**" for p in inspect.signature(obj).parameters.values()]
        except (TypeError, ValueError):
            pass
        line = obj.__doc__.splitlines()[0]
        inner = line[line.index("(") + 1:line.rindex(")")]
        names = []
        for part in re.split(r",\s*(?![^\[\]()]*[\])])", inner):
            part = part.strip()
            if not part or part == "*":
                continue
            names.append("**" if part.startswith("**") else part.split(":")[0].strip())
        return names


if __name__ == "__main__":
    # 77 after a skip and no failure: ctest (SKIP_RETURN_CODE 77) counts the run as skipped, not passed.
    result = unittest.main(verbosity=2, exit=False).result
    sys.exit(1 if not result.wasSuccessful() else 77 if result.skipped else 0)
