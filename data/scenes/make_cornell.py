#!/usr/bin/env python3
"""Generate Prism's default scene, data/scenes/cornell.gltf.

Builds a Cornell box as a single self-contained glTF 2.0 file (binary buffer
embedded as a base64 data URI): floor, ceiling, back wall, red left wall,
green right wall, the short white block with a gold sphere on it, a copper
sphere, a dispersive flint-glass prism where the tall block stood, a
rectangular ceiling light and the reference perspective camera.

Run from the repository root:
    python3 data/scenes/make_cornell.py            # writes cornell.gltf
    python3 data/scenes/make_cornell.py --check    # writes, then validates it

Geometry and camera follow the published Cornell Box data (Cornell University
Program of Computer Graphics, "Cornell Box Data",
https://www.graphics.cornell.edu/online/box/data.html), converted from
millimetres to metres. That data is right-handed (x towards the red wall,
y up, z away from the camera), like glTF, so it is used unmirrored. Walls are
the published quads (ceiling without the light hole); the light sits 0.1 mm
below the ceiling. The RGB albedos are the widely used linear Rec.709
approximations of the measured spectral reflectances, not the measured data.

Standard library only (helpers in gltf_builder.py). To add an object, append one line to OBJECTS, e.g.
    ("copper_sphere", uv_sphere((0.40, 0.10, 0.15), 0.10, 64), metal("copper", (0.95, 0.64, 0.54), 0.1)),
"""
import base64
import json
import math
import os
import struct
import sys

from gltf_builder import (add, box, build_gltf, cross, diffuse, dot, emitter, glass, mean, metal, normalize,
                          prism, quad, scale, sub, uv_sphere, write_gltf)

MM = 0.001  # published data is in millimetres
def mm(*pts): return [scale(p, MM) for p in pts]

# Linear Rec.709 approximations of the measured Cornell reflectances.
WHITE = diffuse("white", (0.73, 0.73, 0.73))
RED = diffuse("red", (0.63, 0.065, 0.05))
GREEN = diffuse("green", (0.14, 0.45, 0.091))
LIGHT = emitter("light", (1.0, 0.78, 0.55), 20.0, (0.78, 0.78, 0.78))
# Measured optics in Prism (extras), close glTF equivalents for other viewers.
COPPER = metal("copper", (0.955, 0.638, 0.538), 0.0, "Cu")
GOLD = metal("gold", (1.0, 0.782, 0.344), 0.0, "Au")
FLINT = glass("flint_glass", 1.78472, 25.68, 1.0, "N-SF11")  # SCHOTT N-SF11: strong dispersion

# ---------------------------------------------------------------- scene
SHORT_BLOCK = [
    [(130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0), (290.0, 165.0, 114.0)],
    [(290.0, 0.0, 114.0), (290.0, 165.0, 114.0), (240.0, 165.0, 272.0), (240.0, 0.0, 272.0)],
    [(130.0, 0.0, 65.0), (130.0, 165.0, 65.0), (290.0, 165.0, 114.0), (290.0, 0.0, 114.0)],
    [(82.0, 0.0, 225.0), (82.0, 165.0, 225.0), (130.0, 165.0, 65.0), (130.0, 0.0, 65.0)],
    [(240.0, 0.0, 272.0), (240.0, 165.0, 272.0), (82.0, 165.0, 225.0), (82.0, 0.0, 225.0)]]
LIGHT_Y = 548.8 - 0.1  # 0.1 mm below the ceiling

# (name, mesh, material). Published quads are already CCW seen from the room.
OBJECTS = [
    ("floor", quad(*mm((552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2))), WHITE),
    ("ceiling", quad(*mm((556, 548.8, 0), (556, 548.8, 559.2), (0, 548.8, 559.2), (0, 548.8, 0))), WHITE),
    ("back_wall", quad(*mm((549.6, 0, 559.2), (0, 0, 559.2), (0, 548.8, 559.2), (556, 548.8, 559.2))), WHITE),
    ("left_wall", quad(*mm((552.8, 0, 0), (549.6, 0, 559.2), (556, 548.8, 559.2), (556, 548.8, 0))), RED),
    ("right_wall", quad(*mm((0, 0, 559.2), (0, 0, 0), (0, 548.8, 0), (0, 548.8, 559.2))), GREEN),
    ("short_block", box([mm(*f) for f in SHORT_BLOCK]), WHITE),
    ("copper_sphere", uv_sphere(mm((370.0, 110.0, 380.0))[0], 0.110, 64), COPPER),
    ("gold_sphere", uv_sphere(mm((186.0, 245.0, 168.0))[0], 0.080, 64), GOLD),
    ("glass_prism", prism(mm((410.0, 0.0, 130.0))[0], 0.150, 0.200, 25.0), FLINT),
    ("light", quad(*mm((343, LIGHT_Y, 227), (343, LIGHT_Y, 332), (213, LIGHT_Y, 332), (213, LIGHT_Y, 227))), LIGHT),
]

