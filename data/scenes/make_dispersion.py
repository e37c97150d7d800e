#!/usr/bin/env python3
"""Generate data/scenes/dispersion.gltf: white light through a dispersive glass prism.

A small bright light shines down on a flint-glass prism (SCHOTT N-SF11 in Prism, the same
glass's index and Abbe number for other viewers) standing on a white floor; the prism throws a
spectrum on the floor. A report scene of `prism converge` (docs/performance.md, "The integrators
at equal time").

Run:  python3 data/scenes/make_dispersion.py
Standard library only (helpers in gltf_builder.py).
"""
import os

from gltf_builder import build_gltf, emitter, glass, lambert, look_at_camera, prism, quad, write_gltf

HERE = os.path.dirname(os.path.abspath(__file__))

FLOOR = lambert("floor", (0.8, 0.8, 0.8))
WALL = lambert("wall", (0.5, 0.5, 0.5))
FLINT = glass("flint_glass", 1.78472, 25.68, 1.0, "N-SF11")
LIGHT = emitter("light", (1.0, 1.0, 1.0), 60.0, (0.0, 0.0, 0.0))

OBJECTS = [
    ("floor", quad((-2, 0, 2), (2, 0, 2), (2, 0, -2), (-2, 0, -2)), FLOOR),
    ("back_wall", quad((-2, 0, -2), (2, 0, -2), (2, 2, -2), (-2, 2, -2)), WALL),
    # 1 mm over the floor: a base coincident with the floor makes which of the two a ray meets
    # depend on the ray, and the integrators' strategies then disagree (VCM's mean falls below BDPT's).
    ("prism", prism((0.0, 0.001, 0.0), 0.5, 0.8, 90.0), FLINT),
    # A 25 cm square light, up and to the side, facing down.
    ("light", quad((-1.0, 1.2, -0.125), (-0.75, 1.2, -0.125), (-0.75, 1.2, 0.125), (-1.0, 1.2, 0.125)), LIGHT),
]

def main():
    write_gltf(os.path.join(HERE, "dispersion.gltf"),
               build_gltf(OBJECTS, look_at_camera("camera", (0.0, 1.6, 2.6), (0.3, 0.1, 0.0), 40.0),
                          "Prism make_dispersion.py", "Prism project", "dispersion"))

if __name__ == "__main__":
    main()
