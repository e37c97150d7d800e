#!/usr/bin/env python3
"""Generate the layered-material showcases and the layered lobes' cost benchmark:

  iridescence.gltf  soap bubbles (KHR_materials_iridescence: a water film, n 1.33, over a
                    closed surface of index 1, so light crosses a single film at each wall),
                    their thickness 250 to 850 nm, and an oil film (n 1.45, 380 nm) on dark water;
  carpaint.gltf     a curved red car-paint panel under a clear coat (KHR_materials_clearcoat,
                    factor 1, roughness 0.04) beside the same paint without it;
  lobes_plain.gltf  the cost benchmark's reference: four spheres of plain metallic-roughness
                    materials (metal, plastic, half-metal, half-transmissive);
  lobes_all.gltf    the same spheres with every layer extension at once (clear coat, sheen,
                    specular colour, iridescence, anisotropy, diffuse transmission): the time per
                    sample of the two is the layered lobes' cost (`prism bench features`).

All four are lit by a long soft box overhead and a dimmer one behind the camera.
Run:  python3 data/scenes/make_layered.py
Standard library only (helpers in gltf_builder.py).
"""
import math
import os

from gltf_builder import (build_gltf, emitter, lambert, look_at_camera, quad, uv_sphere, with_longitude_tangents,
                          write_gltf)

HERE = os.path.dirname(os.path.abspath(__file__))

LIGHT = emitter("softbox", (1.0, 1.0, 1.0), 12.0, (0.0, 0.0, 0.0))
FILL = emitter("fill", (1.0, 1.0, 1.0), 3.0, (0.0, 0.0, 0.0))
BACKDROP = lambert("backdrop", (0.05, 0.05, 0.06))
FLOOR = lambert("floor", (0.35, 0.35, 0.35))


def bubble(name, thickness_nm):
    return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0.0,
                                                    "roughnessFactor": 0.0},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                           "KHR_materials_ior": {"ior": 1.0},
                           "KHR_materials_volume": {"thicknessFactor": 1.0},
                           "KHR_materials_iridescence": {"iridescenceFactor": 1.0, "iridescenceIor": 1.33,
                                                         "iridescenceThicknessMaximum": thickness_nm}}}


OIL_ON_WATER = {"name": "oil_on_water", "pbrMetallicRoughness": {
    "baseColorFactor": [0.02, 0.025, 0.03, 1], "metallicFactor": 0.0, "roughnessFactor": 0.05},
    "extensions": {"KHR_materials_ior": {"ior": 1.33},
                   "KHR_materials_iridescence": {"iridescenceFactor": 1.0, "iridescenceIor": 1.45,
                                                 "iridescenceThicknessMaximum": 380}}}


def car_paint(name, coat):
    m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [0.55, 0.02, 0.03, 1], "metallicFactor": 0.4,
                                                "roughnessFactor": 0.45}}
    if coat:
        m["extensions"] = {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.04}}
    return m


def cylinder_panel(centre, radius, height, angle_deg, segments=48):
    """Part of a vertical cylinder's outside (a bent panel), facing +z, smooth normals."""
    pos, nrm, idx = [], [], []
    half = math.radians(angle_deg) / 2
    for i in range(segments + 1):
        a = -half + 2 * half * i / segments
        n = (math.sin(a), 0.0, math.cos(a))
        for y in (-height / 2, height / 2):
            pos.append((centre[0] + radius * n[0], centre[1] + y, centre[2] + radius * n[2] - radius))
            nrm.append(n)
    for i in range(segments):
        a, b, c, d = 2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1
        idx += [a, b, c, a, c, d]
    return {"positions": pos, "normals": nrm, "indices": idx}


def lights():
    return [("softbox", quad((-1.5, 2.5, -0.6), (1.5, 2.5, -0.6), (1.5, 2.5, 0.2), (-1.5, 2.5, 0.2)), LIGHT),
            ("fill", quad((-1.5, 2.0, 4.0), (1.5, 2.0, 4.0), (1.5, 0.3, 4.0), (-1.5, 0.3, 4.0)), FILL)]