# Published camera: eye (278, 273, -800) mm looking along +z, up +y, 35 mm
# lens, 25 mm x 25 mm film. glTF cameras look down local -z, so rotate 180
# degrees about y: local -z -> world +z, local +x (image right) -> world -x.
CAMERA = {"name": "camera", "translation": list(mm((278.0, 273.0, -800.0))[0]),
          "rotation": [0.0, 1.0, 0.0, 0.0],
          "yfov": 2.0 * math.atan(0.0125 / 0.035), "aspectRatio": 1.0, "znear": 0.01}

# ---------------------------------------------------------------- --check
def check(path):
    g = json.load(open(path))
    buf = base64.b64decode(g["buffers"][0]["uri"].split(",", 1)[1])
    assert len(buf) == g["buffers"][0]["byteLength"]
    size = {"SCALAR": 1, "VEC3": 3}

    def read(i):
        a = g["accessors"][i]
        v = g["bufferViews"][a["bufferView"]]
        n = a["count"] * size[a["type"]]
        assert v["byteOffset"] + v["byteLength"] <= len(buf) and 4 * n <= v["byteLength"]
        vals = struct.unpack_from("<%d%s" % (n, "I" if a["componentType"] == 5125 else "f"), buf, v["byteOffset"])
        return [vals[k:k + 3] for k in range(0, n, 3)] if a["type"] == "VEC3" else list(vals)

    room_centre = (0.278, 0.274, 0.28)
    walls = {"floor", "ceiling", "back_wall", "left_wall", "right_wall", "light"}
    centroid = {}
    for mesh in g["meshes"]:
        p = mesh["primitives"][0]
        pos, nrm, idx = read(p["attributes"]["POSITION"]), read(p["attributes"]["NORMAL"]), read(p["indices"])
        acc = g["accessors"][p["attributes"]["POSITION"]]
        assert acc["min"] == [min(c) for c in zip(*pos)] and acc["max"] == [max(c) for c in zip(*pos)]
        assert len(nrm) == len(pos) and len(idx) % 3 == 0 and max(idx) < len(pos) and p["mode"] == 4
        assert all(abs(dot(n, n) - 1) < 1e-5 for n in nrm)
        c = centroid[mesh["name"]] = mean(pos)
        for t in range(0, len(idx), 3):
            a, b, cc = (pos[k] for k in idx[t:t + 3])
            ng = cross(sub(b, a), sub(cc, a))
            assert dot(ng, ng) > 1e-16, "degenerate triangle in " + mesh["name"]
            ng = normalize(ng)
            for k in idx[t:t + 3]:
                assert dot(ng, nrm[k]) > 0.5, "normal/winding mismatch in " + mesh["name"]
                out = sub(room_centre, pos[k]) if mesh["name"] in walls else sub(pos[k], c)
                assert dot(nrm[k], out) > 0, "normal points the wrong way in " + mesh["name"]
        print("  %-12s %5d triangles  material=%s" % (mesh["name"], len(idx) // 3,
                                                     g["materials"][p["material"]]["name"]))
    # Camera: image right is the camera node's local +x rotated into the world.
    cam = next(n for n in g["nodes"] if "camera" in n)
    q, w = cam["rotation"][:3], cam["rotation"][3]
    rot = lambda v: add(add(v, scale(cross(q, v), 2 * w)), scale(cross(q, cross(q, v)), 2))
    eye, right, fwd = cam["translation"], rot((1, 0, 0)), rot((0, 0, -1))
    assert dot(fwd, (0, 0, 1)) > 0.999999 and dot(rot((0, 1, 0)), (0, 1, 0)) > 0.999999
    red_x = dot(sub(centroid["left_wall"], eye), right)
    green_x = dot(sub(centroid["right_wall"], eye), right)
    assert red_x < 0 < green_x, "red wall must be on the image's left"
    print("  camera: forward=%s right=%s; red wall x=%+.3f (left), green x=%+.3f (right)"
          % (fwd, right, red_x, green_x))
    print("%s OK (%d bytes)" % (path, os.path.getsize(path)))

def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cornell.gltf")
    write_gltf(out, build_gltf(OBJECTS, CAMERA, "Prism make_cornell.py",
                               "Geometry: Cornell Box Data, Cornell University Program of Computer "
                               "Graphics (https://www.graphics.cornell.edu/online/box/data.html); "
                               "scene file: Prism project", "cornell_box"))
    if "--check" in sys.argv[1:]:
        check(out)

if __name__ == "__main__":
    main()
