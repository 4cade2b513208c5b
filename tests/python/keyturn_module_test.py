#!/usr/bin/env python3
"""The keyturn Python module against the command line: the same file and options give the same
numbers as `keyturn describe` and `keyturn classify`; a dataset's feature cache is the one the CLI
fills; bad input raises an exception with keyturn's one-line message.

Run by ctest (tests/CMakeLists.txt) with PYTHONPATH at the built module, KEYTURN the CLI,
KEYTURN_SOURCE the repository and KEYTURN_WORK a scratch folder."""
import csv
import io
import json
import math
import os
import pickle
import shutil
import subprocess
import sys
import threading
import time
import unittest
from pathlib import Path

import numpy as np

import keyturn

KT = os.environ["KEYTURN"]
SOURCE = Path(os.environ["KEYTURN_SOURCE"])
WORK = Path(os.environ["KEYTURN_WORK"])
FRAME = SOURCE / "data/frames/mosd_learn0.pcd"            # a real Kinect frame, shipped
CROP = SOURCE / "tests/data/real/mosd/crop/learn0_o2.pcd"  # a real segmented object cloud
MODEL = SOURCE / "data/models/sim-objects"                  # the built-in model


def cli(*args, check=True):
    return subprocess.run([KT, *map(str, args)], capture_output=True, text=True, check=check)


def csv_rows(text):
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], rows[1:]


def g6(v):
    """A number as describe's CSV writes it (C++ streams at precision 6: %g)."""
    return "%.6g" % v


def row_of(file, d):
    """The CSV row `keyturn describe` writes, made from a Description."""
    removed = {s["name"]: s["removed"] for s in d.filter["steps"]}
    row = [file, str(d.points), str(d.K), "1" if d.low_keypoints else "0", str(d.unreachable_keypoints),
           str(d.unreachable_pairs), g6(d.resolution * 1000.0), d.filter["input_kind"], str(d.input_points)]
    row += [str(removed.get(s, 0)) for s in ("crop", "jump-edges", "support-plane", "cluster", "outliers")]
    row += [g6(d.working["spacing_m"] * 1000.0), str(d.working["removed"]), d.filter["flagged"]]
    return row + [g6(v) for v in d.feature_vector]


class Fixture:
    """A rendered SR4000 view and a small simulated dataset, made once with the CLI."""
    made = False

    @classmethod
    def make(cls):
        if cls.made:
            return
        shutil.rmtree(WORK, ignore_errors=True)
        WORK.mkdir(parents=True)
        cli("render", SOURCE / "data/objects/mug__ycb_025_mug.ply", "--angles", "40", "--out", WORK / "mug.pcd")
        objects = WORK / "objects.csv"
        objects.write_text("class,instance,mesh\n"
                           f"mug,ycb_025_mug,{SOURCE}/data/objects/mug__ycb_025_mug.ply\n"
                           f"bottle,ycb_006_mustard_bottle,{SOURCE}/data/objects/bottle__ycb_006_mustard_bottle.ply\n")
        cli("simulate", "--objects", objects, "--elevations", "30", "--step", "60", "-q", "--out", WORK / "ds")
        cls.made = True


