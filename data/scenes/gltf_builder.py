"""Building blocks for Prism's generated glTF scenes (standard library only): vector helpers,
flat and smooth meshes, glTF materials, and a writer of self-contained .gltf files (buffer embedded
as a base64 data URI). Used by the make_*.py scripts here and stress/make_stress.py.
"""
import base64
import json
import math
import struct
import zlib

# ---------------------------------------------------------------- vectors
def add(a, b): return tuple(x + y for x, y in zip(a, b))
def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def scale(a, s): return tuple(x * s for x in a)
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def normalize(a): return scale(a, 1.0 / math.sqrt(dot(a, a)))
def mean(pts): return scale(tuple(map(sum, zip(*pts))), 1.0 / len(pts))
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

def room(half_width, height, depth, floor, walls):
    """The six inner faces of a box room, x in [-half_width, half_width], y in [0, height], z in
    [0, depth], facing inwards: (name, mesh, material) objects, the floor's material `floor`."""
    w, h, d = half_width, height, depth
    return [
        ("floor", quad((-w, 0, 0), (-w, 0, d), (w, 0, d), (w, 0, 0)), floor),
        ("ceiling", quad((-w, h, 0), (w, h, 0), (w, h, d), (-w, h, d)), walls),
        ("left_wall", quad((-w, 0, 0), (-w, h, 0), (-w, h, d), (-w, 0, d)), walls),
        ("right_wall", quad((w, 0, 0), (w, 0, d), (w, h, d), (w, h, 0)), walls),
        ("far_wall", quad((-w, 0, d), (-w, h, d), (w, h, d), (w, 0, d)), walls),
        ("near_wall", quad((-w, 0, 0), (w, 0, 0), (w, h, 0), (-w, h, 0)), walls),
    ]

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
        # The poles' vertices and the seam's two columns at the very same positions (sin π and
        # sin 2π are not 0 in floating point): the sphere is closed (accel/closed_surface.h).
        sin_th = 0.0 if i in (0, rings) else math.sin(th)
        cos_th = 1.0 if i == 0 else -1.0 if i == rings else math.cos(th)
        for j in range(segments + 1):
            ph = 2.0 * math.pi * (j % segments) / segments
            n = (sin_th * math.cos(ph), cos_th, sin_th * math.sin(ph))
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

def turned_disk(centre, radius, segments):
    """Flat disk facing +y, as if turned on a lathe: its tangents run around the centre (the
    direction of KHR_materials_anisotropy's brushing)."""
    pos, nrm, tan, idx = [centre], [(0.0, 1.0, 0.0)], [(1.0, 0.0, 0.0, 1.0)], []
    for j in range(segments):
        ph = 2.0 * math.pi * j / segments
        pos.append(add(centre, (radius * math.cos(ph), 0.0, radius * math.sin(ph))))
        nrm.append((0.0, 1.0, 0.0))
        tan.append((-math.sin(ph), 0.0, math.cos(ph), 1.0))
        idx += [0, 1 + (j + 1) % segments, 1 + j]
    return {"positions": pos, "normals": nrm, "tangents": tan, "indices": idx}

def with_longitude_tangents(sphere):
    """A uv_sphere's tangents along its latitude circles (brushed around the vertical axis)."""
    tan = []
    for n in sphere["normals"]:
        t = (-n[2], 0.0, n[0])
        tan.append(normalize(t) + (1.0,) if dot(t, t) > 1e-12 else (1.0, 0.0, 0.0, 1.0))
    return dict(sphere, tangents=tan)

def prism(base_centre, side, length, yaw_deg=0.0):
    """Equilateral triangular prism lying on one rectangular face: triangle of
    edge `side` in the local xy plane, extruded `length` along local z, then
    rotated yaw_deg about +y. base_centre is the centre of the bottom face."""
    tri = [(-side / 2, 0.0), (side / 2, 0.0), (0.0, side * math.sqrt(3.0) / 2)]
    end = lambda z: [add(base_centre, rot_y((x, y, z), yaw_deg)) for x, y in tri]
    f, b = end(-length / 2), end(length / 2)
    sides = [[f[i], f[(i + 1) % 3], b[(i + 1) % 3], b[i]] for i in range(3)]
    return convex_solid([f, b] + sides)

