#!/usr/bin/env python3
"""Writes small datasets in other people's layouts from the real Kinect cuts in
tests/data/real/mosd (two boxes of scene learn0, three cylinders of learn34), for
the import tests. Standard library only (PNG written with zlib). Usage:

  write_depth_views.py MOSD_DIR OUT_DIR

OUT_DIR/washington_crop/  CATEGORY/INSTANCE/INSTANCE_V_F_{depthcrop,maskcrop,crop}.png + _loc.txt
                          (Washington RGB-D's cropped form), plus three files it must report:
                          a video 3, a name that is not INSTANCE_V_F, a view without its _loc.txt
OUT_DIR/washington_pcd/   CATEGORY/INSTANCE/INSTANCE_V_F.pcd (ascii: x y z rgb imX imY, as Washington's)
OUT_DIR/folders/          CLASS/INSTANCE/eLABEL/VIEW.{pcd,ply,png} (+ VIEW_mask.png, VIEW_loc.txt)
OUT_DIR/pair/             view_depth.png (+ mask, loc) and view.pcd: the same view, the PCD
                          computed here from the PNG's pixels (an independent implementation)
OUT_DIR/camera.json       the intrinsics mOSD's grid implies (least squares), depth in mm
"""
import array, json, math, pathlib, random, struct, sys, zlib

mosd, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
W, H = 640, 480


def read_pcd_xyz(path):
    data = path.read_bytes()
    end = data.index(b"DATA binary\n") + len(b"DATA binary\n")
    a = array.array("f")
    a.frombytes(data[end:end + W * H * 12])
    return a


def png(path, w, h, values, bits=16, channels=1):
    colour_type = {1: 0, 3: 2}[channels]
    fmt = ">" + ("H" if bits == 16 else "B") * (w * channels)
    raw = b"".join(b"\x00" + struct.pack(fmt, *values[r * w * channels:(r + 1) * w * channels]) for r in range(h))
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    ihdr = struct.pack(">IIBBBBB", w, h, bits, colour_type, 0, 0, 0)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def f32(x):  # the float a C++ static_cast<float> makes of the double
    return struct.unpack("f", struct.pack("f", x))[0]


