#!/usr/bin/env python3
"""Draws a binary PLY surface written by tissuemesh (double x, y, z; uchar-count uint faces) as a flat-shaded
grey PNG seen along +y (z up), with a depth buffer. Standard library only; for README pictures.

    bench/snake/render_png.py skull.ply skull.png
"""
import math
import struct
import sys
import zlib


def read_ply(path):
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    nv = int(header.split("element vertex ")[1].split()[0])
    nf = int(header.split("element face ")[1].split()[0])
    labels = header.count("property ushort") + header.count("property uint16")
    vertices = [struct.unpack_from("<3d", data, end + 24 * i) for i in range(nv)]
    faces, at = [], end + 24 * nv
    for _ in range(nf):
        n = data[at]
        faces.append(struct.unpack_from("<%dI" % n, data, at + 1))
        at += 1 + 4 * n + 2 * labels
    return vertices, faces


def write_png(path, width, height, rows):
    raw = b"".join(b"\x00" + bytes(row) for row in rows)
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    with open(path, "wb") as out:
        out.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0))
                  + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main(source, target, size=600):
    vertices, faces = read_ply(source)
    xs = [v[0] for v in vertices]
    zs = [v[2] for v in vertices]
    scale = 0.9 * size / max(max(xs) - min(xs), max(zs) - min(zs))
    cx, cz = (max(xs) + min(xs)) / 2, (max(zs) + min(zs)) / 2
    light = (0.3, -0.8, 0.5)
    norm_light = math.sqrt(sum(c * c for c in light))
    depth = [[1e300] * size for _ in range(size)]
    image = [[255] * size for _ in range(size)]
    for f in faces:
        a, b, c = (vertices[i] for i in f[:3])
        u = [b[k] - a[k] for k in range(3)]
        w = [c[k] - a[k] for k in range(3)]
        n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
        length = math.sqrt(sum(x * x for x in n)) or 1
        shade = abs(sum(n[k] * light[k] for k in range(3))) / (length * norm_light)
        grey = int(50 + 190 * shade)
        # Screen: x to the right, z up; the viewer looks along +y, so smaller y is nearer.
        p = [(size / 2 + scale * (q[0] - cx), size / 2 - scale * (q[2] - cz), q[1]) for q in (a, b, c)]
        area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1])
        if area == 0:
            continue
        for y in range(max(0, int(min(q[1] for q in p))), min(size, int(max(q[1] for q in p)) + 1)):
            for x in range(max(0, int(min(q[0] for q in p))), min(size, int(max(q[0] for q in p)) + 1)):
                l1 = ((p[1][0] - x) * (p[2][1] - y) - (p[2][0] - x) * (p[1][1] - y)) / area
                l2 = ((p[2][0] - x) * (p[0][1] - y) - (p[0][0] - x) * (p[2][1] - y)) / area
                l3 = 1 - l1 - l2
                if min(l1, l2, l3) < 0:
                    continue
                d = l1 * p[0][2] + l2 * p[1][2] + l3 * p[2][2]
                if d < depth[y][x]:
                    depth[y][x] = d
                    image[y][x] = grey
    write_png(target, size, size, image)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
