#!/usr/bin/env python3
"""Agreement with a peer: render the shared glTF assets (and, on request, the project's many-light scenes
lamp_hall and screen_room) with Prism and with Blender 3.4 Cycles
(the harness in tools/cycles of the shared assets, PRISM_SHARED_DIR) at the same size, camera,
spp and bounce limit, back to back, and compare the images in linear Rec.709.

    tools/compare_cycles.py [--spp 1024] [--width 320] [--height H] [--assets Box,TransmissionTest]
                            [--threads 2] [--max-depth 16] [--out out/compare_cycles] [--previews]

For each asset it prints the image means (R, G, B and Rec.709 luminance Y) of both renderers,
their relative difference (Prism / Cycles - 1), the RMSE relative to Cycles' mean, and the
seconds of each renderer; it writes both EXRs, the logs and summary.md / summary.csv to --out.
tools/README.md has the conventions (units, bounces, cameras); docs/performance.md the figures and the
known differences.

Skips (message, exit 0) when the shared assets (PRISM_SHARED_DIR, see tools/shared_dir.py) or
Blender are absent. Exit 1 when a render fails.
Needs Python 3 and numpy (which the Cycles harness needs anyway).
"""
import argparse
import copy
import csv
import json
import math
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import time

from shared_dir import shared_dir

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The shared assets both renderers load, each read from
# PRISM_SHARED_DIR/assets/gltf/<name>/glTF/<name>.gltf.
ASSETS = ["MetalRoughSpheresNoTextures", "TransmissionTest", "TransmissionRoughnessTest", "GlassVaseFlowers",
          "LightsPunctualLamp", "EmissiveStrengthTest", "AttenuationTest", "Box"]
# --equal-error's reference length where 2048 spp is too short: LightsPunctualLamp's point-light
# peaks are heavy-tailed, and with 2 x 1024 spp references its ratio moved by +-0.2 between runs.
REFERENCE_SPP = {"LightsPunctualLamp": 16384}
# The layered-material assets, compared on request with --assets.
LAYERED_ASSETS = ["ClearcoatWicker", "ClearCoatCarPaint", "SheenCloth", "SpecularTest"]
# The project's own many-light scenes (data/scenes/<name>.gltf), compared on request with --assets.
SCENES = ["lamp_hall", "screen_room"]
KNOWN = ASSETS + LAYERED_ASSETS + SCENES

DEFAULT_ASPECT = 4.0 / 3.0  # image aspect for assets without a camera
LUMA = (0.2126, 0.7152, 0.0722)  # Rec.709 luminance of linear Rec.709 RGB


def skip(message):
    print("compare_cycles: SKIPPED: " + message)
    sys.exit(0)


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--spp", type=int, default=1024, help="samples per pixel for both (default 1024)")
    ap.add_argument("--width", type=int, default=320, help="image width for both (default 320)")
    ap.add_argument("--height", type=int, default=0,
                    help="image height for both (default: width / the camera's aspectRatio, 4:3 without one)")
    ap.add_argument("--assets", default=",".join(ASSETS),
                    help="comma-separated subset of: " + ", ".join(KNOWN))
    ap.add_argument("--threads", type=int, default=2, help="threads for each renderer (default 2)")
    ap.add_argument("--max-depth", type=int, default=16,
                    help="Prism --max-depth D (bounces, camera hit = 0); Cycles gets --max-bounces D-1 (default 16)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--camera", type=int, default=0,
                    help="camera index in glTF node-index order (the harness's --camera-index); mapped to "
                         "Prism's scene-order index (default 0)")
    ap.add_argument("--env", default="1,1,1",
                    help="constant environment R,G,B given to BOTH renderers for assets without lights (no "
                         "punctual light and no untextured emissive material); assets with lights get none; "
                         "'none': never (default 1,1,1)")
    ap.add_argument("--out", default=os.path.join(REPO, "out", "compare_cycles"),
                    help="directory for the EXRs, logs and summary.md/summary.csv (default out/compare_cycles)")
    ap.add_argument("--shared", default=str(shared_dir()),
                    help="the shared assets' folder (default: PRISM_SHARED_DIR, else shared/ beside the "
                         "project's root; now %(default)s)")
    ap.add_argument("--prism", default=os.path.join(REPO, "build", "apps", "prism"), help="Prism executable")
    ap.add_argument("--blender", default=os.environ.get("BLENDER", "blender"), help="Blender executable")
    ap.add_argument("--nice", type=int, default=int(os.environ.get("NICE", "10")),
                    help="nice level for both renderers (the harness's default: 10)")
    ap.add_argument("--previews", action="store_true",
                    help="also write an 8-bit sRGB preview, Prism left and Cycles right, per asset")
    ap.add_argument("--equal-error", action="store_true",
                    help="instead of one comparison, the time each renderer needs to reach the same error: each "
                         "against its own reference (two independent halves, their noise subtracted) over a "
                         "ladder of spp budgets; see tools/README.md")
    ap.add_argument("--ladder", default="4,8,16,32,64,128,256",
                    help="--equal-error: the spp budgets, comma-separated (default 4,8,16,32,64,128,256)")
    ap.add_argument("--ref-spp", type=int, default=None,
                    help="--equal-error: spp of each renderer's reference, rendered as two halves with other seeds "
                         "(default 2048; LightsPunctualLamp 16384)")
    ap.add_argument("--repeat", type=int, default=1,
                    help="--equal-error: render each rung this many times, Cycles and Prism alternated, and take "
                         "each one's median seconds (the images repeat: the seed is fixed); on a noisy machine, 3")
    ap.add_argument("--reuse-references", action="store_true",
                    help="--equal-error: keep references already in --out for the same size, depth and spp")
    ap.add_argument("--references-only", action="store_true",
                    help="--equal-error: render the references and exit (to split a long run into short ones)")
    ap.add_argument("--conventions", action="store_true",
                    help="instead of the assets, check the unit and bounce conventions on the harness's "
                         "point-light plane and Cornell box (64 spp, 128x128)")
    a = ap.parse_args()
    if a.spp < 1 or a.width < 1 or a.height < 0 or a.threads < 1 or a.max_depth < 1 or a.camera < 0:
        ap.error("--spp, --width, --threads and --max-depth must be >= 1; --height and --camera >= 0")
    a.assets = [s for s in (x.strip() for x in a.assets.split(",")) if s]
    try:
        a.ladder = sorted({int(x) for x in a.ladder.split(",") if x.strip()})
    except ValueError:
        ap.error("--ladder takes comma-separated integers")
    if a.equal_error and (not a.ladder or a.ladder[0] < 1 or (a.ref_spp is not None and a.ref_spp < 2) or a.repeat < 1):
        ap.error("--ladder needs spp >= 1, --ref-spp >= 2 and --repeat >= 1")
    return a