def room():
    return [("floor", quad((-4, 0, 4), (4, 0, 4), (4, 0, -3), (-4, 0, -3)), FLOOR),
            ("backdrop", quad((-4, 0, -3), (4, 0, -3), (4, 4, -3), (-4, 4, -3)), BACKDROP)]


def plain_material(name, color, metallic, roughness, transmission=0.0):
    m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(color) + [1], "metallicFactor": metallic,
                                                "roughnessFactor": roughness}}
    if transmission:
        m["extensions"] = {"KHR_materials_transmission": {"transmissionFactor": transmission}}
    return m


def all_lobes(material):
    """The material with every layer extension Prism has (each at a middling value)."""
    m = dict(material, name=material["name"] + "_layered")
    m["extensions"] = dict(m.get("extensions", {}),
                           KHR_materials_clearcoat={"clearcoatFactor": 0.8, "clearcoatRoughnessFactor": 0.2},
                           KHR_materials_sheen={"sheenColorFactor": [0.5, 0.5, 1.0], "sheenRoughnessFactor": 0.5},
                           KHR_materials_specular={"specularColorFactor": [1.5, 1.0, 0.5]},
                           KHR_materials_iridescence={"iridescenceFactor": 0.5, "iridescenceIor": 1.6,
                                                      "iridescenceThicknessMaximum": 250},
                           KHR_materials_anisotropy={"anisotropyStrength": 0.5},
                           KHR_materials_diffuse_transmission={"diffuseTransmissionFactor": 0.3})
    return m


def lobe_benchmark(layered):
    """Four spheres in a row filling a 3:1 frame: metal, plastic, half-metal, half-transmissive plastic."""
    materials = [plain_material("metal", (0.9, 0.6, 0.3), 1.0, 0.4), plain_material("plastic", (0.2, 0.4, 0.8), 0.0, 0.3),
                 plain_material("half_metal", (0.8, 0.8, 0.8), 0.5, 0.5),
                 plain_material("half_transmissive", (0.9, 0.9, 0.9), 0.0, 0.3, transmission=0.5)]
    objects = room() + lights()
    for i, m in enumerate(materials):
        sphere = with_longitude_tangents(uv_sphere((-0.96 + 0.64 * i, 0.3, 0.0), 0.3, 48))
        objects.append(("sphere_" + m["name"], sphere, all_lobes(m) if layered else m))
    camera = dict(look_at_camera("camera", (0.0, 0.35, 2.5), (0.0, 0.3, 0.0), 20.4), aspectRatio=3.0)
    name = "lobes_all" if layered else "lobes_plain"
    write_gltf(os.path.join(HERE, name + ".gltf"),
               build_gltf(objects, camera, "Prism make_layered.py", "Prism project", name))


def main():
    bubbles = [(-1.05, 250), (-0.35, 450), (0.35, 650), (1.05, 850)]
    objects = room() + lights()
    objects[0] = ("water", quad((-4, 0, 4), (4, 0, 4), (4, 0, -3), (-4, 0, -3)), OIL_ON_WATER)
    for x, d in bubbles:
        objects.append(("bubble_%d_nm" % d, uv_sphere((x, 0.75, 0.0), 0.3, 64), bubble("soap_%d_nm" % d, d)))
    write_gltf(os.path.join(HERE, "iridescence.gltf"),
               build_gltf(objects, look_at_camera("camera", (0.0, 1.3, 3.2), (0.0, 0.55, 0.0), 38.0),
                          "Prism make_layered.py", "Prism project", "iridescence"))

    objects = room() + lights()
    objects.append(("coated_panel", cylinder_panel((0.55, 0.8, 0.0), 1.2, 1.2, 60), car_paint("car_paint_coated", True)))
    objects.append(("bare_panel", cylinder_panel((-0.75, 0.8, 0.0), 1.2, 1.2, 60), car_paint("car_paint_bare", False)))
    write_gltf(os.path.join(HERE, "carpaint.gltf"),
               build_gltf(objects, look_at_camera("camera", (0.0, 1.2, 3.4), (0.0, 0.8, 0.0), 36.0),
                          "Prism make_layered.py", "Prism project", "carpaint"))
    lobe_benchmark(False)
    lobe_benchmark(True)


if __name__ == "__main__":
    main()