class LoadCloud(unittest.TestCase):
    def test_version_is_the_programs(self):
        self.assertEqual(keyturn.__version__, cli("--version").stdout.strip())

    def test_organized_frame_keeps_its_grid_with_nan(self):
        c = keyturn.load_cloud(FRAME)
        self.assertEqual(c.points.shape, (480, 640, 3))
        self.assertEqual(c.points.dtype, np.float32)
        valid = np.isfinite(c.points).all(axis=2)
        self.assertEqual(int(valid.sum()), c.valid_count)
        self.assertGreater(480 * 640 - c.valid_count, 0)  # the frame has holes: NaN pixels
        self.assertTrue(0.3 < float(np.nanmedian(c.points[..., 2])) < 3.0)  # metres in front of the camera

    def test_segmented_cloud_is_n_by_3(self):
        c = keyturn.load_cloud(str(CROP))
        self.assertEqual(c.points.ndim, 2)
        self.assertEqual(c.points.shape[1], 3)
        self.assertEqual(c.points.shape[0], len(c))

    def test_amplitude_and_confidence_of_a_rendered_view(self):
        Fixture.make()
        c = keyturn.load_cloud(WORK / "mug.pcd")
        self.assertEqual(c.points.shape, (144, 176, 3))
        self.assertEqual(c.amplitude.shape, (144, 176))
        self.assertEqual(c.confidence.shape, (144, 176))
        # Pixels that see the mug or the turntable return light; the rest have no point.
        hit = np.isfinite(c.points).all(axis=2)
        self.assertGreater(float(c.amplitude[hit].mean()), 0.0)
        self.assertIsNone(keyturn.load_cloud(FRAME).amplitude)


class OpenMpWaiting(unittest.TestCase):
    """Importing keyturn makes OpenMP's idle threads wait passively (libgomp's spin count 0), unless
    the user chose a policy: its default spinning slowed reconstruct() on a busy machine."""

    def spin_counts(self, policy):
        env = {k: v for k, v in os.environ.items() if k != "OMP_WAIT_POLICY"}
        env["OMP_DISPLAY_ENV"] = "verbose"
        if policy:
            env["OMP_WAIT_POLICY"] = policy
        out = subprocess.run([sys.executable, "-c", "import keyturn"], env=env, capture_output=True, text=True, check=True)
        return [line.split("'")[1] for line in out.stderr.splitlines() if "GOMP_SPINCOUNT" in line]

    def test_passive_unless_chosen(self):
        self.assertEqual(self.spin_counts(None), ["0"])
        self.assertEqual(self.spin_counts("active"), ["30000000000"])