# --------------------------------------------------------------------------- glTF inspection
def scene_roots(g):
    if g.get("scenes"):
        return g["scenes"][g.get("scene", 0)].get("nodes", [])
    children = {c for n in g.get("nodes", []) for c in n.get("children", [])}
    return [i for i in range(len(g.get("nodes", []))) if i not in children]


def scene_nodes_dfs(g):
    """Nodes of the default scene in depth-first order: the order Prism collects cameras in."""
    out = []

    def visit(i):
        out.append(i)
        for c in g["nodes"][i].get("children", []):
            visit(c)
    for r in scene_roots(g):
        visit(r)
    return out


def inspect_gltf(g):
    nodes = scene_nodes_dfs(g)
    cam_dfs = [i for i in nodes if "camera" in g["nodes"][i]]
    cam_by_index = sorted(cam_dfs)  # the harness's order: glTF node index
    punctual = [i for i in nodes if "KHR_lights_punctual" in g["nodes"][i].get("extensions", {})]
    used_materials = set()
    for i in nodes:
        m = g["nodes"][i].get("mesh")
        if m is not None:
            for p in g["meshes"][m].get("primitives", []):
                if "material" in p:
                    used_materials.add(p["material"])
    emissive, emissive_textured = [], []
    for mi in sorted(used_materials):
        mat = g["materials"][mi]
        strength = mat.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
        if max(mat.get("emissiveFactor", [0, 0, 0])) * strength > 0:
            # Emission through an emissiveTexture (label text, a lamp's glowing parts) is decoration,
            # not the scene's lighting: such an asset is meant to be lit by an environment.
            (emissive_textured if "emissiveTexture" in mat else emissive).append(mat.get("name", "material%d" % mi))
    return dict(cam_dfs=cam_dfs, cam_by_index=cam_by_index, punctual=punctual, emissive=emissive,
                emissive_textured=emissive_textured)


def camera_aspect(g, node):
    cam = g["cameras"][g["nodes"][node]["camera"]]
    if cam.get("type") == "perspective":
        return cam["perspective"].get("aspectRatio")
    o = cam.get("orthographic", {})
    return abs(o["xmag"] / o["ymag"]) if o.get("ymag") else None


def write_with_camera(src, g, cam, width, height, dest_dir):
    """A copy of the .gltf `src` in dest_dir with the harness's auto camera added as a root node of the
    default scene; every other file of the source folder is symlinked so relative URIs still resolve."""
    if os.path.isdir(dest_dir):
        shutil.rmtree(dest_dir)
    os.makedirs(dest_dir)
    src_dir = os.path.dirname(os.path.abspath(src))
    for name in os.listdir(src_dir):
        if name != os.path.basename(src):
            os.symlink(os.path.join(src_dir, name), os.path.join(dest_dir, name))
    g = copy.deepcopy(g)
    g.setdefault("cameras", []).append({
        "name": "harness_auto_camera", "type": "perspective",
        "perspective": {"yfov": cam["yfov"], "znear": cam["znear"], "aspectRatio": width / height}})
    g["nodes"].append({"name": "harness_auto_camera", "camera": len(g["cameras"]) - 1,
                       "translation": cam["translation"], "rotation": cam["rotation"]})
    if g.get("scenes"):
        g["scenes"][g.get("scene", 0)].setdefault("nodes", []).append(len(g["nodes"]) - 1)
    out = os.path.join(dest_dir, os.path.basename(src))
    with open(out, "w") as f:
        json.dump(g, f)
    return out


def asset_setup(a, assets_dir, name):
    """The asset's file, glTF, cameras, image size and environment (only for assets without lights)."""
    src = (os.path.join(REPO, "data", "scenes", name + ".gltf") if name in SCENES
           else os.path.join(assets_dir, name, "glTF", name + ".gltf"))
    with open(src) as f:
        g = json.load(f)
    info = inspect_gltf(g)
    cams = info["cam_by_index"]
    if cams and a.camera >= len(cams):
        raise RuntimeError("--camera %d: the asset has %d camera(s)" % (a.camera, len(cams)))
    aspect = (camera_aspect(g, cams[a.camera]) if cams else None) or DEFAULT_ASPECT
    has_light = bool(info["punctual"] or info["emissive"])
    return dict(src=src, g=g, info=info, cams=cams, width=a.width, height=a.height or max(1, round(a.width / aspect)),
                has_light=has_light, env=None if has_light or a.env == "none" else a.env)


def prism_scene(a, s, auto, work):
    """The file and camera index Prism renders: the asset when it has a camera, else a copy of it with the
    camera the harness framed (`auto`, from Cycles' log)."""
    if s["cams"]:
        return s["src"], s["info"]["cam_dfs"].index(s["cams"][a.camera])
    if auto is None:
        raise RuntimeError("the harness printed no auto_camera_gltf line; see the Cycles log in %s" % work)
    return write_with_camera(s["src"], s["g"], auto, s["width"], s["height"], os.path.join(work, "scene")), 0


