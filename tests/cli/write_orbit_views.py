#!/usr/bin/env python3
"""Writes views of one lumpy object from cameras orbiting it (as laser scans of a
statue are taken), as ASCII PCD files, with their poses as a keyturn list and
inverted: the views overlap under the right poses and not at all under the
inverse. Usage: write_orbit_views.py OUT_DIR"""
import math, pathlib, random, sys

out = pathlib.Path(sys.argv[1])
out.mkdir(parents=True, exist_ok=True)
rng = random.Random(5)
obj = []
for _ in range(4000):
    d = [rng.gauss(0, 1) for _ in range(3)]
    n = math.sqrt(sum(v * v for v in d))
    d = [v / n for v in d]
    r = 0.05 * (1 + 0.25 * math.sin(3 * d[0] + 1) * math.cos(2 * d[1]) + 0.15 * d[2] * d[2] * d[0])
    obj.append([r * v for v in d])


def rot_y(a):
    c, s = math.cos(a), math.sin(a)
    return [[c, 0, s], [0, 1, 0], [-s, 0, c]]


def quaternion_y(a):  # x y z w
    return [0.0, math.sin(a / 2), 0.0, math.cos(a / 2)]


poses, inverted = [], []
for i in range(4):
    a = math.radians(30 * i)
    # World ← view: the camera 0.5 m from the object's centre, turned by a about y.
    R = rot_y(a)
    t = [-0.5 * R[0][2], -0.5 * R[1][2], -0.5 * R[2][2]]  # camera at -0.5 m along its own optical axis
    # The view's points p = Rᵀ (w − t).
    pts = [[sum(R[k][j] * (w[k] - t[k]) for k in range(3)) for j in range(3)] for w in obj]
    name = f"view{i}.pcd"
    body = "\n".join(f"{p[0]:.7f} {p[1]:.7f} {p[2]:.7f}" for p in pts)
    (out / name).write_text("VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                            f"WIDTH {len(pts)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(pts)}\nDATA ascii\n{body}\n")
    q = quaternion_y(a)
    poses.append(f"{name} {' '.join(map(repr, t + q))}")
    ti = [-sum(R[k][j] * t[k] for k in range(3)) for j in range(3)]  # view ← world
    inverted.append(f"{name} {' '.join(map(repr, ti + [0.0, -q[1], 0.0, q[3]]))}")
(out / "poses.txt").write_text("\n".join(poses) + "\n")
(out / "inverted.txt").write_text("\n".join(inverted) + "\n")
