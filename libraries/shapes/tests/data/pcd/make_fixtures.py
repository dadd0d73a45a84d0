#!/usr/bin/env python3
"""Writes the PCD fixtures of this folder, independently of shroud's writer.

Each file is laid out as PCL's pcd_io writes it (header lines, `_` padding
fields, rgb packed as a float, NaN for invalid points of organised clouds).
The binary_compressed fixture is LZF-encoded by the small encoder below
(literal runs, plus back references at distance 1 for runs of one byte), not
by the `lzf` crate the reader uses.

Point k of the unorganised fixtures (k = 0, 1, ...):
    x = k / 2 - 1, y = 2 - k / 4, z = k * k / 8, intensity = 10 k + 5,
all exact in f32. Run from this folder: python3 make_fixtures.py
"""

import math
import struct

HEADER = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"
VIEWPOINT = "VIEWPOINT 0 0 0 1 0 0 0\n"


def point(k):
    return (k / 2 - 1, 2 - k / 4, k * k / 8, 10 * k + 5)


def rgb(k):
    """PCL packs 8-bit r, g, b (and alpha 255) into one 32-bit word."""
    return 0xFF000000 | (k * 40 % 256) << 16 | (255 - k) << 8 | 7


def header(fields, sizes, types, counts, width, height, data):
    return (
        HEADER
        + f"FIELDS {fields}\nSIZE {sizes}\nTYPE {types}\nCOUNT {counts}\n"
        + f"WIDTH {width}\nHEIGHT {height}\n{VIEWPOINT}POINTS {width * height}\n"
        + f"DATA {data}\n"
    ).encode()


def ascii_xyz_rgb_intensity(n=8):
    """PCL's ASCII writer: rgb written as the unsigned integer of its bits."""
    out = header("x y z rgb intensity", "4 4 4 4 4", "F F F F F", "1 1 1 1 1", n, 1, "ascii")
    for k in range(n):
        x, y, z, i = point(k)
        out += f"{x:g} {y:g} {z:g} {rgb(k)} {i:g}\n".encode()
    return out


def binary_xyzi_padded(n=6):
    """A pcl::PCLPointCloud2 of pcl::PointXYZI written in binary: PCL's memory
    layout (x y z, 4 padding bytes, intensity, 12 padding bytes: 32 bytes a
    point) with the padding named `_`."""
    out = header("x y z _ intensity _", "4 4 4 1 4 1", "F F F U F U", "1 1 1 4 1 12", n, 1, "binary")
    for k in range(n):
        x, y, z, i = point(k)
        out += struct.pack("<fff", x, y, z) + b"\xaa" * 4 + struct.pack("<f", i) + b"\xbb" * 12
    return out


def binary_intensity_first(n=5):
    """Intensity first as uint16, double coordinates, then rgb and a label."""
    out = header("intensity x y z rgb label", "2 8 8 8 4 4", "U F F F F U", "1 1 1 1 1 1", n, 1, "binary")
    for k in range(n):
        x, y, z, i = point(k)
        out += struct.pack("<Hddd", int(i), x, y, z)
        out += struct.pack("<I", rgb(k)) + struct.pack("<I", 100 + k)
    return out


def lzf_encode(data):
    """LZF (liblzf's format): a control byte < 32 starts a literal run of
    control + 1 bytes; a control byte (len << 5 | offset_high), [len - 7 when
    len = 7], offset_low copies len + 2 bytes from offset + 1 bytes back.
    Runs of one repeated byte become back references at distance 1."""
    out = bytearray()
    literal = bytearray()

    def flush():
        for start in range(0, len(literal), 32):
            run = literal[start:start + 32]
            out.append(len(run) - 1)
            out.extend(run)
        literal.clear()

    i = 0
    while i < len(data):
        run = 1
        while i + run < len(data) and data[i + run] == data[i] and run < 1 + 264:
            run += 1
        if run >= 4:
            literal.append(data[i])  # the byte the reference copies
            flush()
            copy = run - 1  # 3 ..= 264 bytes, distance 1 (offset 0)
            length = copy - 2
            if length < 7:
                out.append(length << 5)
            else:
                out.extend([7 << 5, length - 7])
            out.append(0)
            i += run
        else:
            literal.append(data[i])
            i += 1
    flush()
    return bytes(out)


def compressed_xyz_rgb_fpfh_intensity(n=7):
    """binary_compressed: field-major data (all x, all y, ... each field's
    COUNT x SIZE bytes per point), a 33-float fpfh histogram that is mostly
    zeros, and the intensity last."""
    out = header(
        "x y z rgb fpfh intensity", "4 4 4 4 4 4", "F F F F F F", "1 1 1 1 33 1", n, 1, "binary_compressed"
    )
    columns = [b"", b"", b"", b"", b"", b""]
    for k in range(n):
        x, y, z, i = point(k)
        columns[0] += struct.pack("<f", x)
        columns[1] += struct.pack("<f", y)
        columns[2] += struct.pack("<f", z)
        columns[3] += struct.pack("<I", rgb(k))
        histogram = [0.0] * 33
        histogram[k] = 100.0
        columns[4] += struct.pack("<33f", *histogram)
        columns[5] += struct.pack("<f", i)
    raw = b"".join(columns)
    packed = lzf_encode(raw)
    assert len(packed) < len(raw)
    return out + struct.pack("<II", len(packed), len(raw)) + packed


def organised(width=4, height=3):
    """A 4 x 3 organised pcl::PointXYZ cloud (binary, with PCL's 4 padding
    bytes) whose points 1, 6 and 11 are invalid: NaN x, y and z. Point
    r * width + c is (c, r, c + r) otherwise."""
    out = header("x y z _", "4 4 4 1", "F F F U", "1 1 1 4", width, height, "binary")
    for r in range(height):
        for c in range(width):
            k = r * width + c
            xyz = (math.nan,) * 3 if k in (1, 6, 11) else (c, r, c + r)
            out += struct.pack("<fff", *xyz) + b"\x00" * 4
    return out


def organised_ascii(width=3, height=2):
    """The same convention in ASCII: PCL writes invalid points as `nan`."""
    out = header("x y z", "4 4 4", "F F F", "1 1 1", width, height, "ascii")
    for r in range(height):
        for c in range(width):
            k = r * width + c
            out += b"nan nan nan\n" if k in (1, 6, 11) else f"{c} {r} {c + r}\n".encode()
    return out


FIXTURES = {
    "xyz_rgb_intensity_ascii.pcd": ascii_xyz_rgb_intensity,
    "xyzi_padded_binary.pcd": binary_xyzi_padded,
    "intensity_first_binary.pcd": binary_intensity_first,
    "xyz_rgb_fpfh_intensity_compressed.pcd": compressed_xyz_rgb_fpfh_intensity,
    "organised_nan_binary.pcd": organised,
    "organised_nan_ascii.pcd": organised_ascii,
}

if __name__ == "__main__":
    for name, make in FIXTURES.items():
        with open(name, "wb") as f:
            f.write(make())
