#!/usr/bin/env python3
"""Generate data/scenes/diamond.gltf: a brilliant-cut-like diamond's fire under a small light.

A round gem of eight-fold symmetry (octagonal table, 16-sided girdle, crown of bezel and star
facets, pavilion of 16 facets to a point; proportions near the Tolkowsky brilliant's: table 57%
of the diameter, crown angle 34.5°, pavilion angle 40.75°) of diamond (IOR 2.42, Abbe number 55:
KHR_materials_dispersion 20/55), table up, on a dark floor under one small bright light. 78
triangles. A report scene of `prism converge` (docs/performance.md, "The integrators at equal
time").

Run:  python3 data/scenes/make_diamond.py
Standard library only (helpers in gltf_builder.py).
"""
import math
import os

from gltf_builder import (add, build_gltf, convex_solid, emitter, glass, lambert, look_at_camera, quad, write_gltf)

HERE = os.path.dirname(os.path.abspath(__file__))

RADIUS = 0.02                                            # girdle radius (m): a 4 cm gem
TABLE_R = 0.57 * RADIUS
CROWN_H = (RADIUS - TABLE_R) * math.tan(math.radians(34.5))
PAVILION_D = RADIUS * math.tan(math.radians(40.75))
GIRDLE_H = 0.03 * RADIUS
BASE = (0.0, PAVILION_D + GIRDLE_H + 0.0002, 0.0)         # the upper girdle's centre; the culet just clears the floor

FLOOR = lambert("floor", (0.04, 0.04, 0.045))
DIAMOND = glass("diamond", 2.42, 55.0, RADIUS)
LIGHT = emitter("light", (1.0, 1.0, 1.0), 800.0, (0.0, 0.0, 0.0))

def ring(radius, height, count, turn=0.0):
    return [add(BASE, (radius * math.cos(2 * math.pi * (k + turn) / count), height,
                       radius * math.sin(2 * math.pi * (k + turn) / count))) for k in range(count)]

def brilliant():
    table = ring(TABLE_R, CROWN_H, 8)
    upper = ring(RADIUS, 0.0, 16)
    lower = ring(RADIUS, -GIRDLE_H, 16)
    culet = add(BASE, (0.0, -GIRDLE_H - PAVILION_D, 0.0))
    faces = [table]
    for k in range(8):
        t0, t1 = table[k], table[(k + 1) % 8]
        g0, g1, g2 = upper[2 * k], upper[2 * k + 1], upper[(2 * k + 2) % 16]
        faces += [[t0, g0, g1], [t0, g1, t1], [t1, g1, g2]]  # bezel halves and the star between
    for j in range(16):
        faces.append([upper[j], upper[(j + 1) % 16], lower[(j + 1) % 16], lower[j]])  # girdle
        faces.append([lower[j], lower[(j + 1) % 16], culet])                          # pavilion
    return convex_solid(faces)

OBJECTS = [
    ("floor", quad((-0.5, 0, 0.5), (0.5, 0, 0.5), (0.5, 0, -0.5), (-0.5, 0, -0.5)), FLOOR),
    ("diamond", brilliant(), DIAMOND),
    # A 3 cm square light 30 cm up, over the camera's side and a little to the left, facing down.
    ("light", quad((-0.06, 0.3, 0.03), (-0.03, 0.3, 0.03), (-0.03, 0.3, 0.06), (-0.06, 0.3, 0.06)), LIGHT),
]

def main():
    camera = look_at_camera("camera", (0.0, 0.11, 0.1), (0.0, 0.025, 0.0), 30.0)
    write_gltf(os.path.join(HERE, "diamond.gltf"),
               build_gltf(OBJECTS, camera, "Prism make_diamond.py", "Prism project", "diamond"))

if __name__ == "__main__":
    main()
