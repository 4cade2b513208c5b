#!/usr/bin/env python3
"""Cuts labelled real RGB-D scenes (mOSD: organized 640x480 PCD with a per-point
`label` field) into the three kinds of input keyturn's filter recognises:

  full/SCENE.pcd             the whole organized frame (x y z), table and objects
  masked/SCENE_oN.pcd        the organized frame with every pixel but object N NaN
  crop/SCENE_oN.pcd          object N alone as an unorganized cloud

mOSD labels: 0 = NaN, 1-9 = the table, >= 20 = objects (object id = label // 10).
Standard library only (PCD binary_compressed is LZF: decompressed here).
Usage: make-real-fixtures.py OUT_DIR SCENE.pcd [SCENE.pcd ...]
"""
import math
import os
import struct
import sys


def lzf_decompress(data, out_len):
    out = bytearray()
    i, n = 0, len(data)
    while i < n:
        ctrl = data[i]
        i += 1
        if ctrl < 32:
            out += data[i:i + ctrl + 1]
            i += ctrl + 1
            continue
        length = ctrl >> 5
        if length == 7:
            length += data[i]
            i += 1
        ref = len(out) - ((ctrl & 0x1F) << 8) - 1 - data[i]
        i += 1
        length += 2
        if ref < 0:
            raise ValueError("corrupt LZF stream")
        if ref + length <= len(out):
            out += out[ref:ref + length]
        else:
            for k in range(length):
                out.append(out[ref + k])
    if len(out) != out_len:
        raise ValueError("LZF stream gives %d bytes, header says %d" % (len(out), out_len))
    return bytes(out)


def read_pcd(path):
    with open(path, "rb") as f:
        raw = f.read()
    header, pos = {}, 0
    while True:
        end = raw.index(b"\n", pos)
        line = raw[pos:end].decode("ascii").strip()
        pos = end + 1
        if not line or line.startswith("#"):
            continue
        key, _, rest = line.partition(" ")
        header[key] = rest.split()
        if key == "DATA":
            break
    fields = header["FIELDS"]
    sizes = [int(s) for s in header["SIZE"]]
    types = header["TYPE"]
    width, height = int(header["WIDTH"][0]), int(header["HEIGHT"][0])
    n = width * height
    fmt = {("U", 4): "I", ("F", 4): "f", ("I", 4): "i"}
    columns = {}
    if header["DATA"][0] == "binary_compressed":
        csize, usize = struct.unpack_from("<II", raw, pos)
        blob = lzf_decompress(raw[pos + 8:pos + 8 + csize], usize)
        off = 0
        for name, size, typ in zip(fields, sizes, types):
            columns[name] = struct.unpack_from("<%d%s" % (n, fmt[(typ, size)]), blob, off)
            off += n * size
    elif header["DATA"][0] == "binary":
        step = sum(sizes)
        rec = struct.Struct("<" + "".join(fmt[(t, s)] for t, s in zip(types, sizes)))
        rows = [rec.unpack_from(raw, pos + i * step) for i in range(n)]
        for k, name in enumerate(fields):
            columns[name] = [r[k] for r in rows]
    else:
        raise ValueError("%s: DATA %s not handled" % (path, header["DATA"][0]))
    return width, height, columns


def write_pcd(path, width, height, xyz):
    """Binary PCD with fields x y z; `xyz` is a list of (x, y, z) tuples."""
    head = ("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\n"
            "SIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH %d\nHEIGHT %d\n"
            "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS %d\nDATA binary\n" % (width, height, len(xyz)))
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(head.encode("ascii"))
        f.write(b"".join(struct.pack("<fff", *p) for p in xyz))
    os.replace(tmp, path)


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    out = argv[1]
    for kind in ("full", "masked", "crop"):
        os.makedirs(os.path.join(out, kind), exist_ok=True)
    nan = (math.nan, math.nan, math.nan)
    for scene_path in argv[2:]:
        scene = os.path.splitext(os.path.basename(scene_path))[0]
        w, h, col = read_pcd(scene_path)
        xyz = list(zip(col["x"], col["y"], col["z"]))
        valid = [all(math.isfinite(c) for c in p) for p in xyz]
        write_pcd(os.path.join(out, "full", scene + ".pcd"), w, h,
                  [p if ok else nan for p, ok in zip(xyz, valid)])
        objects = sorted({l // 10 for l in col["label"] if l >= 20})
        for obj in objects:
            mine = [ok and l // 10 == obj for l, ok in zip(col["label"], valid)]
            name = "%s_o%d.pcd" % (scene, obj - 1)
            write_pcd(os.path.join(out, "masked", name), w, h,
                      [p if m else nan for p, m in zip(xyz, mine)])
            crop = [p for p, m in zip(xyz, mine) if m]
            write_pcd(os.path.join(out, "crop", name), len(crop), 1, crop)
            print("%s object %d: %d points" % (scene, obj - 1, len(crop)))


if __name__ == "__main__":
    main(sys.argv)