class Describe(unittest.TestCase):
    def assert_matches_cli(self, path, cli_args, **kwargs):
        header, rows = csv_rows(cli("describe", path, "-q", *cli_args).stdout)
        self.assertEqual(len(rows), 1)
        d = keyturn.describe(path, **kwargs)
        ours = row_of(str(path), d)
        self.assertEqual(len(ours), len(header))
        for name, theirs, mine in zip(header, rows[0], ours):
            self.assertEqual(mine, theirs, f"{path}: column {name}")
        return d

    def test_shipped_frame_default_options_equal_the_cli_row(self):
        d = self.assert_matches_cli(FRAME, [])
        self.assertEqual(d.features, ["kpd2", "kpd3", "kpa3", "gkpd1", "gkpd2", "gkpcd2"])
        self.assertEqual(d.filter["input_kind"], "frame")
        for name, pdf in d.pdfs.items():
            self.assertEqual(pdf.shape, (32,), name)
            self.assertAlmostEqual(float(pdf.sum()), 1.0, places=6, msg=name)
        # The keypoints are rows of the described points.
        self.assertEqual(d.keypoints.shape, (d.K, 3))
        np.testing.assert_array_equal(d.described_points[d.keypoint_indices], d.keypoints)
        self.assertEqual(d.described_points.shape, (d.points, 3))

    def test_options_are_the_cli_flags(self):
        Fixture.make()
        self.assert_matches_cli(WORK / "mug.pcd", ["--features", "kpd2,kpa3,d2", "--bins", "16", "--extent", "0.3",
                                                   "--iss-nms", "3", "--samples-across", "25", "--seed", "3"],
                                features=["kpd2", "kpa3", "d2"], bins=16, extent_m=0.3, iss_nms=3.0,
                                working_samples_across=25, seed=3)
        self.assert_matches_cli(CROP, ["--features", "kpd2", "--no-filter", "--range", "per-view"],
                                features="kpd2", filter=False, range="per-view")

    def test_explain_is_what_the_cli_prints(self):
        theirs = cli("describe", FRAME, "-q", "--explain").stderr
        d = keyturn.describe(str(FRAME), explain=True)
        self.assertIn("support-plane", d.explanation)
        self.assertEqual(d.explanation, theirs)
        self.assertIsNone(keyturn.describe(str(FRAME)).explanation)

    def test_arrays_and_clouds_describe_as_the_file(self):
        c = keyturn.load_cloud(FRAME)
        by_file = keyturn.describe(FRAME, features="kpd2")
        by_cloud = keyturn.describe(c, features="kpd2")
        by_array = keyturn.describe(c.points, features="kpd2")
        by_float64 = keyturn.describe(c.points.astype(np.float64), features="kpd2")
        for other in (by_cloud, by_array, by_float64):
            np.testing.assert_array_equal(other.feature_vector, by_file.feature_vector)
            self.assertEqual(other.K, by_file.K)
        # An unorganized array of the valid points, said to be one, is a segmented cloud: another input kind.
        flat = c.points[np.isfinite(c.points).all(axis=2)]
        self.assertEqual(keyturn.describe(flat, features="kpd2", kind="segmented").filter["input_kind"],
                         "segmented-cloud")

    def test_parameters_are_the_librarys_table(self):
        p = keyturn.parameters()
        self.assertEqual(p["bins"]["default"], 32)
        self.assertEqual(p["extent_m"]["default"], 0.35)
        self.assertIs(p["plane_removal"]["default"], True)
        self.assertEqual(p["low_keypoints"]["default"], 10)
        self.assertIsNone(p["low_keypoints"]["spec_key"])
        self.assertEqual(p["extent_m"]["spec_key"], "extent_m")
        # Every row is a keyword here, under its own name (the CLI spells its flags in app/;
        # test_options_are_the_cli_flags shows both set the same options).
        for name, row in p.items():
            self.assertEqual(set(row), {"default", "help", "spec_key"}, name)
            self.assertIn(name, keyturn.describe.__doc__)

    def test_gil_released_while_describing(self):
        entered, done, inside = threading.Event(), threading.Event(), [0]
        cloud = keyturn.load_cloud(FRAME)  # loaded here: loading a file releases the GIL on its own

        def work():
            entered.set()
            keyturn.describe(cloud, working_samples_across=120)  # dense: ~0.5 s in the chain
            done.set()

        describing = work.__code__.co_firstlineno + 2  # the describe line
        # No thread is made to give up the GIL on a timer during the test: this loop runs while the
        # thread stands on the describe call only if describe itself released the GIL. Holding it, the
        # loop would get it only after describe returned: 0 passes (so measured on a build without the
        # release; with it, 13,700-17,600 in 3 runs). No sleep guesses when the thread is inside.
        interval = sys.getswitchinterval()
        sys.setswitchinterval(30.0)
        try:
            t = threading.Thread(target=work)
            t.start()
            entered.wait()
            while not done.is_set():
                frame = sys._current_frames().get(t.ident)
                if frame is not None and frame.f_code is work.__code__ and frame.f_lineno == describing:
                    inside[0] += 1
                time.sleep(0)  # lets the thread take the GIL back when describe returns
            t.join()
        finally:
            sys.setswitchinterval(interval)
        print("passes while describing:", inside[0], file=sys.stderr)
        self.assertGreater(inside[0], 0)


