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

Standard library only. To add an object, append one line to OBJECTS, e.g.
    ("copper_sphere", uv_sphere((0.40, 0.10, 0.15), 0.10, 64), metal("copper", (0.95, 0.64, 0.54), 0.1)),
"""
import base64
import json
import math
import os
import struct
import sys

MM = 0.001  # published data is in millimetres

# ---------------------------------------------------------------- vectors
def add(a, b): return tuple(x + y for x, y in zip(a, b))
def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def scale(a, s): return tuple(x * s for x in a)
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def normalize(a): return scale(a, 1.0 / math.sqrt(dot(a, a)))
def mean(pts): return scale(tuple(map(sum, zip(*pts))), 1.0 / len(pts))
def mm(*pts): return [scale(p, MM) for p in pts]
def rot_y(p, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return (c * p[0] + s * p[2], p[1], -s * p[0] + c * p[2])

# ---------------------------------------------------------------- meshes
# A mesh is a dict of parallel lists: positions, normals (tuples) and indices.
def merge(*meshes):
    out = {"positions": [], "normals": [], "indices": []}
    for m in meshes:
        base = len(out["positions"])
        out["positions"] += m["positions"]
        out["normals"] += m["normals"]
        out["indices"] += [base + i for i in m["indices"]]
    return out

def polygon(*pts):
    """Flat convex polygon, vertices counter-clockwise seen from the front
    (normal) side; fan-triangulated. A non-planar quad (the published left
    wall is slightly twisted) gets one flat normal per triangle instead."""
    n = normalize(tuple(sum(c) for c in zip(*(cross(pts[i], pts[(i + 1) % len(pts)])
                                               for i in range(len(pts))))))  # Newell
    if all(abs(dot(n, sub(p, pts[0]))) < 1e-9 for p in pts):
        return {"positions": list(pts), "normals": [n] * len(pts),
                "indices": [j for i in range(1, len(pts) - 1) for j in (0, i, i + 1)]}
    tris = [(pts[0], pts[i], pts[i + 1]) for i in range(1, len(pts) - 1)]
    return merge(*(polygon(*t) for t in tris))

def quad(a, b, c, d):
    return polygon(a, b, c, d)

def convex_solid(faces):
    """Closed (or bottomless) convex solid from polygons given in any winding;
    each face is turned to face away from the solid's centroid."""
    centre = mean([p for f in faces for p in f])
    out = []
    for f in faces:
        f = list(f)
        if dot(cross(sub(f[1], f[0]), sub(f[2], f[0])), sub(mean(f), centre)) < 0:
            f.reverse()
        out.append(polygon(*f))
    return merge(*out)

def box(faces):
    """Box from 5 or 6 explicit quads (e.g. the published block vertex lists)."""
    assert len(faces) in (5, 6) and all(len(f) == 4 for f in faces)
    return convex_solid(faces)

def cuboid(centre, size, yaw_deg=0.0):
    """Axis-aligned box (size = full extents), rotated yaw_deg about +y."""
    h = scale(size, 0.5)
    corner = lambda sx, sy, sz: add(centre, rot_y((sx * h[0], sy * h[1], sz * h[2]), yaw_deg))
    # each face: fix coordinate `axis` to `side`, walk the other two around the square
    faces = []
    for axis in range(3):
        u, v = [k for k in range(3) if k != axis]
        for side in (-1, 1):
            face = []
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                s = [0, 0, 0]
                s[axis], s[u], s[v] = side, a, b
                face.append(corner(*s))
            faces.append(face)
    return box(faces)

