#!/usr/bin/env python3
"""Generate data/scenes/lamp_hall.gltf: a hall lit by 1,152 small ceiling lamps of six colours.

A many-light scene for light sampling: a 24 m x 48 m hall, 4 m high, with a grid of 24 x 48 square
lamps (0.25 m, 2,304 emissive triangles) just below the ceiling and two rows of pillars that cast
shadows. Any point sees hundreds of lamps, but only the few above it light it much: choosing lamps
by power alone wastes nearly every shadow ray (see --light-sampler in the README).

Run from the repository root:
    python3 data/scenes/make_lamp_hall.py
Standard library only (helpers in gltf_builder.py).
"""
import os

from gltf_builder import build_gltf, cuboid, diffuse, emitter, look_at_camera, merge, quad, room, write_gltf

WIDTH, LENGTH, HEIGHT = 24.0, 48.0, 4.0
LAMPS_X, LAMPS_Z, LAMP = 24, 48, 0.25
COLOURS = [("warm", (1.0, 0.72, 0.42)), ("cool", (0.62, 0.78, 1.0)), ("red", (1.0, 0.25, 0.2)),
           ("green", (0.3, 1.0, 0.35)), ("blue", (0.3, 0.4, 1.0)), ("amber", (1.0, 0.55, 0.1))]

def lamp(x, z):
    """A square lamp facing down, just below the ceiling (counter-clockwise seen from below)."""
    y, h = HEIGHT - 0.01, LAMP / 2
    return quad((x - h, y, z - h), (x + h, y, z - h), (x + h, y, z + h), (x - h, y, z + h))

def objects():
    w, h = WIDTH / 2, HEIGHT
    white, grey = diffuse("white", (0.7, 0.7, 0.7)), diffuse("floor", (0.45, 0.42, 0.4))
    out = room(w, h, LENGTH, grey, white) + [
        ("pillars", merge(*(cuboid((x, h / 2, z), (0.6, h, 0.6)) for x in (-6.0, 6.0)
                            for z in (6.0, 14.0, 22.0, 30.0, 38.0))), white),
    ]
    lamps = [[] for _ in COLOURS]
    for i in range(LAMPS_X):
        for j in range(LAMPS_Z):
            lamps[(i + 2 * j) % len(COLOURS)].append(lamp(-w + (i + 0.5) * WIDTH / LAMPS_X, (j + 0.5) * LENGTH / LAMPS_Z))
    for (name, rgb), quads in zip(COLOURS, lamps):
        out.append(("lamps_" + name, merge(*quads), emitter("lamp_" + name, rgb, 6.0, (0.8, 0.8, 0.8))))
    return out

def main():
    camera = look_at_camera("camera", (0.0, 1.7, 1.0), (0.0, 1.4, 30.0), 50.0)
    camera["aspectRatio"] = 16 / 9
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "lamp_hall.gltf")
    write_gltf(out, build_gltf(objects(), camera, "Prism make_lamp_hall.py", "Prism project", "lamp_hall"))

if __name__ == "__main__":
    main()