class Classify(unittest.TestCase):
    def assert_classifies_as_cli(self, model, view):
        theirs = json.loads(cli("classify", model, view, "--json", "-q").stdout)
        self.assertEqual(len(theirs), 1)
        m = keyturn.Model(model)
        for given in (view, keyturn.load_cloud(view), keyturn.load_cloud(view).points):
            ours = m.classify(given)
            self.assertEqual(ours.cls, theirs[0]["class"])
            self.assertEqual(ours.probability, theirs[0]["probability"])
            self.assertEqual(ours.probabilities, theirs[0]["probabilities"])
            self.assertEqual(ours.keypoints, theirs[0]["keypoints"])
        self.assertEqual(list(ours.probabilities), m.classes)
        self.assertAlmostEqual(sum(ours.probabilities.values()), 1.0, places=5)
        return ours

    def test_built_in_model_as_the_cli(self):
        Fixture.make()
        ours = self.assert_classifies_as_cli(MODEL, WORK / "mug.pcd")
        self.assertEqual(ours.cls, "ycb_025_mug")
        m = keyturn.Model(MODEL)
        self.assertEqual(m.blocks, ["kpd2", "kpa3"])
        self.assertEqual(m.inputs, 64)
        self.assertEqual(len(m.classes), 15)

    def test_a_model_trained_by_the_cli(self):
        Fixture.make()
        model = WORK / "model"
        cli("train", WORK / "ds", "--features", "kpd2+kpa3", "--rounds", "10", "-q", "--out", model)
        view = WORK / "ds/bottle/ycb_006_mustard_bottle/e30/a60.0.pcd"
        self.assertTrue(view.exists(), view)
        self.assert_classifies_as_cli(model, view)
        self.assertEqual(sorted(keyturn.Model(model).classes), ["ycb_006_mustard_bottle", "ycb_025_mug"])


    def test_open_set_answers_as_the_cli(self):
        """Issue 34: an open-set model's answer, best class, score and threshold are the CLI's; a view
        too empty to describe is "no object", not an exception."""
        Fixture.make()
        objects = WORK / "objects3.csv"
        objects.write_text("class,instance,mesh\n"
                           f"mug,ycb_025_mug,{SOURCE}/data/objects/mug__ycb_025_mug.ply\n"
                           f"bottle,ycb_006_mustard_bottle,{SOURCE}/data/objects/bottle__ycb_006_mustard_bottle.ply\n"
                           f"box,ycb_004_sugar_box,{SOURCE}/data/objects/box__ycb_004_sugar_box.ply\n")
        cli("simulate", "--objects", objects, "--elevations", "30", "--step", "90", "-q", "--out", WORK / "ds3")
        model = WORK / "open-model"
        cli("train", WORK / "ds3", "--features", "kpd2+kpa3", "--rounds", "10", "--open-set", "knn", "-q", "--out", model)
        m = keyturn.Model(model)
        self.assertEqual(m.open_set["method"], "knn")
        self.assertEqual(m.open_set["false_accept"], 0.05)
        for view in (WORK / "ds3/box/ycb_004_sugar_box/e30/a90.0.pcd", WORK / "mug.pcd", FRAME):
            theirs = json.loads(cli("classify", model, view, "--json", "-q").stdout)[0]
            ours = m.classify(view)
            self.assertEqual(ours.cls, theirs["class"], view)
            self.assertEqual(ours.answer, theirs["answer"], view)
            self.assertEqual(ours.best, theirs["best"], view)
            self.assertEqual(ours.score, theirs["score"], view)
            self.assertEqual(ours.threshold, theirs["threshold"], view)
            self.assertEqual(ours.answer == "class", ours.score >= ours.threshold, view)
            self.assertEqual(pickle.loads(pickle.dumps(ours)), ours)
        self.assertEqual(m.classify(WORK / "ds3/box/ycb_004_sugar_box/e30/a90.0.pcd").cls, "ycb_004_sugar_box")
        empty = m.classify(np.array([[0, 0, 0.5], [0.01, 0, 0.5]], np.float32))
        self.assertEqual((empty.cls, empty.answer, empty.best, empty.score), ("no object", "no object", "", None))
        self.assertIn("points left after filtering", empty.problem)
        # A model written before issue 34 (the shipped one without its open_set) is closed-set.
        closed = WORK / "closed-model"
        closed.mkdir(exist_ok=True)
        sidecar = json.loads((MODEL / "model.json").read_text())
        del sidecar["open_set"], sidecar["pose_references"]
        (closed / "model.json").write_text(json.dumps(sidecar))
        shutil.copy(MODEL / "model.xgb.json", closed)
        old = keyturn.Model(closed).classify(WORK / "mug.pcd")
        self.assertEqual((old.answer, old.score, old.threshold), ("class", None, None))
        self.assertIsNone(keyturn.Model(closed).open_set)
        self.assertEqual(keyturn.Model(MODEL).open_set["method"], "knn-relative")  # the shipped model today
        trained = keyturn.train(keyturn.Dataset(WORK / "ds3").features("kpd2+kpa3"), rounds=10, open_set="max-probability")
        self.assertEqual(trained.open_set["method"], "max-probability")
        with self.assertRaises(ValueError) as e:
            keyturn.train(keyturn.Dataset(WORK / "ds3").features("kpd2+kpa3"), rounds=10, open_set="entropy")
        self.assertIn("open-set method 'entropy'", str(e.exception))
        # The calibration rule and groups, as train's --open-set-rule and --open-set-groups give them: the
        # same threshold as the CLI's, and a per-group threshold at least the pooled one (knn: a score
        # at or above it is named, and the strictest group sets it).
        ds3 = keyturn.Dataset(WORK / "ds3").features("kpd2+kpa3")
        strict = keyturn.train(ds3, rounds=10, open_set="knn", open_set_rule="per-group", open_set_groups=1000)
        cli("train", WORK / "ds3", "--features", "kpd2+kpa3", "--rounds", "10", "--open-set", "knn",
            "--open-set-rule", "per-group", "--open-set-groups", "1000", "-q", "--out", WORK / "strict-model")
        self.assertEqual(strict.open_set["rule"], "per-group")
        self.assertEqual(strict.open_set["threshold"], keyturn.Model(WORK / "strict-model").open_set["threshold"])
        self.assertEqual(m.open_set["rule"], "pooled")
        self.assertGreaterEqual(strict.open_set["threshold"], m.open_set["threshold"])
        with self.assertRaises(ValueError) as e:
            keyturn.train(ds3, rounds=10, open_set="knn", open_set_rule="strictest")
        self.assertIn("strictest", str(e.exception))
        with self.assertRaises(ValueError) as e:
            keyturn.train(ds3, rounds=10, open_set="knn", open_set_groups=1)
        self.assertIn("open_set_groups must be within 2..1000, not 1", str(e.exception))


