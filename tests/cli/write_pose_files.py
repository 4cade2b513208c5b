#!/usr/bin/env python3
"""Writes one keyturn dataset's exact poses in every pose format keyturn reads
(and an inverted keyturn list), so the command-line test can check that each
format gives the same repeatability. Usage: write_pose_files.py DATASET OUT_DIR"""
import json, math, pathlib, sys

root, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
out.mkdir(parents=True, exist_ok=True)
views = sorted(root.rglob("a*.json"), key=lambda p: float(p.stem[1:]))


def inverse(T):  # of a rigid 4 × 4
    R = [[T[j][i] for j in range(3)] for i in range(3)]
    t = [-sum(R[i][k] * T[k][3] for k in range(3)) for i in range(3)]
    return [R[0] + [t[0]], R[1] + [t[1]], R[2] + [t[2]], [0.0, 0.0, 0.0, 1.0]]


def quaternion(R):  # x y z w of a rotation matrix (Shepperd's method)
    tr = R[0][0] + R[1][1] + R[2][2]
    if tr > 0:
        s = 2 * math.sqrt(tr + 1)
        return [(R[2][1] - R[1][2]) / s, (R[0][2] - R[2][0]) / s, (R[1][0] - R[0][1]) / s, s / 4]
    i = max(range(3), key=lambda k: R[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2 * math.sqrt(1 + R[i][i] - R[j][j] - R[k][k])
    q = [0.0] * 4
    q[i], q[j], q[k], q[3] = s / 4, (R[j][i] + R[i][j]) / s, (R[k][i] + R[i][k]) / s, (R[k][j] - R[j][k]) / s
    return q


def line(values):
    return " ".join(repr(float(v)) for v in values)


keyturn, inverted, stanford, tum, tum_views, matrix = [], [], ["camera 0 0 0 0 0 0 1"], [], [], []
for n, sidecar in enumerate(views):
    pcd = str(sidecar.with_suffix(".pcd").resolve())
    W = inverse(json.load(open(sidecar))["camera_from_turntable"])  # world (turntable) ← view
    R, t = [row[:3] for row in W[:3]], [W[i][3] for i in range(3)]
    q = quaternion(R)
    keyturn.append(f"{pcd} {line(t + q)}")
    V = inverse(W)
    inverted.append(f"{pcd} {line([V[i][3] for i in range(3)] + quaternion([row[:3] for row in V[:3]]))}")
    # Stanford: common = R(q)ᵀ p + t, so its quaternion is the conjugate.
    stanford.append(f"bmesh {pcd} {line(t + [-q[0], -q[1], -q[2], q[3]])}")
    tum.append(f"{1000 + n:.6f} {line(t + q)}")
    tum_views.append(f"{1000 + n + 0.004:.6f} {pcd}")
    matrix.append(f"{pcd} {line([v for row in W for v in row])}")
for name, lines in [("poses.txt", keyturn), ("inverted.txt", inverted), ("scans.conf", stanford),
                    ("trajectory.txt", tum), ("depth.txt", tum_views), ("matrices.txt", matrix)]:
    (out / name).write_text("# written by write_pose_files.py\n" + "\n".join(lines) + "\n")
