#!/usr/bin/env python3
"""Generate data/scenes/rough_dispersion.gltf: the dispersion scene with a frosted prism.

The flint-glass prism of dispersion.gltf (SCHOTT N-SF11) with GGX roughness 0.3: light through it
still splits by wavelength, but into blurred lobes, which the path tracer samples at the hero
wavelength's index and weighs over all its wavelengths (hero-wavelength spectral MIS). The scene
for measuring that estimator's colour noise (docs/design.md, "Dispersion and spectral MIS").

Run:  python3 data/scenes/make_rough_dispersion.py
Standard library only (helpers in gltf_builder.py).
"""
import copy
import os

import make_dispersion
from gltf_builder import build_gltf, look_at_camera, write_gltf

HERE = os.path.dirname(os.path.abspath(__file__))
ROUGHNESS = 0.3


def main():
    objects = copy.deepcopy(make_dispersion.OBJECTS)
    for name, _, material in objects:
        if name == "prism":
            material["pbrMetallicRoughness"]["roughnessFactor"] = ROUGHNESS
    write_gltf(os.path.join(HERE, "rough_dispersion.gltf"),
               build_gltf(objects, look_at_camera("camera", (0.0, 1.6, 2.6), (0.3, 0.1, 0.0), 40.0),
                          "Prism make_rough_dispersion.py", "Prism project", "rough_dispersion"))


if __name__ == "__main__":
    main()