class DatasetTest(unittest.TestCase):
    def test_views_labels_and_poses(self):
        Fixture.make()
        ds = keyturn.Dataset(WORK / "ds")
        self.assertEqual(len(ds), 12)  # 2 objects × 6 turntable angles
        self.assertEqual(sorted({v.cls for v in ds.views}), ["bottle", "mug"])
        v = ds[0]
        self.assertTrue(Path(v.path).exists())
        self.assertEqual(v.elevation, "30")
        self.assertEqual(v.elevation_deg, 30.0)
        self.assertEqual(sorted({v.commanded_deg for v in ds.views}), [0.0, 60.0, 120.0, 180.0, 240.0, 300.0])
        for v in ds.views:
            self.assertLess(abs(v.measured_deg - v.commanded_deg), 1.0, v.id)
        # The simulated camera knows its pose exactly: views of one object differ by the table's turn.
        first, later = ds[0], ds[1]
        self.assertEqual(first.instance, later.instance)
        t0, t1 = first.camera_from_turntable, later.camera_from_turntable
        self.assertEqual(t0.shape, (4, 4))
        np.testing.assert_allclose(t0[3], [0, 0, 0, 1])
        rel = np.linalg.inv(t0) @ t1
        self.assertAlmostEqual(rel[2, 2], 1.0, places=6)  # a turn about the table's axis
        turned = abs(math.degrees(math.atan2(rel[1, 0], rel[0, 0])))
        self.assertAlmostEqual(turned, abs(later.measured_deg - first.measured_deg), delta=0.01)

    def test_features_fill_and_read_the_cli_cache(self):
        Fixture.make()
        ds_path = WORK / "ds"
        shutil.rmtree(ds_path / ".keyturn", ignore_errors=True)
        ds = keyturn.Dataset(ds_path)
        f = ds.features("kpd2+kpa3", cache=True)
        self.assertTrue(Path(f.cache).exists())
        self.assertEqual(f.x.shape, (12, 64))
        self.assertEqual(f.x.dtype, np.float32)
        self.assertEqual(f.ids, [v.id for v in ds.views])
        self.assertEqual(f.cls, [v.cls for v in ds.views])
        self.assertTrue(np.isfinite(f.x).all())
        # Each row is the view's describe, at the cache's float precision.
        d = keyturn.describe(ds[3].path, features=["kpd2", "kpa3"])
        np.testing.assert_array_equal(f.x[3], d.feature_vector.astype(np.float32))
        self.assertEqual(f.keypoints[3], d.K)
        # The CLI finds the cache the module filled: describe --cache writes nothing new.
        before = os.stat(f.cache).st_mtime_ns
        out = cli("describe", ds_path, "--cache")
        self.assertIn(f.cache, out.stderr)
        self.assertEqual(os.stat(f.cache).st_mtime_ns, before)
        # Another parameter set is another cache.
        g = ds.features(["kpd2"], cache=True, bins=16)
        self.assertNotEqual(g.cache, f.cache)
        self.assertEqual(g.x.shape, (12, 16))
        self.assertEqual(g.spec["bins"], "16")


