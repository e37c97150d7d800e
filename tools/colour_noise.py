#!/usr/bin/env python3
"""Colour noise per sample of one or more Prism binaries on one scene (e.g. before and after a
change to wavelength sampling): K renders with seeds 1000..1000+K-1, back to back; for each pixel
the variance across the renders of R, G, B, the Rec.709 luminance Y and the colour differences
R-Y and B-Y, times spp (so: per sample), averaged over the image or a region; the image means with
their standard errors (they must agree between binaries); the median seconds per render.

    tools/colour_noise.py data/scenes/rough_dispersion.gltf --prism OLD_PRISM build/apps/prism \\
        --spp 16 --seeds 16 --width 128 --roi 0.16,0.36,0.53,0.62

Needs numpy and exrstats.py, the EXR reader of the Cycles harness in the shared assets
(PRISM_SHARED_DIR/tools/cycles); without them it prints `colour_noise: SKIPPED: ...` and exits 0.
"""
import argparse
import os
import statistics
import subprocess
import sys
import time

from shared_dir import shared_dir

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, str(shared_dir() / "tools" / "cycles"))
sys.dont_write_bytecode = True
try:
    import numpy as np
    import exrstats
except ImportError as e:
    if sys.executable != "/usr/bin/python3" and os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    print("colour_noise: SKIPPED: %s" % e)
    sys.exit(0)
from compare_cycles import LUMA, load_rgb


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene")
    ap.add_argument("--prism", nargs="+", default=[os.path.join(HERE, "..", "build", "apps", "prism")])
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--seeds", type=int, default=16)
    ap.add_argument("--width", type=int, default=128)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--roi", help="x0,y0,x1,y1 as fractions of the image (default: all of it)")
    ap.add_argument("--out", default="out/colour_noise")
    a, extra = ap.parse_known_args()  # unknown options (after --) go to prism render
    extra = [x for x in extra if x != "--"]
    os.makedirs(a.out, exist_ok=True)
    for n, binary in enumerate(a.prism):
        images, seconds = [], []
        for k in range(a.seeds):
            exr = os.path.join(a.out, "prism%d_%d.exr" % (n, k))
            cmd = [binary, "render", a.scene, "-o", exr, "--spp", str(a.spp), "--seed", str(1000 + k),
                   "--width", str(a.width), "--threads", str(a.threads), "-q"] + extra
            start = time.time()
            subprocess.run(cmd, check=True)
            seconds.append(time.time() - start)
            images.append(load_rgb(exrstats, exr)[0])
        x = np.stack(images)  # seeds, height, width, RGB
        if a.roi:
            x0, y0, x1, y1 = (float(v) for v in a.roi.split(","))
            h, w = x.shape[1:3]
            x = x[:, int(y0 * h):int(y1 * h), int(x0 * w):int(x1 * w)]
        y = x @ np.array(LUMA)
        channels = {"R": x[..., 0], "G": x[..., 1], "B": x[..., 2], "Y": y, "R-Y": x[..., 0] - y, "B-Y": x[..., 2] - y}
        print("%s: %.2f s/render" % (binary, statistics.median(seconds)))
        for name, v in channels.items():
            per_render = v.reshape(a.seeds, -1).mean(1)
            print("  %-3s variance/sample %.4g   mean %.5f ± %.5f" % (
                name, v.var(0, ddof=1).mean() * a.spp, per_render.mean(), per_render.std(ddof=1) / np.sqrt(a.seeds)))


if __name__ == "__main__":
    main()
