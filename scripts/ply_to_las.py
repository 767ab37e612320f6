#!/usr/bin/env python3
"""A LAS 1.2 point format 2 file from a binary little-endian PLY of float x y z (what `pcsketch sample` writes), for
measuring the streamed LAS read on big clouds (docs/io.md, "Large clouds"). The points are moved to UTM-like offsets
(500000, 4649000, 100) and quantised at 1e-6; intensity, classification (2, 6, 7 in turn) and 16-bit colours are
synthesised from the index. No numpy: about 1 s per million points.

    scripts/ply_to_las.py big20M.ply big20M.las
"""
import struct
import sys
from array import array


def read_ply(path):
    with open(path, "rb") as f:
        header = b""
        while not header.endswith(b"end_header\n"):
            header += f.readline()
        lines = header.decode().split("\n")
        assert "format binary_little_endian 1.0" in lines, "binary little-endian PLY only"
        count = next(int(l.split()[2]) for l in lines if l.startswith("element vertex"))
        props = [l.split()[1:] for l in lines if l.startswith("property")]
        assert props[:3] == [["float", "x"], ["float", "y"], ["float", "z"]] and len(props) == 3, props
        xyz = array("f")
        xyz.frombytes(f.read(12 * count))
        return count, xyz


def main(src, dst):
    count, xyz = read_ply(src)
    scale, offset = 1e-6, (500000.0, 4649000.0, 100.0)
    lo = [min(xyz[a::3]) for a in range(3)]
    hi = [max(xyz[a::3]) for a in range(3)]
    header = bytearray(227)
    header[0:4] = b"LASF"
    header[24:26] = bytes([1, 2])
    header[26:58] = b"pcsketch ply_to_las".ljust(32, b"\0")
    struct.pack_into("<HIIBHI", header, 94, 227, 227, 0, 2, 26, count)
    struct.pack_into("<3d3d", header, 131, scale, scale, scale, *offset)
    struct.pack_into("<6d", header, 179, hi[0] + offset[0], lo[0] + offset[0], hi[1] + offset[1], lo[1] + offset[1],
                     hi[2] + offset[2], lo[2] + offset[2])
    record = struct.Struct("<3iHBBbBH3H")
    classes = (2, 6, 7)
    with open(dst, "wb") as out:
        out.write(header)
        block = 1 << 20
        for start in range(0, count, block):
            buf = bytearray(record.size * min(block, count - start))
            for k, i in enumerate(range(start, min(start + block, count))):
                x, y, z = xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]
                record.pack_into(buf, k * record.size, round(x / scale), round(y / scale), round(z / scale),
                                 i * 37 % 65536, 0x09, classes[i % 3], 0, 0, 0,
                                 (i % 256) * 257, (i // 256 % 256) * 257, 7 * 257)
            out.write(buf)


if __name__ == "__main__":
    main(*sys.argv[1:3])
