#!/usr/bin/env python3
"""Generate data/scenes/milk_and_water.gltf: a glass of milk beside a glass of water.

Two glass tumblers (IOR 1.5, walls 2 mm thick) on a white table under one small light and a dim sky: one holds
water (IOR 1.33, a faint blue-green absorption), the other whole milk (IOR 1.35), a scattering
medium given in the material's extras: Jensen et al. 2001 ("A Practical Model for Subsurface Light
Transport", SIGGRAPH, table 2) measured whole milk's reduced scattering σ_s' = 2.55, 3.21, 3.77 and
absorption σ_a = 0.0011, 0.0024, 0.014 per mm in red, green and blue; they are given here as
spectra at 650, 550 and 450 nm, per metre, with g = 0 (σ_s' is the scattering of the equivalent
isotropic medium). Light enters the milk, scatters thousands of times and leaves it white and
soft, where the water stays clear. The liquids stop 0.2 mm short of their glasses and the glasses
0.1 mm over the table, so that no two surfaces coincide.

Run:  python3 data/scenes/make_milk_and_water.py
Standard library only (helpers in gltf_builder.py).
"""
import os

from gltf_builder import (build_gltf, emitter, facing_square, glass, lambert, lathe, look_at_camera, quad,
                          tumbler_profiles, with_attenuation, write_gltf)

HERE = os.path.dirname(os.path.abspath(__file__))

R, H = 0.035, 0.10       # tumbler: outer radius and height (m)
WALL, BOTTOM = 0.002, 0.008
LIQUID_TOP, GAP = 0.075, 0.0002
SEGMENTS = 48

TABLE = lambert("table", (0.75, 0.75, 0.75))
GLASS = glass("glass", 1.5, None, 0.002)
WATER = with_attenuation(glass("water", 1.33, None, 0.05), (0.9, 0.97, 0.98), 0.1)
MILK = glass("milk", 1.35, None, 0.05)
MILK["extras"] = {"prism": {"medium": {
    "sigma_s": {"wavelengths": [450, 550, 650], "values": [3770, 3210, 2550]},
    "sigma_a": {"wavelengths": [450, 550, 650], "values": [14, 2.4, 1.1]},
    "g": 0.0}}}
LIGHT = emitter("light", (1.0, 1.0, 1.0), 150.0, (0.0, 0.0, 0.0))

TUMBLER, LIQUID = tumbler_profiles(R, H, WALL, BOTTOM, LIQUID_TOP, GAP)

def main():
    left, right = (-0.045, 0.0001, 0.0), (0.045, 0.0001, 0.0)
    objects = [
        ("table", quad((-0.5, 0, 0.5), (0.5, 0, 0.5), (0.5, 0, -0.5), (-0.5, 0, -0.5)), TABLE),
        ("water glass", lathe(left, TUMBLER, SEGMENTS), GLASS),
        ("water", lathe(left, LIQUID, SEGMENTS), WATER),
        ("milk glass", lathe(right, TUMBLER, SEGMENTS), GLASS),
        ("milk", lathe(right, LIQUID, SEGMENTS), MILK),
        # A 6 cm square light 40 cm away, above and to the side, facing the glasses.
        ("light", facing_square((-0.25, 0.3, 0.1), (0.0, 0.05, 0.0), 0.06), LIGHT),
    ]
    camera = look_at_camera("camera", (0.05, 0.14, 0.32), (0.0, 0.045, 0.0), 35.0)
    write_gltf(os.path.join(HERE, "milk_and_water.gltf"),
               build_gltf(objects, camera, "Prism make_milk_and_water.py", "Prism project", "milk_and_water"))

if __name__ == "__main__":
    main()
