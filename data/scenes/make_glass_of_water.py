#!/usr/bin/env python3
"""Generate data/scenes/glass_of_water.gltf: a glass of water and its caustic on a table.

A tumbler with thin walls (IOR 1.5) two-thirds full of water (IOR 1.33, KHR_materials_volume with
a faint blue-green attenuation) stands on a white table under one small, bright light, up and
behind it; the glass focuses the light into a caustic on the table in front of it. The water
stops 0.2 mm short of the glass and the glass 0.1 mm over the table (air films), so that no two
surfaces coincide. A report scene of `prism converge` (docs/performance.md, "The integrators at
equal time").

Run:  python3 data/scenes/make_glass_of_water.py
Standard library only (helpers in gltf_builder.py).
"""
import os

from gltf_builder import (build_gltf, emitter, facing_square, glass, lambert, lathe, look_at_camera, quad,
                          tumbler_profiles, with_attenuation, write_gltf)

HERE = os.path.dirname(os.path.abspath(__file__))

R, H = 0.035, 0.10       # tumbler: outer radius and height (m)
WALL, BOTTOM = 0.002, 0.008
WATER_TOP, GAP = 0.07, 0.0002
SEGMENTS = 48
BASE = (0.0, 0.0001, 0.0)

TABLE = lambert("table", (0.75, 0.75, 0.75))
GLASS = glass("glass", 1.5, None, 0.002)
WATER = with_attenuation(glass("water", 1.33, None, 0.05), (0.9, 0.97, 0.98), 0.1)
LIGHT = emitter("light", (1.0, 1.0, 1.0), 400.0, (0.0, 0.0, 0.0))

TUMBLER, WATER_BODY = tumbler_profiles(R, H, WALL, BOTTOM, WATER_TOP, GAP)

OBJECTS = [
    ("table", quad((-0.5, 0, 0.5), (0.5, 0, 0.5), (0.5, 0, -0.5), (-0.5, 0, -0.5)), TABLE),
    ("tumbler", lathe(BASE, TUMBLER, SEGMENTS), GLASS),
    ("water", lathe(BASE, WATER_BODY, SEGMENTS), WATER),
    # A 3 cm square light 30 cm from the glass, behind it and above, facing it.
    ("light", facing_square((-0.12, 0.22, -0.15), (0.0, 0.05, 0.0), 0.03), LIGHT),
]

def main():
    camera = look_at_camera("camera", (0.16, 0.2, 0.3), (0.02, 0.03, 0.03), 35.0)
    write_gltf(os.path.join(HERE, "glass_of_water.gltf"),
               build_gltf(OBJECTS, camera, "Prism make_glass_of_water.py", "Prism project", "glass_of_water"))

if __name__ == "__main__":
    main()
