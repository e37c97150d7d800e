#!/usr/bin/python3
"""The error a render estimates for itself against its true error, under the default sampler.

For each scene: a long reference render, then renders at a few sample counts with several seeds.
Each render's header carries its own estimate, prism.estimatedRelRmse (README: the error
estimate); its true relative RMSE is sqrt(mean over pixels of (Y - Y_ref)^2 - the reference's own
estimated variance) / mean Y_ref, Y the Rec.709 luminance. Both are averaged over the seeds as mean
squares. The table prints estimate / truth, which should be 1 +- 0.2 (the test suite's margin).

With --compare OTHER_PRISM, it instead prints the true relative RMSE of both binaries at equal spp
against the same reference, the ratio of the samples they took, and the ratio of samples they
need for equal error, (RMSE ratio)² x samples ratio, MSE falling as 1/samples (the cost of a
sampler change, e.g. splitting a pixel's net into independently scrambled replicates).

    tools/bench_error_estimate.py [--prism build/apps/prism] [--compare OTHER] [--width 64]
        [--spp 4,16,64] [--seeds 4] [--ref-spp 4096] [--scenes Box,Duck,data/scenes/cornell.gltf]

A scene is a .gltf/.glb path or the name of an asset in assets/gltf of the shared assets
(PRISM_SHARED_DIR; rendered with --env 1,1,1). Reads EXRs with the Cycles harness's exrstats.py
(PRISM_SHARED_DIR/tools/cycles).
"""
import argparse
import os
import subprocess
import sys

from shared_dir import shared_dir

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = str(shared_dir())
sys.path.insert(0, os.path.join(SHARED, "tools", "cycles"))
sys.dont_write_bytecode = True  # never leave a __pycache__ in the shared assets
import exrstats  # noqa: E402
import numpy as np  # noqa: E402


def scene_args(scene):
    if scene.endswith((".gltf", ".glb")):
        return [scene]
    return [os.path.join(SHARED, "assets", "gltf", scene, "glTF", scene + ".gltf"), "--env", "1,1,1"]


def render(prism, a, scene, out, extra):
    cmd = [prism, "render"] + scene_args(scene) + ["-o", out, "--width", str(a.width), "-q"] + extra
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    img = exrstats.read_exr(out)
    ch = img["channels"]
    y = 0.2126 * np.asarray(ch["R"], dtype=np.float64) + 0.7152 * np.asarray(ch["G"], dtype=np.float64) + \
        0.0722 * np.asarray(ch["B"], dtype=np.float64)
    h = img["header"]
    samples = float(h["prism.samples"]) if "prism.samples" in h else float(h["prism.sppMean"]) * y.size
    return y, float(h["prism.estimatedRelRmse"]), samples


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--prism", default=os.path.join(HERE, "..", "build", "apps", "prism"))
    p.add_argument("--compare", help="another prism binary: print both true errors at equal spp instead")
    p.add_argument("--width", type=int, default=64)
    p.add_argument("--spp", default="4,16,64")
    p.add_argument("--seeds", type=int, default=4)
    p.add_argument("--ref-spp", type=int, default=4096)
    p.add_argument("--scenes", default="Box,AttenuationTest,MetalRoughSpheresNoTextures,TransmissionTest,Duck," +
                   os.path.join(HERE, "..", "data", "scenes", "cornell.gltf"))
    p.add_argument("--extra", default="", help="options for every render")
    p.add_argument("--out", default="out/bench_error_estimate")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    extra = a.extra.split()
    if a.compare:
        print("| scene | spp | true relRMSE, %s | true relRMSE, %s | ratio | samples ratio | "
              "samples for equal error: ratio² x samples ratio |" % (a.prism, a.compare))
        print("|---|---|---|---|---|---|---|")
    else:
        print("| scene | spp | estimated relRMSE | true relRMSE | estimated / true | per seed: min, max |")
        print("|---|---|---|---|---|---|")
    for scene in a.scenes.split(","):
        name = os.path.splitext(os.path.basename(scene))[0]
        ref, ref_est, _ = render(a.prism, a, scene, os.path.join(a.out, name + "_ref.exr"),
                              ["--spp", str(a.ref_spp), "--seed", "1000"] + extra)
        ref_mean = float(np.mean(ref))
        ref_mse = (ref_est * ref_mean) ** 2  # the reference's own noise, taken out of the squared error

        def errors(prism, spp):
            true_mse, est_mse, samples = [], [], 0.0
            for seed in range(a.seeds):
                y, est, n = render(prism, a, scene, os.path.join(a.out, "%s_%s_%d.exr" % (name, spp, seed)),
                                ["--spp", spp, "--seed", str(seed)] + extra)
                true_mse.append(float(np.mean((y - ref) ** 2)) - ref_mse)
                est_mse.append(est ** 2)
                samples += n
            true_mse, est_mse = np.array(true_mse), np.array(est_mse)
            per_seed = np.sqrt(est_mse / np.maximum(true_mse, 1e-30)) * ref_mean
            return (np.sqrt(max(np.mean(true_mse), 0)) / ref_mean, np.sqrt(np.mean(est_mse)),
                    (float(per_seed.min()), float(per_seed.max())), samples)

        for spp in a.spp.split(","):
            true, est, spread, samples = errors(a.prism, spp)
            if a.compare:
                other, _, _, other_samples = errors(a.compare, spp)
                ratio, cost = true / other, samples / other_samples
                print("| %s | %s | %.4f | %.4f | %.3f | %.3f | %.3f |" % (
                    name, spp, true, other, ratio, cost, ratio ** 2 * cost), flush=True)
            else:
                print("| %s | %s | %.4f | %.4f | %.2f | %.2f, %.2f |" % ((name, spp, est, true, est / true) + spread),
                      flush=True)
        print("| %s | reference: %d spp, own estimate %.5f | | | |" % (name, a.ref_spp, ref_est), flush=True)


if __name__ == "__main__":
    main()