def lathe(centre, profile, segments):
    """Solid of revolution about the vertical axis through `centre`: `profile` is a closed loop of
    (radius, height) points, walked so that the material lies to its left (counter-clockwise in
    the r-y plane). Each profile edge becomes a band of quads, smooth around the axis and sharp at
    the profile's corners; bands that touch the axis become fans."""
    pos, nrm, idx = [], [], []
    for (r0, y0), (r1, y1) in zip(profile, profile[1:] + profile[:1]):
        length = math.hypot(r1 - r0, y1 - y0)
        nr, ny = (y1 - y0) / length, -(r1 - r0) / length  # the edge's outward normal in the r-y plane
        base = len(pos)
        for j in range(segments + 1):
            ph = 2.0 * math.pi * j / segments
            c, s = math.cos(ph), math.sin(ph)
            for r, y in ((r0, y0), (r1, y1)):
                pos.append(add(centre, (r * c, y, r * s)))
                nrm.append((nr * c, ny, nr * s))
        for j in range(segments):
            a, b, c_, d = base + 2 * j, base + 2 * j + 1, base + 2 * j + 3, base + 2 * j + 2
            if r0 > 0:
                idx += [a, b, d]
            if r1 > 0:
                idx += [b, c_, d]
    return {"positions": pos, "normals": nrm, "indices": idx}

def tumbler_profiles(radius, height, wall, bottom, liquid_top, gap):
    """lathe() profiles of a tumbler of outer `radius` and `height`, with walls `wall` and a base
    `bottom` thick, and of the liquid in it up to `liquid_top`, `gap` short of the glass all round
    (an air film, so that no two surfaces coincide)."""
    glass = [(0.0, 0.0), (radius, 0.0), (radius, height), (radius - wall, height), (radius - wall, bottom),
             (0.0, bottom)]
    r = radius - wall - gap
    liquid = [(0.0, bottom + gap), (r, bottom + gap), (r, liquid_top), (0.0, liquid_top)]
    return glass, liquid

def facing_square(centre, target, size):
    """A square of edge `size` at centre, its front side facing target."""
    n = normalize(sub(target, centre))
    u = normalize(cross(n, (0.0, 1.0, 0.0)))
    v = cross(u, n)
    h = size / 2
    at = lambda a, b: add(centre, add(scale(u, a * h), scale(v, b * h)))
    return quad(at(-1, -1), at(-1, 1), at(1, 1), at(1, -1))

# ---------------------------------------------------------------- materials
def diffuse(name, rgb):
    return {"name": name, "pbrMetallicRoughness": {
        "baseColorFactor": list(rgb) + [1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}

def lambert(name, rgb):
    """A purely Lambertian surface: glTF diffuse with KHR_materials_specular's factor 0."""
    m = diffuse(name, rgb)
    m["extensions"] = {"KHR_materials_specular": {"specularFactor": 0.0}}
    return m

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

def brushed(material, strength, rotation=0.0):
    """The material with KHR_materials_anisotropy (brushed along the mesh tangents)."""
    m = dict(material)
    m["extensions"] = dict(m.get("extensions", {}),
                           KHR_materials_anisotropy={"anisotropyStrength": strength, "anisotropyRotation": rotation})
    return m

def glass(name, ior, abbe, thickness, catalogue=None):
    """Clear dielectric; KHR_materials_dispersion uses dispersion = 20 / Abbe (omitted when abbe
    is None). `catalogue` names Prism's measured dispersion formula for the same glass."""
    m = diffuse(name, (1.0, 1.0, 1.0))
    m["pbrMetallicRoughness"]["roughnessFactor"] = 0.0
    m["extensions"] = {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                       "KHR_materials_ior": {"ior": ior},
                       "KHR_materials_volume": {"thicknessFactor": thickness}}
    if abbe is not None:
        m["extensions"]["KHR_materials_dispersion"] = {"dispersion": 20.0 / abbe}
    if catalogue:
        m["extras"] = {"prism": {"glass": catalogue}}
    return m

def with_attenuation(material, rgb, distance):
    """The material with KHR_materials_volume's absorption: colour rgb left after `distance`."""
    m = dict(material)
    m["extensions"] = dict(m["extensions"])
    m["extensions"]["KHR_materials_volume"] = dict(m["extensions"]["KHR_materials_volume"],
                                                   attenuationColor=list(rgb), attenuationDistance=distance)
    return m

def spot_light(name, position, target, intensity, outer_deg, inner_deg):
    """KHR_lights_punctual spot light (intensity in candela) at `position` aimed at `target`."""
    return {"name": name, "type": "spot", "intensity": intensity, "color": [1.0, 1.0, 1.0],
            "spot": {"innerConeAngle": math.radians(inner_deg), "outerConeAngle": math.radians(outer_deg)},
            "translation": list(position), "rotation": look_rotation(position, target)}

# ---------------------------------------------------------------- glTF writer
def f32(v):
    return struct.unpack("<f", struct.pack("<f", v))[0]

def png(width, height, rows):
    """An 8-bit RGB PNG file of `rows` (top first), each a list of (r, g, b) bytes."""
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rows)
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))

