#!/usr/bin/env python3
"""Seed corpora for the fuzz targets: make_corpus.py OUTDIR writes OUTDIR/<target>/<seed>.

fuzz_gltf     valid .gltf (buffers as data: URIs) and .glb scenes, and the hostile cases of
              tests/hostile/make_cases.py that fit in one file
fuzz_env_map  small uncompressed OpenEXR and Radiance HDR images
fuzz_image    small PNG, BMP, TGA and PPM images
Standard library only; deterministic.
"""

import base64
import json
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "hostile"))
import make_cases  # noqa: E402


def exr(width, height, value=0.5):
    """A scanline OpenEXR file, uncompressed, float B, G, R channels (OpenEXR file layout)."""

    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data

    channels = b"".join(c + b"\0" + struct.pack("<iBBBBii", 2, 0, 0, 0, 0, 1, 1) for c in (b"B", b"G", b"R")) + b"\0"
    box = struct.pack("<4i", 0, 0, width - 1, height - 1)
    header = (
        attr("channels", "chlist", channels)
        + attr("compression", "compression", b"\0")
        + attr("dataWindow", "box2i", box)
        + attr("displayWindow", "box2i", box)
        + attr("lineOrder", "lineOrder", b"\0")
        + attr("pixelAspectRatio", "float", struct.pack("<f", 1))
        + attr("screenWindowCenter", "v2f", struct.pack("<2f", 0, 0))
        + attr("screenWindowWidth", "float", struct.pack("<f", 1))
        + b"\0"
    )
    start = 8 + len(header) + 8 * height
    line = struct.pack("<f", value) * (3 * width)
    lines = [struct.pack("<ii", y, len(line)) + line for y in range(height)]
    offsets = b"".join(struct.pack("<Q", start + y * len(lines[0])) for y in range(height))
    return b"\x76\x2f\x31\x01" + struct.pack("<I", 2) + header + offsets + b"".join(lines)


def hdr(width, height, rle=False):
    head = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + f"-Y {height} +X {width}\n".encode()
    if not rle:
        return head + b"\x80\x40\x20\x81" * (width * height)
    # New-style RLE scanlines: 2, 2, width, then each component as runs.
    body = b""
    for _ in range(height):
        body += bytes([2, 2, width >> 8, width & 255])
        for value in (0x80, 0x40, 0x20, 0x81):
            body += bytes([128 + width, value])
    return head + body


def bmp(width, height):
    row = (b"\x20\x40\x80" * width).ljust((3 * width + 3) // 4 * 4, b"\0")
    pixels = row * height
    return (b"BM" + struct.pack("<IHHI", 54 + len(pixels), 0, 0, 54)
            + struct.pack("<IiiHHIIiiII", 40, width, height, 1, 24, 0, len(pixels), 2835, 2835, 0, 0) + pixels)


def tga(width, height):
    return struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, width, height, 24, 0) + b"\x20\x40\x80" * (width * height)


def gltf_single_file(g, binary):
    g = json.loads(json.dumps(g))
    g["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(binary).decode()
    g["buffers"][0]["byteLength"] = len(binary)
    return json.dumps(g, separators=(",", ":")).encode()


def seeds():
    B = make_cases.base_gltf
    out = {"fuzz_gltf": {}, "fuzz_env_map": {}, "fuzz_image": {}}
    g = out["fuzz_gltf"]
    g["valid.gltf"] = gltf_single_file(B(), make_cases.base_bin())
    g["valid_colors.gltf"] = gltf_single_file(B(colors=True), make_cases.base_bin([(1, 0, 0), (0, 1, 0), (0, 0, 1)]))
    g["valid.glb"] = make_cases.glb(make_cases.glb_gltf(), make_cases.base_bin())
    textured = make_cases.textured(B(), {"uri": "data:image/png;base64," + base64.b64encode(make_cases.png(2, 2)).decode()})
    g["textured.gltf"] = gltf_single_file(textured, make_cases.base_bin())
    make_cases.build_cases()
    for c in make_cases.CASES:  # single-file hostile cases, with their buffer inlined
        files = c["files"]
        if len(files) == 1 and c["scene"] in files and not c["links"]:
            g[c["name"] + os.path.splitext(c["scene"])[1]] = files[c["scene"]][:200000]
        elif set(files) == {"scene.gltf", "tri.bin"} and not c["links"]:
            try:
                g[c["name"] + ".gltf"] = gltf_single_file(json.loads(files["scene.gltf"]), files["tri.bin"])
            except (ValueError, KeyError, IndexError):
                pass
    e = out["fuzz_env_map"]
    e["grey.exr"] = exr(4, 2)
    e["bright.exr"] = exr(3, 3, 1e6)
    e["grey.hdr"] = hdr(4, 2)
    e["rle.hdr"] = hdr(16, 2, rle=True)
    i = out["fuzz_image"]
    i["rgb.png"] = make_cases.png(4, 4)
    i["rgb.bmp"] = bmp(3, 2)
    i["rgb.tga"] = tga(3, 2)
    i["rgb.ppm"] = b"P6\n2 2\n255\n" + b"\x20\x40\x80" * 4
    i["gray.pgm"] = b"P5\n2 2\n255\n" + b"\x10\x20\x30\x40"
    i["header_only.png"] = make_cases.png(100000, 100000, pixels=False)
    return out


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: make_corpus.py OUTDIR")
    total = 0
    for target, files in seeds().items():
        os.makedirs(os.path.join(sys.argv[1], target), exist_ok=True)
        for name, data in files.items():
            with open(os.path.join(sys.argv[1], target, name), "wb") as f:
                f.write(data)
        total += len(files)
    print(f"{total} seeds in {sys.argv[1]}")
