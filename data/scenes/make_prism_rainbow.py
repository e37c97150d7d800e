#!/usr/bin/env python3
"""Generate data/scenes/prism_rainbow.gltf: Newton's experiment, a white beam split by a prism.

A narrow spot light shines through a vertical slit in a black plate onto an upright equilateral
prism of flint glass (SCHOTT N-SF11 in Prism, its index and Abbe number for other viewers), set
at minimum deviation for yellow light; the spectrum lands on a white screen. A dim ceiling panel
lights the room so that the table, the screen and the prism are visible. The beam is a delta
light through glass: only light paths (bdpt, vcm, light tracing) carry the rainbow; the path
tracer sees the room only. A report scene of `prism converge` (docs/performance.md, "The
integrators at equal time").

Run:  python3 data/scenes/make_prism_rainbow.py
Standard library only (helpers in gltf_builder.py).
"""
import math
import os

from gltf_builder import (add, build_gltf, convex_solid, cross, emitter, glass, lambert, look_at_camera, merge, normalize,
                          quad, scale, spot_light, write_gltf)

HERE = os.path.dirname(os.path.abspath(__file__))

N_D = 1.78472     # N-SF11 at the helium d line
SIDE = 0.12       # prism edge (m)
HEIGHT = 0.12
BEAM_Y = 0.06     # height of the beam over the table
LAMP_DISTANCE = 0.5
SLIT = (0.003, 0.04)  # width, height (m), 0.45 m from the lamp
SCREEN_DISTANCE = 0.8
LIFT = 0.001      # the prism stands 1 mm over the table: no two surfaces coincide

TABLE = lambert("table", (0.35, 0.35, 0.35))
SCREEN = lambert("screen", (0.85, 0.85, 0.85))
BLACK = lambert("black", (0.02, 0.02, 0.02))
FLINT = glass("flint_glass", N_D, 25.68, 1.0, "N-SF11")
CEILING = emitter("ceiling_panel", (1.0, 1.0, 1.0), 20.0, (0.0, 0.0, 0.0))

def direction(deg):
    """Unit vector in the table's plane at deg from +x towards +z."""
    return (math.cos(math.radians(deg)), 0.0, math.sin(math.radians(deg)))

def flat_rect(centre, u, v, u_range, v_range):
    """Rectangle centre + [u_range]·u + [v_range]·v (u, v unit and perpendicular)."""
    at = lambda a, b: add(centre, add(scale(u, a), scale(v, b)))
    (u0, u1), (v0, v1) = u_range, v_range
    return quad(at(u0, v0), at(u1, v0), at(u1, v1), at(u0, v1))

# The prism's triangle: base edge parallel to x, apex towards +z, centroid at the origin. At
# minimum deviation the ray inside runs parallel to the base, entering the left face at
# i = asin(n sin 30°) and leaving the right face symmetrically.
r = SIDE / math.sqrt(3.0)
TRIANGLE = [(-SIDE / 2, -r / 2), (SIDE / 2, -r / 2), (0.0, r)]
I_DEG = math.degrees(math.asin(N_D * 0.5))
IN, OUT = direction(I_DEG - 30.0), direction(30.0 - I_DEG)
ENTRY = ((TRIANGLE[0][0] + TRIANGLE[2][0]) / 2, BEAM_Y, (TRIANGLE[0][1] + TRIANGLE[2][1]) / 2)
EXIT = ((TRIANGLE[1][0] + TRIANGLE[2][0]) / 2, BEAM_Y, (TRIANGLE[1][1] + TRIANGLE[2][1]) / 2)
LAMP = add(ENTRY, scale(IN, -LAMP_DISTANCE))
UP = (0.0, 1.0, 0.0)

def prism_solid():
    bottom = [(x, LIFT, z) for x, z in TRIANGLE]
    top = [(x, LIFT + HEIGHT, z) for x, z in TRIANGLE]
    sides = [[bottom[i], bottom[(i + 1) % 3], top[(i + 1) % 3], top[i]] for i in range(3)]
    return convex_solid([bottom, top] + sides)

def slit_plate():
    """A black plate across the beam, 0.45 m from the lamp, with a vertical slit in it."""
    centre = add(LAMP, scale(IN, 0.45))
    u = normalize(cross(IN, UP))
    w, h = SLIT[0] / 2, SLIT[1] / 2
    below, above = -BEAM_Y, 0.1
    return merge(flat_rect(centre, u, UP, (-0.1, -w), (below, above)), flat_rect(centre, u, UP, (w, 0.1), (below, above)),
                 flat_rect(centre, u, UP, (-w, w), (h, above)), flat_rect(centre, u, UP, (-w, w), (below, -h)))

def screen():
    centre = add(EXIT, scale(OUT, SCREEN_DISTANCE))
    u = normalize(cross(UP, OUT))
    return flat_rect((centre[0], 0.0, centre[2]), u, UP, (-0.25, 0.25), (0.0, 0.3))

OBJECTS = [
    ("table", quad((-1.2, 0, 1.0), (1.2, 0, 1.0), (1.2, 0, -1.0), (-1.2, 0, -1.0)), TABLE),
    ("prism", prism_solid(), FLINT),
    ("slit_plate", slit_plate(), BLACK),
    ("screen", screen(), SCREEN),
    # A 40 cm square panel 1.5 m up, facing down.
    ("ceiling_panel", quad((0.0, 1.5, -0.2), (0.4, 1.5, -0.2), (0.4, 1.5, 0.2), (0.0, 1.5, 0.2)), CEILING),
]

# Spot light: 2.5° half angle (full intensity to 2°), 2 cm wide at the slit; 150 cd.
LIGHTS = [spot_light("lamp", LAMP, ENTRY, 150.0, 2.5, 2.0)]

def main():
    target = add(EXIT, scale(OUT, 0.35))
    camera = look_at_camera("camera", (-0.3, 0.5, 0.7), (target[0], 0.02, target[2]), 42.0)
    write_gltf(os.path.join(HERE, "prism_rainbow.gltf"),
               build_gltf(OBJECTS, camera, "Prism make_prism_rainbow.py", "Prism project", "prism_rainbow",
                          lights=LIGHTS))

if __name__ == "__main__":
    main()