def build_gltf(objects, camera, generator, copyright, scene_name, root=None, lights=(), images=()):
    """One self-contained glTF: a mesh and node per object, the camera, the punctual lights, all
    under an optional root node (a dict with "translation" and/or "scale") that moves or scales
    the whole scene. `images` are PNG files, texture i for image i (a material names it as
    {"index": i}); a mesh's "uvs" become its TEXCOORD_0."""
    blob = bytearray()
    g = {"asset": {"version": "2.0", "generator": generator, "copyright": copyright},
         "scene": 0, "scenes": [{"name": scene_name, "nodes": []}], "nodes": [], "meshes": [],
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
        if "uvs" in mesh:
            prim["attributes"]["TEXCOORD_0"] = accessor(mesh["uvs"], "f", 5126, "VEC2", 34962)
        if "tangents" in mesh:  # xyz and the bitangent's sign, for anisotropy or normal maps
            prim["attributes"]["TANGENT"] = accessor(mesh["tangents"], "f", 5126, "VEC4", 34962)
        g["meshes"].append({"name": name, "primitives": [prim]})
        g["nodes"].append({"name": name, "mesh": len(g["meshes"]) - 1})

    g["cameras"].append({"name": camera["name"], "type": "perspective", "perspective": {
        k: camera[k] for k in ("aspectRatio", "yfov", "znear")}})
    if "extras" in camera:  # e.g. Prism's thin lens
        g["cameras"][-1]["extras"] = camera["extras"]
    g["nodes"].append({"name": camera["name"], "camera": 0,
                       "translation": camera["translation"], "rotation": camera["rotation"]})
    for i, light in enumerate(lights):
        g.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {"lights": []})["lights"].append(
            {k: v for k, v in light.items() if k not in ("translation", "rotation")})
        g["nodes"].append({"name": light["name"], "translation": light["translation"], "rotation": light["rotation"],
                           "extensions": {"KHR_lights_punctual": {"light": i}}})
    for i, image in enumerate(images):
        g.setdefault("samplers", [{"magFilter": 9729, "minFilter": 9729}])
        g.setdefault("images", []).append({"uri": "data:image/png;base64," + base64.b64encode(image).decode("ascii")})
        g.setdefault("textures", []).append({"source": i, "sampler": 0})
    if root is None:
        g["scenes"][0]["nodes"] = list(range(len(g["nodes"])))
    else:
        g["nodes"].append(dict(root, name="root", children=list(range(len(g["nodes"])))))
        g["scenes"][0]["nodes"] = [len(g["nodes"]) - 1]
    g["buffers"].append({"byteLength": len(blob), "uri": "data:application/octet-stream;base64,"
                         + base64.b64encode(bytes(blob)).decode("ascii")})
    used = sorted({e for m in g["materials"] for e in m.get("extensions", {})} | set(g.get("extensions", {})))
    if used:
        g["extensionsUsed"] = used
    return g

def look_rotation(eye, target):
    """The unit quaternion (x, y, z, w) that turns local -z towards target from eye, +y up (how
    glTF cameras and spot lights look)."""
    f = normalize(sub(target, eye))
    r = normalize(cross(f, (0.0, 1.0, 0.0)))
    u = cross(r, f)
    # Rotation matrix columns: right, up, back (= -f); to a unit quaternion (x, y, z, w).
    m = [[r[0], u[0], -f[0]], [r[1], u[1], -f[1]], [r[2], u[2], -f[2]]]
    w = math.sqrt(max(0.0, 1 + m[0][0] + m[1][1] + m[2][2])) / 2
    if w > 1e-6:
        q = ((m[2][1] - m[1][2]) / (4 * w), (m[0][2] - m[2][0]) / (4 * w), (m[1][0] - m[0][1]) / (4 * w), w)
    else:  # a half turn
        x = math.sqrt(max(0.0, 1 + m[0][0] - m[1][1] - m[2][2])) / 2
        y = math.sqrt(max(0.0, 1 - m[0][0] + m[1][1] - m[2][2])) / 2
        z = math.sqrt(max(0.0, 1 - m[0][0] - m[1][1] + m[2][2])) / 2
        q = (x, y, z, 0.0)
    return list(q)

def look_at_camera(name, eye, target, yfov_deg):
    """A camera node looking from eye at target with +y up (glTF cameras look down local -z)."""
    return {"name": name, "translation": list(eye), "rotation": look_rotation(eye, target),
            "yfov": math.radians(yfov_deg), "aspectRatio": 1.0, "znear": 0.01}

def write_gltf(path, gltf):
    with open(path, "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
    print("wrote", path)
