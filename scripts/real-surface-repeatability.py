#!/usr/bin/env python3
"""Keypoint repeatability on real surfaces (docs/repeatability.md, issue 17).

The shared mOSD scenes are single views without poses, so a real second view with a known pose
does not exist. Instead each real object crop is split into two disjoint random halves of its
points -- two independent samplings of the one real surface, with the sensor's real noise -- and
the second half is moved by a known rigid motion (20 deg about the camera's vertical axis through
the crop's centroid, 3 cm along x). `keyturn repeatability` then scores every detector on the pair,
natively and at ISS's keypoint count, once per ISS suppression radius given. The motion is undone
exactly by the pose list, so only the detectors' response to resampling and rotation is measured
(not a second exposure's noise).

Usage: scripts/real-surface-repeatability.py [--detectors LIST] [--keypoints K] [--eps LIST]
           KEYTURN CROP_DIR OUT_DIR NMS [NMS ...]
Prints one Markdown table: the mean over objects of each detector's keypoints and relative
repeatability at each ε (default 1, 2 and 3 x resolution), native and at an equal budget (ISS's
count, or K). --detectors defaults to iss,harris3d,sift3d,uniform (issue 49 adds iss-chain,
iss-refined, iss-salient: the chain's keypoints as describe places them).
"""
import importlib.util
import json
import math
import os
import random
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("fixtures", os.path.join(HERE, "make-real-fixtures.py"))
fixtures = importlib.util.module_from_spec(spec)
spec.loader.exec_module(fixtures)

ANGLE = math.radians(20.0)
SHIFT = (0.03, 0.0, 0.0)
ROT = ((math.cos(ANGLE), 0.0, math.sin(ANGLE)), (0.0, 1.0, 0.0), (-math.sin(ANGLE), 0.0, math.cos(ANGLE)))
DETECTORS = ("iss", "harris3d", "sift3d", "uniform")


def write_pair(crop, folder):
    """Writes a.pcd, b.pcd (the moved half) and poses.txt (keyturn list: common = R(q) p + t)."""
    _, _, cols = fixtures.read_pcd(crop)
    pts = [p for p in zip(cols["x"], cols["y"], cols["z"]) if all(math.isfinite(v) for v in p)]
    if len(pts) < 100:
        raise SystemExit("%s: only %d valid points" % (crop, len(pts)))
    random.Random(7).shuffle(pts)
    half_a, half_b = pts[0::2], pts[1::2]
    c = [sum(p[i] for p in pts) / len(pts) for i in range(3)]
    # b = R (p - c) + c + shift = R p + t_b; its pose maps b back: p = Rᵀ b − Rᵀ t_b.
    t_b = [c[r] - sum(ROT[r][k] * c[k] for k in range(3)) + SHIFT[r] for r in range(3)]
    moved = [tuple(sum(ROT[r][k] * p[k] for k in range(3)) + t_b[r] for r in range(3)) for p in half_b]
    t = [-sum(ROT[k][r] * t_b[k] for k in range(3)) for r in range(3)]
    os.makedirs(folder, exist_ok=True)
    fixtures.write_pcd(os.path.join(folder, "a.pcd"), len(half_a), 1, half_a)
    fixtures.write_pcd(os.path.join(folder, "b.pcd"), len(moved), 1, moved)
    with open(os.path.join(folder, "poses.txt"), "w") as f:
        f.write("a.pcd 0 0 0 0 0 0 1\n")  # Rᵀ about y is the rotation by −ANGLE: q = (0, −sin, 0, cos)
        f.write("b.pcd %.9f %.9f %.9f 0 %.9f 0 %.9f\n" % (t[0], t[1], t[2], -math.sin(ANGLE / 2), math.cos(ANGLE / 2)))


def main(argv):
    global DETECTORS
    argv, eps, extra = list(argv), "1,2,3", []
    while len(argv) > 1 and argv[1].startswith("--"):
        flag, value = argv[1], argv[2]
        del argv[1:3]
        if flag == "--detectors":
            DETECTORS = tuple(value.split(","))
        elif flag == "--eps":
            eps = value
        elif flag == "--keypoints":
            extra = ["--keypoints", value]
        else:
            raise SystemExit("unknown option " + flag)
    n_eps = len(eps.split(","))
    if len(argv) < 5:
        raise SystemExit("usage: scripts/real-surface-repeatability.py KEYTURN CROP_DIR OUT_DIR NMS [NMS ...]")
    keyturn, crops, out, nms_values = argv[1], argv[2], argv[3], argv[4:]
    names = sorted(n for n in os.listdir(crops) if n.endswith(".pcd"))
    results = {nms: [] for nms in nms_values}
    for i, name in enumerate(names):
        folder = os.path.join(out, name[:-4])
        write_pair(os.path.join(crops, name), folder)
        for nms in nms_values:
            run = subprocess.run([keyturn, "repeatability", os.path.join(folder, "poses.txt"), "--iss-nms", nms,
                                  "--detectors", ",".join(DETECTORS), "--eps", eps, *extra,
                                  "--out", os.path.join(folder, "nms" + nms), "--json"],
                                 capture_output=True, text=True)
            if run.returncode != 0:
                raise SystemExit("%s: keyturn repeatability failed: %s" % (name, run.stderr.strip()))
            results[nms].append(json.loads(run.stdout))
        print("[%d/%d] %s" % (i + 1, len(names), name), file=sys.stderr, flush=True)
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(results, f)
    head = eps.split(",")
    print("| r_nms | detector | keypoints | " + " | ".join("rel@" + e for e in head) + " | " +
          " | ".join("rel@%s at equal K" % e for e in head) + " |")
    print("|---|---|---|" + "---|" * (2 * n_eps))
    for nms in nms_values:
        runs = results[nms]
        for det in DETECTORS:
            d = [r["detectors"][det] for r in runs]
            k = statistics.mean(x["keypoints"] for x in d)
            rel = [statistics.mean(x["relative"][e] for x in d) for e in range(n_eps)]
            eq = [statistics.mean(x["equal_k"]["relative"][e] for x in d) for e in range(n_eps)]
            print("| %s | %s | %.1f | %s | %s |" % (nms, det, k, " | ".join("%.3f" % v for v in rel),
                                                 " | ".join("%.3f" % v for v in eq)))
    overlap = statistics.median(r["overlap"]["median"] for r in results[nms_values[0]])
    print("\n%d objects, overlap median %.2f" % (len(names), overlap))


if __name__ == "__main__":
    main(sys.argv)
