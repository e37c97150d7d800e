#!/usr/bin/python3
"""Adaptive against uniform sampling: the time each needs to reach the same error.

For each scene: a long uniform reference render; uniform renders at doubling sample counts and
adaptive renders (--noise-threshold) at several thresholds, each measured against the reference
(relative MSE, Rousselle et al. 2011: the mean over pixels and R, G, B of (x - ref)² / (ref² + 0.01),
so that neither bright emitters nor black pixels dominate). Each adaptive render's
time is compared with the time the uniform renders need for the same error (log-log interpolation
between the two uniform renders that bracket it). Ratios below 1 mean adaptive sampling wins.

    tools/bench_adaptive.py [--prism build/apps/prism] [--width 96] [--ref-spp 4096]
                            [--scenes data/scenes/cornell.gltf,...] [--out out/bench_adaptive] [--extra '--env 1,1,1']

Reads EXRs with exrstats.py (pure Python + numpy) from the Cycles harness of the shared assets
(PRISM_SHARED_DIR, tools/cycles). The seconds are compared, so run it on an otherwise idle machine.
"""
import argparse
import math
import os
import subprocess
import sys

from shared_dir import shared_dir

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, str(shared_dir() / "tools" / "cycles"))
sys.dont_write_bytecode = True  # never leave a __pycache__ in the shared assets
import exrstats  # noqa: E402
import numpy as np  # noqa: E402


def render(a, scene, out, extra):
    cmd = [a.prism, "render", scene, "-o", out, "--width", str(a.width), "-q"] + a.extra.split() + extra
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    img = exrstats.read_exr(out)
    rgb = np.stack([img["channels"][c] for c in "RGB"], axis=1)
    return rgb, float(img["header"]["prism.seconds"]), float(img["header"]["prism.sppMean"])


def rel_mse(rgb, ref):
    return float(np.mean((rgb - ref) ** 2 / (ref ** 2 + 0.01)))


def uniform_time_at(error, curve):
    """Seconds the uniform renders (sorted by time, error falling) need to reach `error`."""
    for (t0, e0), (t1, e1) in zip(curve, curve[1:]):
        if e1 <= error <= e0:
            f = math.log(e0 / error) / math.log(e0 / e1)
            return math.exp(math.log(t0) + f * math.log(t1 / t0))
    return None


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--prism", default=os.path.join(HERE, "..", "build", "apps", "prism"))
    p.add_argument("--width", type=int, default=96)
    p.add_argument("--ref-spp", type=int, default=4096)
    p.add_argument("--scenes", default=os.path.join(HERE, "..", "data", "scenes", "cornell.gltf"))
    p.add_argument("--uniform-spp", default="16,32,64,128,256,512")
    p.add_argument("--thresholds", default="0.1,0.05,0.03,0.02")
    p.add_argument("--max-spp", type=int, default=512)
    p.add_argument("--out", default="out/bench_adaptive")
    p.add_argument("--extra", default="", help="options for every render, e.g. '--env 1,1,1'")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    print("| scene | threshold | adaptive: s, mean spp, relMSE | uniform s at that error | ratio |")
    print("|---|---|---|---|---|")
    for scene in a.scenes.split(","):
        name = os.path.splitext(os.path.basename(scene))[0]
        ref, _, _ = render(a, scene, os.path.join(a.out, name + "_ref.exr"), ["--spp", str(a.ref_spp), "--seed", "99"])
        curve = []
        for spp in a.uniform_spp.split(","):
            rgb, s, _ = render(a, scene, os.path.join(a.out, "%s_u%s.exr" % (name, spp)), ["--spp", spp])
            curve.append((s, rel_mse(rgb, ref)))
        for t in a.thresholds.split(","):
            rgb, s, mean_spp = render(a, scene, os.path.join(a.out, "%s_a%s.exr" % (name, t)),
                                      ["--spp", str(a.max_spp), "--noise-threshold", t])
            e = rel_mse(rgb, ref)
            u = uniform_time_at(e, curve)
            print("| %s | %s | %.2f s, %.0f spp, %.5f | %s | %s |" % (
                name, t, s, mean_spp, e, "%.2f s" % u if u else "outside the uniform range",
                "%.2f" % (s / u) if u else "-"))
        print("| %s | uniform curve | %s | | |" % (name, ", ".join("%.2f s: %.5f" % c for c in curve)))


if __name__ == "__main__":
    main()
