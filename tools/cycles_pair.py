"""What the small Prism-against-Cycles tools share (lamp_pane.py, layering_cycles.py,
specular_cycles.py): their common options, finding the Cycles harness (tools/cycles of the shared
assets, PRISM_SHARED_DIR), their scene (a square under an orthographic camera), rendering it with both renderers, the
Fresnel reflectance and an image's mean luminance."""

import base64
import json
import os
import shutil
import struct
import subprocess
import sys

from shared_dir import shared_dir

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def add_common_args(ap, tool):
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", default=os.path.join(REPO, "out", tool))
    ap.add_argument("--shared", default=str(shared_dir()),
                    help="the shared assets' folder (default: PRISM_SHARED_DIR, else shared/ beside the project's root)")
    ap.add_argument("--prism", default=os.path.join(REPO, "build", "apps", "prism"))


def harness(tool, shared):
    """The harness folder, with its exrstats module importable; None (saying why) if the tool skips."""
    path = os.path.join(shared, "tools", "cycles")
    if not os.path.isfile(os.path.join(path, "render_gltf.sh")):
        print("%s: SKIPPED: %s (the Cycles harness) not found" % (tool, path))
        return None
    if shutil.which("blender") is None:
        print("%s: SKIPPED: Blender not found" % tool)
        return None
    sys.path.insert(0, path)
    sys.dont_write_bytecode = True
    return path


def plane_scene(generator, material, half=1, view=1, rotation=None, light=None):
    """A glTF scene: a 2·half square at z = 0 facing +z (turned by the quaternion `rotation`) of
    `material`, under an orthographic camera at z = 1 looking along −z that sees ±view; `light`:
    (z, a KHR_lights_punctual light) placed on the axis."""
    p = [(-half, -half, 0), (half, -half, 0), (half, half, 0), (-half, half, 0)]
    blob = struct.pack("<12f", *[c for v in p for c in v]) + struct.pack("<12f", *[0, 0, 1] * 4) + \
        struct.pack("<6I", 0, 1, 2, 0, 2, 3)
    mesh_node = {"mesh": 0, "rotation": rotation} if rotation else {"mesh": 0}
    nodes = [mesh_node, {"camera": 0, "translation": [0, 0, 1]}]
    used = list(material.get("extensions", {}))
    scene = {
        "asset": {"version": "2.0", "generator": generator}, "scene": 0,
        "cameras": [{"type": "orthographic", "orthographic": {"xmag": view, "ymag": view, "znear": 0.01, "zfar": 10}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
        "materials": [material],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [-half, -half, 0], "max": [half, half, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5125, "count": 6, "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 24}],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}]}
    if light:
        z, definition = light
        nodes.append({"translation": [0, 0, z], "extensions": {"KHR_lights_punctual": {"light": 0}}})
        used.insert(0, "KHR_lights_punctual")
        scene["extensions"] = {"KHR_lights_punctual": {"lights": [definition]}}
    scene["nodes"], scene["scenes"], scene["extensionsUsed"] = nodes, [{"nodes": list(range(len(nodes)))}], used
    return scene


def fresnel(c, eta):
    """Unpolarised Fresnel reflectance of a dielectric of relative index eta > 1 at cos θ = c ≥ 0."""
    s2 = (1 - c * c) / eta ** 2
    ct = (1 - s2) ** 0.5
    rs, rp = (c - eta * ct) / (c + eta * ct), (eta * c - ct) / (eta * c + ct)
    return (rs * rs + rp * rp) / 2


def mean_y(exrstats, path):
    """The Rec.709 luminance of an EXR image's mean colour."""
    img = exrstats.read_exr(path)
    names = exrstats.rgb_names(list(img["channels"]))
    luma = (0.2126, 0.7152, 0.0722)
    chans = [img["channels"][n] for n in names]
    return sum(w * sum(c) / len(c) for w, c in zip(luma, chans))


def render_pair(tool, a, work, scene, prism_args, cycles_args):
    """Writes the glTF scene to work/scene.gltf and renders it to prism.exr and cycles.exr beside
    it (a: the common options); their paths."""
    os.makedirs(work, exist_ok=True)
    gltf = os.path.join(work, "scene.gltf")
    with open(gltf, "w") as f:
        json.dump(scene, f, indent=1)
    prism_exr, cycles_exr = os.path.join(work, "prism.exr"), os.path.join(work, "cycles.exr")
    subprocess.run([a.prism, "render", gltf, "-o", prism_exr, "-q", "--threads", str(a.threads)] + prism_args,
                   check=True, stdout=subprocess.DEVNULL)
    r = subprocess.run([os.path.join(a.harness, "render_gltf.sh"), "--in", gltf, "--out", cycles_exr,
                        "--threads", str(a.threads)] + cycles_args,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.exit("%s: Cycles failed; log: %s.log" % (tool, cycles_exr))
    return prism_exr, cycles_exr
