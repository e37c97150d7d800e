#!/usr/bin/env python3
"""Generate data/scenes/screen_room.gltf: a dark room lit only by a screen showing a city at night.

An emissive-texture scene for light sampling: the screen (3.2 m x 1.8 m, two triangles) carries a
256 x 144 texture that is nearly black but for the lit windows of a skyline, about a twentieth of
its texels; it lights a room with a sofa and a low table. Weighed by the texture's mean and sampled
uniformly, most light samples land on the dark texels; sampled by its texels, they land on the
windows (see "Light sampling" in the README).

Run from the repository root:
    python3 data/scenes/make_screen_room.py
Standard library only (helpers in gltf_builder.py); the texture is a seeded pseudo-random skyline.
"""
import os
import random

from gltf_builder import build_gltf, cuboid, diffuse, look_at_camera, png, quad, room, write_gltf

TEX_W, TEX_H = 256, 144

def skyline():
    """Rows (top first) of a night skyline: a dark blue sky, black buildings, warm lit windows."""
    rng = random.Random(7)
    sky, wall = (6, 8, 22), (2, 2, 3)
    rows = [[sky] * TEX_W for _ in range(TEX_H)]
    x = 0
    while x < TEX_W:
        width, height = rng.randint(10, 26), rng.randint(30, 130)
        lit = rng.uniform(0.15, 0.5)
        for bx in range(x, min(x + width, TEX_W)):
            for by in range(TEX_H - height, TEX_H):
                rows[by][bx] = wall
        # Windows: 2 x 3 texel cells on a 4 x 5 grid, each lit with probability `lit`.
        for wx in range(x + 2, min(x + width - 2, TEX_W - 2), 4):
            for wy in range(TEX_H - height + 3, TEX_H - 3, 5):
                if rng.random() < lit:
                    colour = rng.choice([(255, 214, 140), (255, 240, 200), (200, 220, 255)])
                    for dx in range(2):
                        for dy in range(3):
                            rows[wy + dy][wx + dx] = colour
        x += width + rng.randint(0, 4)
    return rows

def objects():
    w, h, d = 3.0, 3.0, 6.0  # half width, height, depth
    white, dark = diffuse("wall", (0.6, 0.6, 0.6)), diffuse("fabric", (0.35, 0.3, 0.28))
    screen = {"name": "screen", "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0],
                                                         "metallicFactor": 0.0, "roughnessFactor": 1.0},
              "emissiveFactor": [1.0, 1.0, 1.0], "emissiveTexture": {"index": 0},
              "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 12.0}}}
    # The screen on the far wall (z = d), facing the room (−z); u along −x (left to right as seen
    # from the room), v down the texture.
    sx, sy, sz = 1.6, 1.7, d - 0.02
    panel = quad((sx, sy - 0.9, sz), (-sx, sy - 0.9, sz), (-sx, sy + 0.9, sz), (sx, sy + 0.9, sz))
    panel["uvs"] = [(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)]
    return room(w, h, d, white, white) + [
        ("sofa", cuboid((0.0, 0.4, 1.6), (2.4, 0.8, 0.9)), dark),
        ("table", cuboid((0.0, 0.25, 3.4), (1.2, 0.5, 0.7)), dark),
        ("screen", panel, screen),
    ]

def main():
    camera = look_at_camera("camera", (2.4, 1.6, 0.4), (-0.6, 0.9, 4.0), 65.0)
    camera["aspectRatio"] = 16 / 9
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "screen_room.gltf")
    write_gltf(out, build_gltf(objects(), camera, "Prism make_screen_room.py", "Prism project", "screen_room",
                               images=[png(TEX_W, TEX_H, skyline())]))

if __name__ == "__main__":
    main()