def fit(full):  # u = fx * x / z + cx by least squares, and v likewise
    s = [[0.0] * 5 for _ in range(2)]
    for i in range(0, W * H, 7):
        x, y, z = full[3 * i:3 * i + 3]
        if not (z == z) or z <= 0:
            continue
        for k, (t, p) in enumerate(((x / z, i % W), (y / z, i // W))):
            s[k][0] += t * t; s[k][1] += t; s[k][2] += 1; s[k][3] += t * p; s[k][4] += p
    res = []
    for a, b, n, tp, p in s:
        f = (n * tp - b * p) / (n * a - b * b)
        res += [f, (p - f * b) / n]
    return res  # fx, cx, fy, cy


scenes = {"learn0": ("box", ["o1", "o2"]), "learn34": ("cylinder", ["o1", "o2", "o3"])}
objects = []  # (category, instance, depth image of the scene in mm, mask)
camera = None
for scene, (category, objs) in scenes.items():
    full = read_pcd_xyz(mosd / "full" / (scene + ".pcd"))
    if camera is None:
        fx, cx, fy, cy = fit(full)
        camera = {"fx": fx, "fy": fy, "cx": cx, "cy": cy}
    depth = [0 if not (full[3 * i + 2] == full[3 * i + 2]) else int(round(full[3 * i + 2] * 1000)) for i in range(W * H)]
    counts = {}
    for o in objs:
        masked = read_pcd_xyz(mosd / "masked" / ("%s_%s.pcd" % (scene, o)))
        mask = [1 if masked[3 * i + 2] == masked[3 * i + 2] else 0 for i in range(W * H)]
        counts[category] = counts.get(category, 0) + 1
        objects.append((category, "%s_%d" % (category, counts[category]), depth, mask))
out.mkdir(parents=True, exist_ok=True)
(out / "camera.json").write_text(json.dumps(camera, indent=1) + "\n")


def frame_of(depth, mask, seed):
    """One frame: the object's bounding box (+ 8 px), depth with ±2 mm noise, 5 % of the mask dropped."""
    rng = random.Random(seed)
    on = [i for i in range(W * H) if mask[i]]
    u0 = max(0, min(i % W for i in on) - 8); u1 = min(W - 1, max(i % W for i in on) + 8)
    v0 = max(0, min(i // W for i in on) - 8); v1 = min(H - 1, max(i // W for i in on) + 8)
    w, h = u1 - u0 + 1, v1 - v0 + 1
    d, m = [], []
    for v in range(v0, v1 + 1):
        for u in range(u0, u1 + 1):
            i = v * W + u
            z = depth[i]
            d.append(max(0, z + rng.randint(-2, 2)) if z else 0)
            m.append(1 if mask[i] and rng.random() > 0.05 else 0)
    return u0, v0, w, h, d, m


def points(u0, v0, w, h, d, m, k):  # what loadDepthImage computes, in Python
    pts = []
    for v in range(h):
        for u in range(w):
            z = d[v * w + u] * 0.001
            if not d[v * w + u] or not m[v * w + u]:
                pts.append(None)
                continue
            pts.append((f32((float(u + u0) - k["cx"]) * z / k["fx"]), f32((float(v + v0) - k["cy"]) * z / k["fy"]), f32(z),
                        u + u0, v + v0))
    return pts


def write_crop(base, u0, v0, w, h, d, m, loc=True):
    png(pathlib.Path(str(base) + "_depthcrop.png"), w, h, d)
    png(pathlib.Path(str(base) + "_maskcrop.png"), w, h, [255 * x for x in m], bits=8)
    png(pathlib.Path(str(base) + "_crop.png"), w, h, [128] * (3 * w * h), bits=8, channels=3)
    if loc:
        pathlib.Path(str(base) + "_loc.txt").write_text("%d,%d\n" % (u0 + 1, v0 + 1))


def ascii_pcd(path, pts, fields, organized=None):
    path.parent.mkdir(parents=True, exist_ok=True)
    n = len(pts)
    w, h = organized if organized else (n, 1)
    types = {"x y z rgb imX imY": ("4 4 4 4 4 4", "F F F F I I", "1 1 1 1 1 1"), "x y z": ("4 4 4", "F F F", "1 1 1")}[fields]
    lines = ["# .PCD v.7 - Point Cloud Data file format", "VERSION .7", "FIELDS " + fields, "SIZE " + types[0],
             "TYPE " + types[1], "COUNT " + types[2], "WIDTH %d" % w, "HEIGHT %d" % h, "VIEWPOINT 0 0 0 1 0 0 0",
             "POINTS %d" % n, "DATA ascii"]
    for p in pts:
        if p is None:
            lines.append("nan nan nan")
        elif fields == "x y z":
            lines.append("%.9g %.9g %.9g" % p[:3])
        else:
            lines.append("%.9g %.9g %.9g 0 %d %d" % p)
    path.write_text("\n".join(lines) + "\n")


for n, (category, instance, depth, mask) in enumerate(objects):
    for video in (1, 2, 4):
        for frame in (1, 2):
            u0, v0, w, h, d, m = frame_of(depth, mask, 1000 * n + 10 * video + frame)
            stem = "%s_%d_%d" % (instance, video, frame)
            write_crop(out / "washington_crop" / category / instance / stem, u0, v0, w, h, d, m)
            pts = [p for p in points(u0, v0, w, h, d, m, camera) if p]
            ascii_pcd(out / "washington_pcd" / category / instance / (stem + ".pcd"), pts, "x y z rgb imX imY")
            elev = {1: "30", 2: "45", 4: "60"}[video]
            view = out / "folders" / category / instance / ("e" + elev) / ("v%d" % frame)
            if frame == 1:  # a depth image with its companions
                png(pathlib.Path(str(view) + "_depth.png"), w, h, d)
                png(pathlib.Path(str(view) + "_mask.png"), w, h, [255 * x for x in m], bits=8)
                pathlib.Path(str(view) + "_loc.txt").write_text("%d,%d\n" % (u0 + 1, v0 + 1))
            elif video == 2:  # an ascii PLY
                view.parent.mkdir(parents=True, exist_ok=True)
                body = "".join("%.9g %.9g %.9g\n" % p[:3] for p in pts)
                pathlib.Path(str(view) + ".ply").write_text(
                    "ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
                    "end_header\n%s" % (len(pts), body))
            else:
                ascii_pcd(pathlib.Path(str(view) + ".pcd"), pts, "x y z")

# What the Washington importer must report, one line each, importing the rest.
category, instance, depth, mask = objects[0]
u0, v0, w, h, d, m = frame_of(depth, mask, 99)
write_crop(out / "washington_crop" / category / instance / ("%s_3_1" % instance), u0, v0, w, h, d, m)
write_crop(out / "washington_crop" / category / instance / ("%s_4_9" % instance), u0, v0, w, h, d, m, loc=False)
(out / "washington_crop" / category / instance / "notes.txt").write_text("taken on a Tuesday\n")

# The same view twice: a depth PNG, and the PCD of its pixels computed here.
u0, v0, w, h, d, m = frame_of(depth, mask, 7)
pair = out / "pair"
pair.mkdir(parents=True, exist_ok=True)
png(pair / "view_depth.png", w, h, d)
png(pair / "view_mask.png", w, h, [255 * x for x in m], bits=8)
(pair / "view_loc.txt").write_text("%d,%d\n" % (u0 + 1, v0 + 1))
ascii_pcd(pair / "view.pcd", points(u0, v0, w, h, d, m, camera), "x y z", organized=(w, h))
print("camera fx %.2f fy %.2f cx %.2f cy %.2f; %d objects" % (camera["fx"], camera["fy"], camera["cx"], camera["cy"], len(objects)))