# --------------------------------------------------------------------------- renderers
def run_cycles(a, harness, gltf, exr, width, height, cam_index, env, spp=None, max_depth=None,
               lighting_mode="COMPAT", seed=None):
    """Cycles through the harness. `max_depth` is in Prism's convention; Cycles gets max_depth - 1."""
    cmd = [os.path.join(harness, "render_gltf.sh"), "--in", gltf, "--out", exr, "--spp", str(spp or a.spp),
           "--width", str(width), "--height", str(height), "--max-bounces", str((max_depth or a.max_depth) - 1),
           "--seed", str(a.seed if seed is None else seed), "--threads", str(a.threads), "--camera-index", str(cam_index),
           "--lighting-mode", lighting_mode, "--filter", "box", "--filter-width", "1",
           "--timings-json", exr + ".json"]
    if env:
        cmd += ["--env", env]
    t0 = time.perf_counter()
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       env=dict(os.environ, BLENDER=a.blender, NICE=str(a.nice)))
    wall = time.perf_counter() - t0
    lines = r.stdout.strip().splitlines()
    last = lines[-1] if lines else ""
    if r.returncode != 0 or not last.startswith("cycles_render_s="):
        raise RuntimeError("Cycles failed (rc=%d); log: %s.log\n%s" % (r.returncode, exr, "\n".join(lines[-15:])))
    rec = {}
    for kv in last.split():
        k, _, v = kv.partition("=")
        try:
            rec[k] = float(v)
        except ValueError:
            rec[k] = v
    rec["script_wall_s"] = wall
    auto = None
    for line in lines:
        m = re.search(r"auto_camera_gltf=(\{.*\})", line)
        if m:
            auto = json.loads(m.group(1))
    notes = [l[len("[render_gltf] "):] for l in lines
             if l.startswith("[render_gltf]") and re.search(r"WARNING|fixup|NOTE|AUTO-CAMERA", l)]
    return rec, auto, notes


def run_prism(a, gltf, exr, width, height, cam_index, env, spp=None, max_depth=None, seed=None):
    cmd = ["nice", "-n", str(a.nice), a.prism, "render", gltf, "-o", exr, "--spp", str(spp or a.spp),
           "--width", str(width), "--height", str(height), "--max-depth", str(max_depth or a.max_depth),
           "--seed", str(a.seed if seed is None else seed), "--threads", str(a.threads), "--camera", str(cam_index)]
    if env:
        cmd += ["--env", env]
    # An asset given a camera is rendered from a copy whose buffers and images are symlinks into the
    # asset's folder (write_with_camera); Prism's file policy follows them only when told to.
    cmd += ["--allow-external-paths"]
    ru0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.perf_counter() - t0
    ru1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    # The progress bar rewrites one line with '\r'; keep only the final state of each line.
    log = "\n".join(l.split("\r")[-1] for l in r.stdout.splitlines())
    with open(exr + ".log", "w") as f:
        f.write(" ".join(cmd) + "\n" + log + "\n")
    if r.returncode != 0 or not os.path.isfile(exr):
        raise RuntimeError("Prism failed (rc=%d); log: %s.log\n%s"
                           % (r.returncode, exr, "\n".join(log.splitlines()[-15:])))
    rec = dict(wall_s=wall, cpu_s=(ru1.ru_utime - ru0.ru_utime) + (ru1.ru_stime - ru0.ru_stime))
    m = re.search(r"loaded .* in ([0-9.]+) s", log)
    rec["load_s"] = float(m.group(1)) if m else float("nan")
    m = re.search(r"built the BVH over \d+ triangles in ([0-9.]+) ms", log)
    rec["bvh_s"] = float(m.group(1)) / 1e3 if m else float("nan")
    warnings = sorted({l.split(": ", 2)[-1] for l in log.splitlines() if l.startswith("warning:")})
    return rec, warnings


# --------------------------------------------------------------------------- comparison
def load_rgb(exrstats, path):
    import numpy as np
    img = exrstats.read_exr(path)
    names = exrstats.rgb_names(list(img["channels"]))
    if len(names) != 3:
        raise RuntimeError("%s: no R, G, B channels" % path)
    rgb = np.stack([np.asarray(img["channels"][n], dtype=np.float64) for n in names], axis=-1)
    return rgb.reshape(img["height"], img["width"], 3), img["header"]


