#!/usr/bin/env python3
"""Generate data/scenes/depth_of_field.gltf: seven measured-metal spheres in a row on a long table,
the middle one in focus through a wide six-bladed aperture, small lamps far behind.

A showcase of the thin lens (README, "Depth of field"): the camera's extras ask for f/1.4 on a 36 mm
film (a 20-degree view: about a 70 mm lens), focused on the gold sphere in the middle (its depth along the view axis), with six blades. The spheres
before and behind it blur by their distance from that plane, and the small lamps on the far wall
become hexagons: the aperture's shape.

Run from the repository root:
    python3 data/scenes/make_depth_of_field.py
Standard library only (helpers in gltf_builder.py).
"""
import os

from gltf_builder import (build_gltf, diffuse, dot, emitter, look_at_camera, merge, metal, normalize, quad, room, sub,
                          uv_sphere, write_gltf)

METALS = ["Ag", "Cu", "Brass", "Au", "Al", "Ti", "Cr"]
TINTS = {"Ag": (0.97, 0.96, 0.91), "Cu": (0.95, 0.64, 0.54), "Brass": (0.91, 0.78, 0.42), "Au": (1.0, 0.78, 0.34),
         "Al": (0.91, 0.92, 0.92), "Ti": (0.54, 0.5, 0.45), "Cr": (0.55, 0.55, 0.55)}
RADIUS = 0.08
EYE, TARGET = (0.05, 0.3, 0.0), (-0.12, 0.05, 6.0)

def centre(i):
    """The i-th sphere's centre: every 0.35 m along a slanting row from 1 m to 3.1 m away."""
    return (0.2 - 0.09 * i, RADIUS, 1.0 + 0.35 * i)

def lamp(x, y, z, side):
    """A small square lamp on the far wall, facing the camera (-z)."""
    h = side / 2
    return quad((x - h, y - h, z), (x - h, y + h, z), (x + h, y + h, z), (x + h, y - h, z))

def objects():
    floor, walls = diffuse("floor", (0.3, 0.28, 0.26)), diffuse("walls", (0.5, 0.5, 0.5))
    out = [o for o in room(3.0, 3.0, 8.0, floor, walls) if o[0] != "near_wall"]
    for i, name in enumerate(METALS):
        out.append(("sphere_" + name, uv_sphere(centre(i), RADIUS, 48),
                    metal(name, TINTS[name], 0.08, catalogue=name)))
    # Lamps on the far wall, 8 m away, and a broad soft light overhead.
    lamps = [lamp(-1.2 + 0.2 * i, 0.25 + 0.18 * (i % 4), 7.99, 0.06) for i in range(13)]
    out.append(("lamps", merge(*lamps), emitter("lamp", (1.0, 0.8, 0.55), 60.0, (0.8, 0.8, 0.8))))
    out.append(("ceiling_light", quad((-1.0, 2.99, 0.5), (1.0, 2.99, 0.5), (1.0, 2.99, 4.0), (-1.0, 2.99, 4.0)),
                emitter("ceiling_light", (1.0, 1.0, 1.0), 4.0, (0.8, 0.8, 0.8))))
    return out

def main():
    camera = look_at_camera("camera", EYE, TARGET, 20.0)
    camera["aspectRatio"] = 3 / 2
    focus = dot(sub(centre(METALS.index("Au")), EYE), normalize(sub(TARGET, EYE)))
    camera["extras"] = {"prism": {"aperture": 1.4, "sensor_width": 36, "focus_distance": round(focus, 4),
                                  "blades": 6, "blade_rotation": 15}}
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "depth_of_field.gltf")
    write_gltf(out, build_gltf(objects(), camera, "Prism make_depth_of_field.py", "Prism project", "depth_of_field"))

if __name__ == "__main__":
    main()
