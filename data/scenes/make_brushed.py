#!/usr/bin/env python3
"""Generate data/scenes/brushed.gltf: brushed aluminium (KHR_materials_anisotropy).

A lathe-turned aluminium disk (brushed around its centre) and a sphere brushed along its
latitudes, both the catalogue's measured aluminium (n, k of Al in Prism; its colour elsewhere),
roughness 0.35, anisotropy 0.8, on a dark floor under a small light: the highlights stretch
across the brushing, the disk's into a radial streak.

Run:  python3 data/scenes/make_brushed.py
Standard library only (helpers in gltf_builder.py).
"""
import os

from gltf_builder import (brushed, build_gltf, emitter, lambert, look_at_camera, metal, quad, turned_disk,
                          uv_sphere, with_longitude_tangents, write_gltf)

HERE = os.path.dirname(os.path.abspath(__file__))

FLOOR = lambert("floor", (0.05, 0.05, 0.05))
ALUMINIUM = brushed(metal("brushed_aluminium", (0.91, 0.92, 0.92), 0.35, "Al"), 0.8)
LIGHT = emitter("light", (1.0, 1.0, 1.0), 40.0, (0.0, 0.0, 0.0))

OBJECTS = [
    ("floor", quad((-3, 0, 3), (3, 0, 3), (3, 0, -3), (-3, 0, -3)), FLOOR),
    ("disk", turned_disk((-0.55, 0.01, 0.0), 0.5, 128), ALUMINIUM),
    ("sphere", with_longitude_tangents(uv_sphere((0.6, 0.4, 0.0), 0.4, 96)), ALUMINIUM),
    # A 20 cm square light above and behind, facing down.
    ("light", quad((-0.1, 1.6, -1.1), (0.1, 1.6, -1.1), (0.1, 1.6, -0.9), (-0.1, 1.6, -0.9)), LIGHT),
]

def main():
    write_gltf(os.path.join(HERE, "brushed.gltf"),
               build_gltf(OBJECTS, look_at_camera("camera", (0.0, 1.5, 2.2), (0.0, 0.2, 0.0), 40.0),
                          "Prism make_brushed.py", "Prism project", "brushed"))

if __name__ == "__main__":
    main()