def compare(p, c, env):
    import numpy as np
    bad_p = int((~np.isfinite(p)).sum())
    bad_c = int((~np.isfinite(c)).sum())
    p = np.where(np.isfinite(p), p, 0.0)
    c = np.where(np.isfinite(c), c, 0.0)
    luma = np.asarray(LUMA)
    yp, yc = p @ luma, c @ luma
    mp = list(p.reshape(-1, 3).mean(axis=0)) + [float(yp.mean())]
    mc = list(c.reshape(-1, 3).mean(axis=0)) + [float(yc.mean())]
    rel = [(x / y - 1.0) if y != 0 else float("nan") for x, y in zip(mp, mc)]
    mean_c = float(c.mean())
    rmse_rgb = float(np.sqrt(((p - c) ** 2).mean())) / mean_c if mean_c else float("nan")
    rmse_y = float(np.sqrt(((yp - yc) ** 2).mean())) / mc[3] if mc[3] else float("nan")

    # The same on 4x4 pixel blocks: Monte Carlo noise falls about 4x, systematic differences stay.
    def blocks(y):
        h, w = (y.shape[0] // 4) * 4, (y.shape[1] // 4) * 4
        return y[:h, :w].reshape(h // 4, 4, w // 4, 4).mean(axis=(1, 3))
    bp, bc = blocks(yp), blocks(yc)
    rmse_y4 = float(np.sqrt(((bp - bc) ** 2).mean())) / float(bc.mean()) if bc.mean() else float("nan")

    # With a constant environment, pixels that see only the background are the same in both and
    # dilute the image-mean difference. "Foreground": pixels where Cycles' value is not the
    # environment's (some sample hit geometry); the mean of Y over those alone.
    fg_frac, fg_rel = float("nan"), float("nan")
    if env:
        e = np.asarray([float(x) for x in env.split(",")] * (3 if env.count(",") == 0 else 1))
        fg = np.abs(c - e).max(axis=-1) > 1e-5 * max(float(e.max()), 1e-12)
        fg_frac = float(fg.mean())
        if fg.any() and yc[fg].mean() != 0:
            fg_rel = float(yp[fg].mean() / yc[fg].mean() - 1.0)
    return dict(mean_prism=mp, mean_cycles=mc, rel=rel, rmse_rgb=rmse_rgb, rmse_y=rmse_y, rmse_y4=rmse_y4,
                fg_frac=fg_frac, fg_rel=fg_rel, nonfinite_prism=bad_p, nonfinite_cycles=bad_c)


def write_preview(exrstats, p, c, path):
    """Prism (left) and Cycles (right) side by side, linear values clipped and sRGB-encoded."""
    import numpy as np
    rgb = np.concatenate([p, np.zeros((p.shape[0], 4, 3)), c], axis=1)
    h, w, _ = rgb.shape
    flat = rgb.reshape(-1, 3)
    exrstats.write_png(path, w, h, flat[:, 0], flat[:, 1], flat[:, 2])


def pct(x):
    return "n/a" if x != x else "%+.1f%%" % (100 * x)


# --------------------------------------------------------------------------- conventions
def check_conventions(a, harness, exrstats):
    """Renders the harness's analytic scenes to confirm the two conventions the comparison rests on."""
    import numpy as np
    scenes = os.path.join(harness, "scenes")
    work = os.path.join(a.out, "conventions")
    os.makedirs(work, exist_ok=True)

    def roi_y(path, x0, y0, x1, y1):
        rgb, _ = load_rgb(exrstats, path)
        return float(rgb[y0:y1, x0:x1].reshape(-1, 3).mean(axis=0) @ np.asarray(LUMA))

    ok = True
    # 1. Units: a point light of 683·π cd, 1 m above a ρ = 0.8 Lambertian plane (no specular:
    #    KHR_materials_ior 1.0). Prism reads candela with emission in cd/m², so the plane's radiance
    #    is 0.8·683 = 546.4; Cycles' COMPAT mode gives the same, SPEC divides by 683 (0.8).
    plane = os.path.join(scenes, "pointlight_plane.gltf")
    roi = (62, 62, 66, 66)
    run_prism(a, plane, os.path.join(work, "plane_prism.exr"), 128, 128, 0, None, spp=64, max_depth=1)
    y_prism = roi_y(os.path.join(work, "plane_prism.exr"), *roi)
    y = {}
    for mode in ("COMPAT", "SPEC"):
        exr = os.path.join(work, "plane_cycles_%s.exr" % mode)
        run_cycles(a, harness, plane, exr, 128, 128, 0, None, spp=64, max_depth=1, lighting_mode=mode)
        y[mode] = roi_y(exr, *roi)
    print("units: point light 683*pi cd 1 m above a rho=0.8 plane, centre luminance (expected 546.4 = 0.8*683 "
          "in cd/m2):")
    print("  Prism %.2f   Cycles COMPAT %.2f (Prism/COMPAT = %.4f)   Cycles SPEC %.4f (Prism/SPEC = %.1f)"
          % (y_prism, y["COMPAT"], y_prism / y["COMPAT"], y["SPEC"], y_prism / y["SPEC"]))
    good = abs(y_prism / y["COMPAT"] - 1) < 0.01 and abs(y_prism / 546.4 - 1) < 0.01
    ok &= good
    print("  %s: Prism's punctual units are the importer's COMPAT mode (SPEC is 683x darker)"
          % ("PASS" if good else "FAIL"))

    # 2. Bounces: the Cornell box's ceiling is lit only indirectly (its light is on the ceiling).
    #    Prism --max-depth D (camera hit = depth 0) must match Cycles --max-bounces D-1.
    cornell = os.path.join(scenes, "cornell.gltf")
    ceiling = (20, 4, 40, 12)
    print("bounces: Cornell box ceiling (lit only indirectly), mean luminance:")
    vals = {}
    for d in (1, 2):
        pe, ce = os.path.join(work, "cornell_prism_D%d.exr" % d), os.path.join(work, "cornell_cycles_B%d.exr" % (d - 1))
        run_prism(a, cornell, pe, 128, 128, 0, None, spp=64, max_depth=d)
        run_cycles(a, harness, cornell, ce, 128, 128, 0, None, spp=64, max_depth=d)
        vals[d] = (roi_y(pe, *ceiling), roi_y(ce, *ceiling))
        print("  Prism --max-depth %d: %.5f   Cycles --max-bounces %d: %.5f" % (d, vals[d][0], d - 1, vals[d][1]))
    good = vals[1] == (0.0, 0.0) and min(vals[2]) > 0
    ok &= good
    print("  %s: depth 1 = bounces 0 is direct light only (black ceiling) in both; depth 2 = bounces 1 lights it"
          % ("PASS" if good else "FAIL"))
    return 0 if ok else 1


# --------------------------------------------------------------------------- equal error
REF_SEEDS = (1001, 1002)  # the references' two halves; the ladder uses --seed


def debiased_rel_rmse(x, h1, h2):
    """RMSE of x against the reference (h1 + h2) / 2, relative to its mean, with the reference's own noise
    subtracted: E|x - ref|^2 = MSE(x) + Var(ref), and Var(ref) = E|h1 - h2|^2 / 4 for independent halves."""
    ref = (h1 + h2) / 2
    mse = float(((x - ref) ** 2).mean() - ((h1 - h2) ** 2).mean() / 4)
    return math.sqrt(max(mse, 0.0)) / float(ref.mean())


def reference_rel_rmse(h1, h2):
    """The reference's own relative RMSE (its noise; the mean of two halves)."""
    return math.sqrt(float(((h1 - h2) ** 2).mean()) / 4) / float(((h1 + h2) / 2).mean())


def time_at_error(rungs, target):
    """Seconds to reach relative RMSE `target`, by linear interpolation of log(seconds) against log(error)
    between the two rungs that bracket it (or extrapolation from the two nearest); and whether it extrapolated."""
    pts = [(math.log(r["error"]), math.log(r["seconds"])) for r in rungs if r["error"] > 0 and r["seconds"] > 0]
    if len(pts) < 2:
        return float("nan"), True
    lt = math.log(target)
    for (e0, t0), (e1, t1) in zip(pts, pts[1:]):
        if min(e0, e1) <= lt <= max(e0, e1) and e0 != e1:
            return math.exp(t0 + (t1 - t0) * (lt - e0) / (e1 - e0)), False
    (e0, t0), (e1, t1) = (pts[-2], pts[-1]) if lt < pts[-1][0] else (pts[0], pts[1])
    if e0 == e1:
        return float("nan"), True
    return math.exp(t0 + (t1 - t0) * (lt - e0) / (e1 - e0)), True


def render_both(a, harness, s, work, stem, spp, seed, auto):
    """Cycles then Prism at spp with this seed: (cycles record, prism record, Cycles' auto camera)."""
    cyc_exr, prism_exr = os.path.join(work, "cycles_" + stem + ".exr"), os.path.join(work, "prism_" + stem + ".exr")
    cyc, cyc_auto, _ = run_cycles(a, harness, s["src"], cyc_exr, s["width"], s["height"], a.camera, s["env"], spp=spp,
                                  seed=seed)
    auto = auto or cyc_auto
    prism_in, prism_cam = prism_scene(a, s, auto, work)
    prism, _ = run_prism(a, prism_in, prism_exr, s["width"], s["height"], prism_cam, s["env"], spp=spp, seed=seed)
    return cyc, prism, auto


def equal_error(a, harness, exrstats, assets_dir):
    import numpy as np

    def image(path):
        rgb, header = load_rgb(exrstats, path)
        return np.where(np.isfinite(rgb), rgb, 0.0), header

    print("Equal-error time, Prism vs Cycles (Blender 3.4): %d threads each, Prism --max-depth %d = Cycles "
          "--max-bounces %d, references in two halves (seeds %d, %d), ladder %s spp (seed %d). Seconds: path "
          "tracing only (Prism's prism.seconds, Cycles' cycles_pathtrace_s), each rung's the median of %d."
          % (a.threads, a.max_depth, a.max_depth - 1, *REF_SEEDS, ",".join(map(str, a.ladder)), a.seed, a.repeat))
    results, failed = [], []
    for name in a.assets:
        work = os.path.join(a.out, name)
        os.makedirs(work, exist_ok=True)
        try:
            s = asset_setup(a, assets_dir, name)
            ref_spp = a.ref_spp if a.ref_spp is not None else REFERENCE_SPP.get(name, 2048)
            half = ref_spp // 2
            print("\n== %s  %dx%d, %s; references 2 x %d spp" % (name, s["width"], s["height"],
                                          "env " + s["env"] if s["env"] else "its own lights", half), flush=True)
            camera_file = os.path.join(work, "auto_camera.json")
            auto = None
            if os.path.isfile(camera_file):
                with open(camera_file) as f:
                    auto = json.load(f)
            refs = {}
            for k, seed in enumerate(REF_SEEDS):
                stem = "ref%d_%dspp_%dx%d_d%d" % (k, half, s["width"], s["height"], a.max_depth)
                paths = [os.path.join(work, r + "_" + stem + ".exr") for r in ("cycles", "prism")]
                if not (a.reuse_references and all(map(os.path.isfile, paths)) and (auto or s["cams"])):
                    t0 = time.perf_counter()
                    _, _, auto = render_both(a, harness, s, work, stem, half, seed, auto)
                    print("  reference half %d: %d spp each, %.0f s" % (k + 1, half, time.perf_counter() - t0),
                          flush=True)
                    if auto:
                        with open(camera_file, "w") as f:
                            json.dump(auto, f)
                for r, path in zip(("cycles", "prism"), paths):
                    refs.setdefault(r, []).append(image(path)[0])
            ref_noise = {r: reference_rel_rmse(*refs[r]) for r in ("cycles", "prism")}
            for r in ("cycles", "prism"):
                print("  %s reference: rel RMSE of its own noise %.5f" % (r, ref_noise[r]))
            if a.references_only:
                continue
            rungs = {"cycles": [], "prism": []}
            print("  %6s  %10s %10s  %10s %10s" % ("spp", "Cycles s", "rel RMSE", "Prism s", "rel RMSE"))
            for spp in a.ladder:
                stem = "%dspp" % spp
                seconds = {"cycles": [], "prism": []}
                for _ in range(a.repeat):
                    cyc, prism, auto = render_both(a, harness, s, work, stem, spp, a.seed, auto)
                    seconds["cycles"].append(float(cyc.get("cycles_pathtrace_s", float("nan"))))
                    seconds["prism"].append(float(image(os.path.join(work, "prism_%s.exr" % stem))[1].get(
                        "prism.seconds", float("nan"))))
                for r in ("cycles", "prism"):
                    img, _ = image(os.path.join(work, "%s_%s.exr" % (r, stem)))
                    rungs[r].append(dict(spp=spp, seconds=statistics.median(seconds[r]), all_seconds=seconds[r],
                                         error=debiased_rel_rmse(img, *refs[r])))
                c, p = rungs["cycles"][-1], rungs["prism"][-1]
                print("  %6d  %10.3f %10.5f  %10.3f %10.5f" % (spp, c["seconds"], c["error"], p["seconds"], p["error"]),
                      flush=True)
            top_c, top_p = rungs["cycles"][-1], rungs["prism"][-1]
            target = top_c["error"]
            t_prism, extrapolated = time_at_error(rungs["prism"], target)
            r = dict(asset=name, size="%dx%d" % (s["width"], s["height"]), rungs=rungs, target=target, repeat=a.repeat,
                     top_spp=top_c["spp"], ref_spp=2 * half, t_cycles=top_c["seconds"], t_prism=t_prism,
                     extrapolated=extrapolated,
                     ratio=t_prism / top_c["seconds"] if top_c["seconds"] > 0 else float("nan"),
                     error_ratio=top_p["error"] / top_c["error"] if top_c["error"] > 0 else float("nan"),
                     sample_time_ratio=top_p["seconds"] / top_c["seconds"] if top_c["seconds"] > 0 else float("nan"),
                     ref_noise=max(ref_noise.values()) / target if target > 0 else float("inf"))
            print("  Cycles reaches %.5f at %d spp in %.2f s; Prism needs %.2f s%s: equal-error time Prism/Cycles "
                  "%.2f; error at %d spp Prism/Cycles %.2f; time per sample Prism/Cycles %.2f"
                  % (target, top_c["spp"], top_c["seconds"], t_prism, " (extrapolated)" if extrapolated else "",
                     r["ratio"], top_c["spp"], r["error_ratio"], r["sample_time_ratio"]))
            with open(os.path.join(work, "equal_error.json"), "w") as f:
                json.dump(r, f)
            results.append(r)
        except Exception as e:  # one asset failing must not hide the others
            print("  FAILED: %s" % e, flush=True)
            failed.append(name)
    # The summary holds every asset measured into --out so far, so a run split by asset still gets one table.
    results = []
    for name in KNOWN:
        path = os.path.join(a.out, name, "equal_error.json")
        if os.path.isfile(path) and name not in failed:
            with open(path) as f:
                results.append(json.load(f))
    if results:
        write_equal_error_summary(a, results, failed)
    return 1 if failed else 0


EQUAL_ERROR_HEADER = ["asset", "size", "reference spp", "Cycles: spp, rel RMSE, s", "Prism s to that error",
                      "equal-error time Prism/Cycles", "rel RMSE at equal spp Prism/Cycles",
                      "time per sample Prism/Cycles", "reference noise / target"]


def write_equal_error_summary(a, results, failed):
    rows = [[r["asset"], r["size"], str(r.get("ref_spp", "?")),
             "%d, %.4f, %.2f%s" % (r["top_spp"], r["target"], r["t_cycles"],
                                   " (median of %d)" % r["repeat"] if r.get("repeat", 1) > 1 else ""),
             "%.2f%s" % (r["t_prism"], " (extrap.)" if r["extrapolated"] else ""), "%.2f" % r["ratio"],
             "%.2f" % r["error_ratio"], "%.2f" % r["sample_time_ratio"],
             "%.2f" % r.get("ref_noise", float("nan"))] for r in results]
    with open(os.path.join(a.out, "equal_error.md"), "w") as f:
        f.write("# Equal-error time, Prism vs Cycles\n\n%s, %d threads each, Prism `--max-depth %d`, references in "
                "two halves with their noise subtracted, ladder %s spp.\n\n"
                % (time.strftime("%Y-%m-%d %H:%M"), a.threads, a.max_depth, ",".join(map(str, a.ladder))))
        f.write("| " + " | ".join(EQUAL_ERROR_HEADER) + " |\n|" + "---|" * len(EQUAL_ERROR_HEADER) + "\n")
        for row in rows:
            f.write("| " + " | ".join(row) + " |\n")
        if failed:
            f.write("\nFailed: %s\n" % ", ".join(failed))
    with open(os.path.join(a.out, "equal_error.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["asset", "renderer", "spp", "seconds", "rel_rmse"])
        for r in results:
            for renderer in ("cycles", "prism"):
                for g in r["rungs"][renderer]:
                    w.writerow([r["asset"], renderer, g["spp"], "%.4f" % g["seconds"], "%.6g" % g["error"]])
    widths = [max(len(x[i]) for x in [EQUAL_ERROR_HEADER] + rows) for i in range(len(EQUAL_ERROR_HEADER))]
    print("\nsummary: %s, %s" % (os.path.join(a.out, "equal_error.md"), os.path.join(a.out, "equal_error.csv")))
    for k, row in enumerate([EQUAL_ERROR_HEADER] + rows):
        print("  ".join(x.ljust(w) for x, w in zip(row, widths)))
        if k == 0:
            print("  ".join("-" * w for w in widths))


# --------------------------------------------------------------------------- main
def main():
    a = parse_args()
    harness = os.path.join(a.shared, "tools", "cycles")
    assets_dir = os.path.join(a.shared, "assets", "gltf")
    if not os.path.isfile(os.path.join(harness, "render_gltf.sh")) or not os.path.isdir(assets_dir):
        skip("%s (the Cycles harness and shared assets) not found" % a.shared)
    if shutil.which(a.blender) is None:
        skip("Blender ('%s') not found; install it as %s/README.md says" % (a.blender, harness))
    try:
        import numpy  # noqa: F401
    except ImportError:
        # Under pyenv or a virtualenv `python3` may not see Debian's python3-numpy: use the system one.
        if os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3") and \
                os.access("/usr/bin/python3", os.X_OK) and not os.environ.get("COMPARE_CYCLES_REEXEC"):
            print("compare_cycles: numpy not importable from %s; re-running with /usr/bin/python3" % sys.executable)
            sys.stdout.flush()
            os.environ["COMPARE_CYCLES_REEXEC"] = "1"
            os.execv("/usr/bin/python3", ["/usr/bin/python3", os.path.abspath(__file__)] + sys.argv[1:])
        skip("python3-numpy is missing (the Cycles harness needs it too)")
    if not os.access(a.prism, os.X_OK):
        print("compare_cycles: error: %s not found; build Prism first (make build)" % a.prism, file=sys.stderr)
        return 1
    sys.path.insert(0, harness)
    sys.dont_write_bytecode = True  # never leave a __pycache__ in the shared assets
    import exrstats

    unknown = [x for x in a.assets if x not in KNOWN]
    if unknown:
        print("compare_cycles: error: unknown asset(s) %s; choose from %s" % (", ".join(unknown), ", ".join(KNOWN)),
              file=sys.stderr)
        return 2
    os.makedirs(a.out, exist_ok=True)
    if a.conventions:
        return check_conventions(a, harness, exrstats)
    if a.equal_error:
        return equal_error(a, harness, exrstats, assets_dir)
    print("Prism vs Cycles (Blender 3.4, %s): %d spp, %d threads each, Prism --max-depth %d = "
          "Cycles --max-bounces %d, Cycles --lighting-mode COMPAT, box filter 1 px, seed %d, linear Rec.709"
          % (harness, a.spp, a.threads, a.max_depth, a.max_depth - 1, a.seed))
    results, failed = [], []
    for name in a.assets:
        work = os.path.join(a.out, name)
        os.makedirs(work, exist_ok=True)
        try:
            s = asset_setup(a, assets_dir, name)
            info, cams, width, height, env = s["info"], s["cams"], s["width"], s["height"], s["env"]
            has_light = s["has_light"]
            print("\n== %s  %dx%d, %s, %s" % (
                name, width, height,
                ("camera %d (node %d)" % (a.camera, cams[a.camera])) if cams else
                "no camera: the harness's auto camera",
                ("lights: %d punctual, %d emissive material(s); no environment" %
                 (len(info["punctual"]), len(info["emissive"]))) if has_light else
                ("no lights%s: --env %s for both" % (" (only textured emission)" if info["emissive_textured"] else "",
                                                     env or "none"))),
                flush=True)

            cyc_exr = os.path.join(work, "cycles.exr")
            prism_exr = os.path.join(work, "prism.exr")
            # Cycles first: for an asset without a camera it prints the camera it framed, which Prism reuses.
            cyc, auto, cyc_notes = run_cycles(a, harness, s["src"], cyc_exr, width, height, a.camera, env)
            prism_in, prism_cam = prism_scene(a, s, auto, work)
            prism, warnings = run_prism(a, prism_in, prism_exr, width, height, prism_cam, env)

            p, ph = load_rgb(exrstats, prism_exr)
            c, _ = load_rgb(exrstats, cyc_exr)
            if p.shape != c.shape:
                raise RuntimeError("image sizes differ: Prism %s, Cycles %s" % (p.shape[:2], c.shape[:2]))
            cmp_ = compare(p, c, env)
            prism["render_s"] = float(ph.get("prism.seconds", float("nan")))
            prism["invalid"] = ph.get("prism.invalidSamples", "?")
            if a.previews:
                write_preview(exrstats, p, c, os.path.join(work, "prism_vs_cycles.png"))

            mp, mc, rel = cmp_["mean_prism"], cmp_["mean_cycles"], cmp_["rel"]
            print("  %-10s %11s %11s %11s %11s" % ("mean", "R", "G", "B", "Y"))
            print("  %-10s %11.5g %11.5g %11.5g %11.5g" % ("Prism", *mp))
            print("  %-10s %11.5g %11.5g %11.5g %11.5g" % ("Cycles", *mc))
            print("  %-10s %11s %11s %11s %11s" % ("rel diff", *[pct(x) for x in rel]))
            if env:
                print("  %-10s %11s %11s %11s %11s  (Y over the %.0f%% of pixels that are not pure background)"
                      % ("foreground", "", "", "", pct(cmp_["fg_rel"]), 100 * cmp_["fg_frac"]))
            print("  rel RMSE   %.1f%% (RGB)  %.1f%% (Y)  %.1f%% (Y, 4x4-pixel blocks)"
                  % (100 * cmp_["rmse_rgb"], 100 * cmp_["rmse_y"], 100 * cmp_["rmse_y4"]))
            print("  seconds    Prism: render %.2f, wall %.2f (load %.2f, BVH %.2f; %.1f CPU-s)"
                  % (prism["render_s"], prism["wall_s"], prism["load_s"], prism["bvh_s"], prism["cpu_s"]))
            print("             Cycles: cycles_render_s %.2f (path trace %.2f, sync+BVH %.2f; %.1f CPU-s), "
                  "total_s %.2f (import %.2f)"
                  % (cyc["cycles_render_s"], cyc.get("cycles_pathtrace_s", float("nan")),
                     cyc.get("cycles_sync_s", float("nan")), cyc.get("cycles_render_cpu_s", float("nan")),
                     cyc["total_s"], cyc.get("import_s", float("nan"))))
            if cmp_["nonfinite_prism"] or cmp_["nonfinite_cycles"] or str(prism["invalid"]) != "0":
                print("  NOTE non-finite pixel values: Prism %d, Cycles %d; Prism invalid samples %s"
                      % (cmp_["nonfinite_prism"], cmp_["nonfinite_cycles"], prism["invalid"]))
            for w in warnings:
                print("  Prism warning: " + w)
            for n in cyc_notes:
                if "auto_camera_gltf" not in n:
                    print("  Cycles harness: " + n)
            results.append(dict(asset=name, width=width, height=height, env=env or "", camera="node %d" % cams[a.camera]
                                if cams else "auto", cmp=cmp_, prism=prism, cycles=cyc, warnings=warnings,
                                cycles_notes=cyc_notes))
        except Exception as e:  # one asset failing must not hide the others
            print("  FAILED: %s" % e, flush=True)
            failed.append(name)
    write_summary(a, results, failed)
    print("\nsummary: %s, %s" % (os.path.join(a.out, "summary.md"), os.path.join(a.out, "summary.csv")))
    print_table(results)
    return 1 if failed else 0


def table_rows(results):
    for r in results:
        c, p, y = r["cmp"], r["prism"], r["cycles"]
        yield [r["asset"], "%dx%d" % (r["width"], r["height"]), pct(c["rel"][3]), pct(c["fg_rel"]),
               " ".join(pct(x) for x in c["rel"][:3]), "%.1f%%" % (100 * c["rmse_rgb"]),
               "%.1f%%" % (100 * c["rmse_y4"]), "%.2f / %.2f" % (p["render_s"], p["wall_s"]),
               "%.2f / %.2f" % (y["cycles_render_s"], y["total_s"]),
               "%.1f / %.1f" % (p["cpu_s"], y.get("cycles_render_cpu_s", float("nan")))]


HEADER = ["asset", "size", "mean Y rel diff", "foreground Y", "mean R G B rel diff", "rel RMSE (RGB)",
          "rel RMSE (Y, 4x4)",
          "Prism s: render / wall", "Cycles s: render / total", "CPU-s: Prism / Cycles"]


def print_table(results):
    rows = [HEADER] + list(table_rows(results))
    widths = [max(len(r[i]) for r in rows) for i in range(len(HEADER))]
    for k, r in enumerate(rows):
        print("  ".join(x.ljust(w) for x, w in zip(r, widths)))
        if k == 0:
            print("  ".join("-" * w for w in widths))


def write_summary(a, results, failed):
    with open(os.path.join(a.out, "summary.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["asset", "width", "height", "spp", "max_depth_prism", "max_bounces_cycles", "threads", "env",
                    "camera", "prism_mean_R", "prism_mean_G", "prism_mean_B", "prism_mean_Y", "cycles_mean_R",
                    "cycles_mean_G", "cycles_mean_B", "cycles_mean_Y", "rel_diff_R", "rel_diff_G", "rel_diff_B",
                    "rel_diff_Y", "foreground_fraction", "foreground_rel_diff_Y", "rel_rmse_rgb", "rel_rmse_Y",
                    "rel_rmse_Y_4x4", "prism_render_s", "prism_wall_s",
                    "prism_load_s", "prism_bvh_s", "prism_cpu_s", "prism_invalid_samples", "cycles_render_s",
                    "cycles_pathtrace_s", "cycles_sync_s", "cycles_render_cpu_s", "cycles_import_s",
                    "cycles_total_s", "cycles_process_wall_s"])
        for r in results:
            c, p, y = r["cmp"], r["prism"], r["cycles"]
            w.writerow([r["asset"], r["width"], r["height"], a.spp, a.max_depth, a.max_depth - 1, a.threads, r["env"],
                        r["camera"], *["%.6g" % x for x in c["mean_prism"] + c["mean_cycles"] + c["rel"]],
                        "%.4g" % c["fg_frac"], "%.5g" % c["fg_rel"],
                        *["%.5g" % c[k] for k in ("rmse_rgb", "rmse_y", "rmse_y4")],
                        *["%.3f" % p[k] for k in ("render_s", "wall_s", "load_s", "bvh_s", "cpu_s")], p["invalid"],
                        *[y.get(k, "") for k in ("cycles_render_s", "cycles_pathtrace_s", "cycles_sync_s",
                                                 "cycles_render_cpu_s", "import_s", "total_s", "process_wall_s")]])
    with open(os.path.join(a.out, "summary.md"), "w") as f:
        f.write("# Prism vs Cycles\n\n%s, %d spp, %d threads each, Prism `--max-depth %d` = Cycles `--max-bounces %d`, "
                "Cycles `--lighting-mode COMPAT`, box filter, seed %d, linear Rec.709. Relative differences are "
                "Prism / Cycles − 1 (\"foreground\": over the pixels that do not see only the constant "
                "environment); RMSE is relative to Cycles' mean. Seconds: Prism's `prism.seconds` (path "
                "tracing) / wall time of the whole process; Cycles' `cycles_render_s` (sync + BVH + path tracing) "
                "/ `total_s` (Blender start to exit). CPU-s (all threads; steadier on a shared machine): the whole "
                "Prism process / Cycles' `cycles_render_cpu_s`.\n\n"
                % (time.strftime("%Y-%m-%d %H:%M"), a.spp, a.threads, a.max_depth, a.max_depth - 1, a.seed))
        f.write("| " + " | ".join(HEADER) + " |\n|" + "---|" * len(HEADER) + "\n")
        for row in table_rows(results):
            f.write("| " + " | ".join(row) + " |\n")
        if failed:
            f.write("\nFailed: %s\n" % ", ".join(failed))
        for r in results:
            if r["warnings"] or r["cycles_notes"]:
                f.write("\n**%s**: camera %s%s\n\n" % (r["asset"], r["camera"],
                                                       ", env " + r["env"] if r["env"] else ""))
                for w in r["warnings"]:
                    f.write("- Prism: %s\n" % w)
                for n in r["cycles_notes"]:
                    f.write("- Cycles harness: %s\n" % n)


if __name__ == "__main__":
    sys.exit(main())
