#!/usr/bin/env python3
"""Writes fuzz_oni's seed recordings: .oni files laid out as OpenNI2's Recorder lays out its own
(the same records in the same order as a recording of keyturn's simulated camera), with a 4 x 3
uncompressed depth stream so that a recording is about 2 KB.
usage: oni_seed.py OUT.oni [FRAME.jpg]
  with FRAME.jpg (a 640 x 480 JPEG, such as a colour frame of a recording of the simulated camera):
  a colour stream too, one frame, compressed with that image (OpenNI2's JPEG codec)."""
import struct
import sys


def record(rtype, node, fields=b"", payload=b"", undo=0):
    return struct.pack("<4sIIIIQ", b"NIR\0", rtype, node, 28 + len(fields), len(payload), undo) + fields + payload


def string(s):
    b = s.encode() + b"\0"
    return struct.pack("<I", len(b)) + b


def int_prop(node, name, value):
    return record(0x03, node, string(name) + struct.pack("<IQ", 8, value))


def gen_prop(node, name, data):
    return record(0x06, node, string(name) + struct.pack("<I", len(data)) + data)


def node_records(node, name, ntype, codec, frames, width, height, xn_format, oni_format, bpp, seek_at):
    mode = struct.pack("<III", width, height, 30)
    out = record(0x0D, node, string(name) + struct.pack("<I4sIQQQ", ntype, codec, frames, 0, 33333 * (frames - 1), seek_at))
    out += int_prop(node, "oniRequiredFrameSize", width * height * bpp)
    out += int_prop(node, "xnIsGenerating", 1)
    if ntype == 2:
        out += int_prop(node, "xnDeviceMaxDepth", 4500)
    out += int_prop(node, "xnSupportedMapOutputModesCount", 1)
    out += gen_prop(node, "xnSupportedMapOutputModes", mode)
    out += gen_prop(node, "xnMapOutputMode", mode)
    out += gen_prop(node, "xnSupportedPixelFormats", struct.pack("<I", 1 << (xn_format - 1)))
    out += int_prop(node, "xnPixelFormat", xn_format)
    out += int_prop(node, "oniPixelFormat", oni_format)
    out += gen_prop(node, "xnFOV", struct.pack("<dd", 1.0226, 0.7906))
    out += int_prop(node, "Cropping", 1)
    out += gen_prop(node, "xnCropping", struct.pack("<?xHHHHxx", False, 0, 0, width, height))
    out += int_prop(node, "Mirror", 1)
    out += int_prop(node, "xnMirror", 0)
    return out


def main():
    out = sys.argv[1]
    jpeg = open(sys.argv[2], "rb").read() if len(sys.argv) > 2 else None
    frames = 1 if jpeg else 2
    depth = [struct.pack("<12H", *[(800 + 10 * k + i) for i in range(12)]) for k in range(frames)]
    # node id, name, type (2 depth, 3 image), codec, frames' data, size, OpenNI 1 and 2 pixel formats, bytes a pixel
    nodes = [(1, "Depth", 2, b"NONE", depth, 4, 3, 4, 100, 2)]
    if jpeg:
        nodes.append((2, "Image", 3, b"JPEG", [jpeg] * frames, 640, 480, 1, 200, 3))
    seek_at = {n[0]: 0 for n in nodes}
    for _ in range(2):  # the first pass finds where the seek tables land
        body = b""
        for node, name, ntype, codec, _data, w, h, xn, oni, bpp in nodes:
            body += node_records(node, name, ntype, codec, frames, w, h, xn, oni, bpp, seek_at[node])
        for node, *_ in nodes:
            body += record(0x09, node) + record(0x08, node, struct.pack("<IQ", 0xFFFFFFFF, 0xFFFFFFFFFFFFFFFF))
        frame_at = {n[0]: [] for n in nodes}
        for k in range(frames):
            for node, _name, _t, _c, data, *_ in nodes:
                frame_at[node].append(24 + len(body))
                body += record(0x0A, node, struct.pack("<QI", 33333 * k, k + 1), data[k])
        for node, *_ in nodes:
            body += record(0x07, node)
            seek_at[node] = 24 + len(body)
            table = struct.pack("<QIQ", 0, 0, 0)
            table += b"".join(struct.pack("<QIQ", 33333 * k, 0, frame_at[node][k]) for k in range(frames))
            body += record(0x0E, node, b"", table)
        body += record(0x0B, 0)
    header = b"NI10" + struct.pack("<BBHIQI", 1, 0, 1, 0, 33333 * (frames - 1), max(n[0] for n in nodes))
    open(out, "wb").write(header + body)


main()
