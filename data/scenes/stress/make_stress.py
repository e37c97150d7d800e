#!/usr/bin/env python3
"""Generate Prism's stress scenes, data/scenes/stress/*.gltf: the same content at extreme
scales and positions, degenerate geometry, a tiny very bright light, extreme indices of
refraction and extreme absorption. tests/render/test_stress.cpp renders each and compares it
with its analytic value or with the well-conditioned original.

Run from anywhere:  python3 data/scenes/stress/make_stress.py
Standard library only (helpers in ../gltf_builder.py).
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltf_builder import (build_gltf, cuboid, emitter, glass, lambert, look_at_camera, merge, polygon, quad,
                          uv_sphere, write_gltf)

HERE = os.path.dirname(os.path.abspath(__file__))
GENERATOR = "Prism make_stress.py"
COPYRIGHT = "Prism project"

WHITE = lambert("white", (0.8, 0.8, 0.8))
ORANGE = lambert("orange", (0.8, 0.4, 0.1))
LIGHT = emitter("light", (1.0, 1.0, 1.0), 10.0, (0.0, 0.0, 0.0))


def floor(w):
    return quad((-w, 0, w), (w, 0, w), (w, 0, -w), (-w, 0, -w))


def sliver_floor(w, n):
    """The same floor as n slivers fanned from one corner (angles ~1/n), plus zero-area
    triangles: a repeated vertex and three collinear points."""
    corner, far = (-w, 0.0, w), []
    for i in range(n + 1):  # along the two far edges: (w, w) → (w, −w) → (−w, −w) in (x, z)
        t = i / n
        far.append((w, 0.0, w - 4 * w * t) if t <= 0.5 else (w - 4 * w * (t - 0.5), 0.0, -w))
    mesh = merge(*(polygon(corner, far[i], far[i + 1]) for i in range(n)))
    # Degenerate triangles share the floor's normal; they must never be hit.
    base = len(mesh["positions"])
    mesh["positions"] += [(0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.5, 0.0, 0.5), (0.1, 0.0, 0.1), (0.2, 0.0, 0.2), (0.3, 0.0, 0.3)]
    mesh["normals"] += [(0.0, 1.0, 0.0)] * 6
    mesh["indices"] += [base, base + 1, base + 2, base + 3, base + 4, base + 5]
    return mesh


def room(floor_mesh):
    """A floor, a back wall, a sphere, a box and a ceiling light: about 4 m across."""
    return [("floor", floor_mesh, WHITE),
            ("back_wall", quad((-2, 0, -2), (2, 0, -2), (2, 3, -2), (-2, 3, -2)), WHITE),
            ("sphere", uv_sphere((-0.6, 0.5, -0.4), 0.5, 48), ORANGE),
            ("box", cuboid((0.8, 0.4, -0.2), (0.8, 0.8, 0.8), 25.0), WHITE),
            ("light", quad((-0.5, 2.5, -0.5), (0.5, 2.5, -0.5), (0.5, 2.5, 0.5), (-0.5, 2.5, 0.5)), LIGHT)]  # faces down


ROOM_CAMERA = look_at_camera("camera", (0.0, 1.5, 4.0), (0.0, 0.8, 0.0), 45.0)


def write(name, objects, camera, root=None):
    write_gltf(os.path.join(HERE, name), build_gltf(objects, camera, GENERATOR, COPYRIGHT, name[:-5], root))


def main():
    # One room at unit scale, scaled by 1e-4 and 1e4, and moved 1e5 from the origin: the images
    # must match (radiance is scale-invariant; offsets must follow the coordinates' magnitude).
    write("room.gltf", room(floor(2)), ROOM_CAMERA)
    write("room_tiny.gltf", room(floor(2)), ROOM_CAMERA, {"scale": [1e-4] * 3})
    write("room_huge.gltf", room(floor(2)), ROOM_CAMERA, {"scale": [1e4] * 3})
    write("room_far.gltf", room(floor(2)), ROOM_CAMERA, {"translation": [1e5, -1e5, 1e5]})
    # The floor as 2000 slivers and a few zero-area triangles.
    write("room_slivers.gltf", room(sliver_floor(2, 2000)), ROOM_CAMERA)
    # A 1 mm square light of luminance 1e6 cd/m² (1 cd) 1 m above a white floor: directly
    # below, E = L A / h² = 1 lux, so the floor's radiance is ρ E / π = 0.8 / π.
    tiny_light = emitter("tiny_light", (1.0, 1.0, 1.0), 1e6, (0.0, 0.0, 0.0))
    write("tiny_bright_light.gltf",
          [("floor", floor(3), WHITE),
           ("light", quad((-5e-4, 1, -5e-4), (5e-4, 1, -5e-4), (5e-4, 1, 5e-4), (-5e-4, 1, 5e-4)), tiny_light)],
          look_at_camera("camera", (0.0, 0.6, 0.6), (0.0, 0.0, 0.0), 10.0))
    # Clear glass spheres of index 1 (index-matched), 1.0001, 4 and 10, to be lit by a uniform
    # --env: each must look exactly like the environment (a furnace).
    spheres = [("sphere_%g" % n, uv_sphere((2.2 * i - 3.3, 0, 0), 1.0, 64), glass("glass_%g" % n, n, None, 1.0))
               for i, n in enumerate([1.0, 1.0001, 4.0, 10.0])]
    write("extreme_ior.gltf", spheres, look_at_camera("camera", (0.0, 0.0, 12.0), (0.0, 0.0, 0.0), 40.0))
    # Index-matched slabs 1 unit thick absorbing sigma_a d = 1e4 and 1e-8 (KHR_materials_volume:
    # sigma_a = -ln(attenuationColor) / attenuationDistance): in front of a uniform --env they
    # transmit exp(-1e4) = 0 and exp(-1e-8).
    slabs = []
    for i, sigma in enumerate([1e4, 1e-8]):
        m = glass("absorb_%g" % sigma, 1.0, None, 1.0)
        m["extensions"]["KHR_materials_volume"].update({"attenuationColor": [math.exp(-1.0)] * 3,
                                                          "attenuationDistance": 1.0 / sigma})
        slabs.append(("slab_%g" % sigma, cuboid((1.5 * i - 0.75, 0, 0), (1.0, 1.0, 1.0)), m))
    write("extreme_absorption.gltf", slabs, look_at_camera("camera", (0.0, 0.0, 5.0), (0.0, 0.0, 0.0), 30.0))


if __name__ == "__main__":
    main()