class BadInput(unittest.TestCase):
    def assert_one_line(self, e, *parts):
        text = str(e.exception)
        self.assertNotIn("\n", text)
        for p in parts:
            self.assertIn(p, text)

    def test_wrong_array_shape(self):
        with self.assertRaises(ValueError) as e:
            keyturn.describe(np.zeros((100, 2), np.float32))
        self.assert_one_line(e, "N × 3", "(100, 2)")
        with self.assertRaises(ValueError) as e:
            keyturn.Model(MODEL).classify(np.zeros((4, 5, 6)))
        self.assert_one_line(e, "classify", "(4, 5, 6)")
        with self.assertRaises(TypeError):
            keyturn.describe({"x": 1})

    def test_nan_only_cloud(self):
        with self.assertRaises(keyturn.Error) as e:
            keyturn.describe(np.full((50, 3), np.nan, np.float32))
        self.assert_one_line(e, "no valid points")
        self.assertIsInstance(e.exception, RuntimeError)

    def test_missing_file_names_it(self):
        missing = WORK / "no-such-view.pcd"
        for call in (keyturn.load_cloud, keyturn.describe, keyturn.Model(MODEL).classify):
            with self.assertRaises(FileNotFoundError) as e:
                call(missing)
            self.assert_one_line(e, str(missing))
            self.assertEqual(e.exception.filename, str(missing))
        with self.assertRaises(FileNotFoundError) as e:
            keyturn.Model(WORK / "no-such-model")
        self.assert_one_line(e, "no-such-model")
        with self.assertRaises(FileNotFoundError) as e:
            keyturn.Dataset(WORK / "no-such-dataset")
        self.assert_one_line(e, "no-such-dataset")
        with self.assertRaises(keyturn.Error) as e:
            keyturn.Dataset(SOURCE / "data/frames")  # a folder, not a dataset
        self.assert_one_line(e, "not a keyturn dataset")

    def test_bytes_that_are_not_text_stay_in_the_message(self):
        # A PCD beginning with \xff\xfe (random bytes): keyturn.Error came with an empty message, the
        # C++ text not being UTF-8. Its bytes are written as \\xff now, by the CLI too.
        WORK.mkdir(parents=True, exist_ok=True)
        bad = WORK / "bom.pcd"
        bad.write_bytes(b"\xff\xfe" + bytes(range(0x80, 0x100)) + b"\n")
        expected = f"{bad}: not a valid PCD file (unknown header line 1: '\\xff\\xfe\\x80\\x81"
        for call in (keyturn.load_cloud, keyturn.describe, keyturn.Model(MODEL).classify):
            with self.assertRaises(keyturn.Error) as e:
                call(bad)
            self.assert_one_line(e, expected)
        r = subprocess.run([KT, "describe", "-q", bad], capture_output=True, check=False)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(r.stderr.decode("utf-8"), f"keyturn describe: {expected}"
                         "\\x82\\x83\\x84\\x85\\x86\\x87\\x88\\x89\\x8a\\x8b\\x8c\\x8d\\x8e\\x8f\\x90\\x91')\n")

    def test_bad_parameters(self):
        with self.assertRaises(TypeError) as e:
            keyturn.describe(FRAME, binz=16)
        self.assert_one_line(e, "binz", "bins")
        with self.assertRaises(ValueError) as e:
            keyturn.describe(FRAME, bins=1)
        self.assert_one_line(e, "bins", "2..4096")
        with self.assertRaises(TypeError) as e:
            keyturn.describe(FRAME, bins=16.0)
        self.assert_one_line(e, "bins must be an int")
        with self.assertRaises(ValueError) as e:
            keyturn.describe(FRAME, features=["kpd9"])
        self.assert_one_line(e, "kpd9")

    def test_unknown_block(self):
        Fixture.make()
        with self.assertRaises(ValueError) as e:
            keyturn.Dataset(WORK / "ds").features("kpd2+nope")
        self.assert_one_line(e, "nope")