def uv_sphere(centre, radius, segments):
    """UV sphere with `segments` longitudes and segments//2 latitudes. Smooth
    (radial) normals, since it approximates a curved surface."""
    rings = max(2, segments // 2)
    pos, nrm, idx = [], [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(segments + 1):
            ph = 2.0 * math.pi * j / segments
            n = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            pos.append(add(centre, scale(n, radius)))
            nrm.append(n)
    at = lambda i, j: i * (segments + 1) + j
    for i in range(rings):
        for j in range(segments):
            a, b, c, d = at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)
            if i > 0:
                idx += [a, b, c]          # skip degenerate triangles at the poles
            if i < rings - 1:
                idx += [a, c, d]
    return {"positions": pos, "normals": nrm, "indices": idx}

def prism(base_centre, side, length, yaw_deg=0.0):
    """Equilateral triangular prism lying on one rectangular face: triangle of
    edge `side` in the local xy plane, extruded `length` along local z, then
    rotated yaw_deg about +y. base_centre is the centre of the bottom face."""
    tri = [(-side / 2, 0.0), (side / 2, 0.0), (0.0, side * math.sqrt(3.0) / 2)]
    end = lambda z: [add(base_centre, rot_y((x, y, z), yaw_deg)) for x, y in tri]
    f, b = end(-length / 2), end(length / 2)
    sides = [[f[i], f[(i + 1) % 3], b[(i + 1) % 3], b[i]] for i in range(3)]
    return convex_solid([f, b] + sides)

# ---------------------------------------------------------------- materials
def diffuse(name, rgb):
    return {"name": name, "pbrMetallicRoughness": {
        "baseColorFactor": list(rgb) + [1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}

def emitter(name, rgb, strength, base_rgb):
    m = diffuse(name, base_rgb)
    m["emissiveFactor"] = list(rgb)
    m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
    return m

def metal(name, rgb, roughness, catalogue=None):
    """Metal coloured rgb for any glTF viewer; `catalogue` names Prism's measured n, k table."""
    m = {"name": name, "pbrMetallicRoughness": {
        "baseColorFactor": list(rgb) + [1.0], "metallicFactor": 1.0, "roughnessFactor": roughness}}
    if catalogue:
        m["extras"] = {"prism": {"metal": catalogue}}
    return m

def glass(name, ior, abbe, thickness, catalogue=None):
    """Clear dielectric; KHR_materials_dispersion uses dispersion = 20 / Abbe. `catalogue`
    names Prism's measured dispersion formula for the same glass."""
    m = diffuse(name, (1.0, 1.0, 1.0))
    m["pbrMetallicRoughness"]["roughnessFactor"] = 0.0
    m["extensions"] = {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                       "KHR_materials_ior": {"ior": ior},
                       "KHR_materials_volume": {"thicknessFactor": thickness},
                       "KHR_materials_dispersion": {"dispersion": 20.0 / abbe}}
    if catalogue:
        m["extras"] = {"prism": {"glass": catalogue}}
    return m

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

# ---------------------------------------------------------------- glTF writer
def f32(v):
    return struct.unpack("<f", struct.pack("<f", v))[0]

def build_gltf(objects, camera):
    blob = bytearray()
    g = {"asset": {"version": "2.0", "generator": "Prism make_cornell.py",
                   "copyright": "Geometry: Cornell Box Data, Cornell University Program of Computer "
                                "Graphics (https://www.graphics.cornell.edu/online/box/data.html); "
                                "scene file: Prism project"},
         "scene": 0, "scenes": [{"name": "cornell_box", "nodes": []}], "nodes": [], "meshes": [],
         "materials": [], "cameras": [], "accessors": [], "bufferViews": [], "buffers": []}

    def accessor(data, fmt, ctype, atype, target, bounds=False):
        flat = [x for item in data for x in (item if isinstance(item, tuple) else (item,))]
        g["bufferViews"].append({"buffer": 0, "byteOffset": len(blob),
                                 "byteLength": 4 * len(flat), "target": target})
        blob.extend(struct.pack("<%d%s" % (len(flat), fmt), *flat))
        acc = {"bufferView": len(g["bufferViews"]) - 1, "componentType": ctype,
               "count": len(data), "type": atype}
        if bounds:
            acc["min"] = [min(f32(p[k]) for p in data) for k in range(3)]
            acc["max"] = [max(f32(p[k]) for p in data) for k in range(3)]
        g["accessors"].append(acc)
        return len(g["accessors"]) - 1

    mat_index = {}
    for name, mesh, mat in objects:
        if mat["name"] not in mat_index:
            mat_index[mat["name"]] = len(g["materials"])
            g["materials"].append(mat)
        assert g["materials"][mat_index[mat["name"]]] == mat, "two materials named " + mat["name"]
        prim = {"attributes": {
                    "POSITION": accessor(mesh["positions"], "f", 5126, "VEC3", 34962, bounds=True),
                    "NORMAL": accessor(mesh["normals"], "f", 5126, "VEC3", 34962)},
                "indices": accessor(mesh["indices"], "I", 5125, "SCALAR", 34963),
                "material": mat_index[mat["name"]], "mode": 4}
        g["meshes"].append({"name": name, "primitives": [prim]})
        g["nodes"].append({"name": name, "mesh": len(g["meshes"]) - 1})

    g["cameras"].append({"name": camera["name"], "type": "perspective", "perspective": {
        k: camera[k] for k in ("aspectRatio", "yfov", "znear")}})
    g["nodes"].append({"name": camera["name"], "camera": 0,
                       "translation": camera["translation"], "rotation": camera["rotation"]})
    g["scenes"][0]["nodes"] = list(range(len(g["nodes"])))
    g["buffers"].append({"byteLength": len(blob), "uri": "data:application/octet-stream;base64,"
                         + base64.b64encode(bytes(blob)).decode("ascii")})
    used = sorted({e for m in g["materials"] for e in m.get("extensions", {})})
    if used:
        g["extensionsUsed"] = used
    return g

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
    with open(out, "w") as f:
        json.dump(build_gltf(OBJECTS, CAMERA), f, indent=1)
        f.write("\n")
    print("wrote", out)
    if "--check" in sys.argv[1:]:
        check(out)

if __name__ == "__main__":
    main()