class DegenerateClouds(unittest.TestCase):
    """Issue 35: clouds that load fine and are degenerate killed the interpreter (SIGSEGV in the
    chain); fuzz findings escaped as IndexError. Each is a keyturn.Error in one line now."""
    REG = SOURCE / "tests/fuzz/regressions"

    def test_degenerate_clouds_raise(self):
        for name in ("chain_one_point_1000_times.pcd", "chain_sphere_5cm_1000km.pcd"):
            cloud = keyturn.load_cloud(self.REG / name)
            with self.assertRaises(keyturn.Error) as e:
                keyturn.describe(cloud)
            self.assertNotIn("\n", str(e.exception))
            self.assertIn("degenerate cloud", str(e.exception))

    def test_points_too_far_to_measure_are_named_as_such(self):
        # It said "only 0 of N points left after filtering (segmented-cloud: nothing removed)".
        points = keyturn.load_cloud(CROP)
        with self.assertRaises(keyturn.Error) as e:
            keyturn.describe(points * np.float32(1e30))
        n = len(points)
        self.assertEqual(str(e.exception), f"points: only 0 of {n} points left after filtering "
                         f"(segmented-cloud: {n} beyond 1e+18 m of the origin, no measurement)")

    def test_pcl_prints_nothing(self):
        # Points no plane fits (on a twisted cubic): PCL's RANSAC wrote "[pcl::SampleConsensusModelPlane::
        # optimizeModelCoefficients] Not enough inliers …" to stderr, beside keyturn's own error.
        code = ("import numpy as np, keyturn\n"
                "t = np.linspace(-1, 1, 12, dtype=np.float32)\n"
                "p = np.stack([t, t * t, 2 + t * t * t], axis=1) * np.float32(2)\n"
                "try:\n    keyturn.describe(p, kind='segmented')\nexcept keyturn.Error as e:\n    print(e)\n")
        r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
        self.assertEqual(r.stderr, "")

    def test_a_second_pcd_data_line_raises(self):
        with self.assertRaises(keyturn.Error) as e:
            keyturn.load_cloud(self.REG / "pcd_second_data_line.pcd")
        self.assertIn("is a header line after DATA", str(e.exception))


if __name__ == "__main__":
    unittest.main(verbosity=2)
