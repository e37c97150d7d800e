#!/usr/bin/env python3
"""Refresh tables of docs/performance.md by running their benchmarks.

    tools/update_performance.py NAME [NAME ...] [--prism build/apps/prism] [--dry-run]

Each NAME runs one benchmark with the command docs/performance.md documents, parses what the
command prints or writes, and replaces the text between `<!-- begin MARKER -->` and
`<!-- end MARKER -->` in docs/performance.md with a line saying when, at which commit and on which
CPU it was measured, and the fresh table. A benchmark whose command fails, or whose output cannot be
parsed, stops the script with a message; the tables of benchmarks that finished before it are kept.
The markers are checked before anything runs.

  NAME          markers               what runs (roughly how long on 2 cores)
  cycles        cycles                tools/compare_cycles.py --equal-error on eight shared assets and the hall of lamps
                                      (about an hour with fresh references; Blender 3.4, numpy and
                                      the shared assets, PRISM_SHARED_DIR)
  rays          rays                  tools/bench_rays.sh, one scene per run, ROUNDS=3 REPEAT=3
                                      (10 minutes; raybench built in the shared assets)
  rays-avx2     rays-avx2             the same with --avx2-prism and Embree's AVX2 kernels
  callgrind     callgrind             instructions per sample of lobes_plain and lobes_all under
                                      valgrind's callgrind, --avx2-prism (a few minutes; valgrind)
  lobes         lobes                 prism bench features on lobes_plain and lobes_all, five
                                      alternations (2 minutes)
  default       default               prism render of the default and the dispersion scene,
                                      512x512, 64 spp (2 minutes)
  integrators   integrators-SCENE     path, bdpt and vcm at equal time with prism converge on
                                      --scenes (all five: about 40 minutes)
  convergence   convergence-SCENE     prism converge's doubling budgets on cornell and dispersion
                                      (10 minutes)
  features      features              prism bench features on three scenes (1 minute)
  instances     instances             prism bench instances, three runs (10 seconds)
  farm          farm                  tools/slurm/bench_farm.sh PRISM 512 80 (2 minutes; root)

The renders are timed: run it on an otherwise idle machine. Scratch files go to --out
(default out/performance/, which git ignores).
"""
import argparse
import csv
import datetime
import json
import math
import os
import pathlib
import platform
import re
import shlex
import statistics
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
SCENES = ROOT / "data" / "scenes"


class Failure(Exception):
    pass


# --------------------------------------------------------------------------- running and recording
def run(cmd, env=None):
    """Runs cmd in the project's root; its CompletedProcess (stdout, stderr as text). Fails on a
    non-zero exit code, with the end of what it printed."""
    cmd = [str(c) for c in cmd]
    print("$ " + shlex.join(cmd), file=sys.stderr, flush=True)
    try:
        r = subprocess.run(cmd, cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    except OSError as e:
        raise Failure("cannot run %s: %s" % (cmd[0], e))
    if r.returncode != 0:
        tail = "\n".join((r.stdout + r.stderr).strip().splitlines()[-20:])
        raise Failure("%s exited with code %d:\n%s" % (cmd[0], r.returncode, tail))
    return r


def search(pattern, text, what):
    """The match of pattern in text (multi-line), or a failure naming what was looked for."""
    m = re.search(pattern, text, re.M)
    if not m:
        raise Failure("could not parse %s: no line matches /%s/ in:\n%s"
                      % (what, pattern, "\n".join(text.strip().splitlines()[-20:])))
    return m


def cpu():
    """The CPU model from /proc/cpuinfo, its logical CPUs and its widest vector instructions."""
    model, flags = None, ""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name") and model is None:
                    model = line.split(":", 1)[1].strip()
                elif line.startswith("flags") and not flags:
                    flags = " " + line.split(":", 1)[1].strip() + " "
    except OSError:
        pass
    details = ["%d logical CPUs" % (os.cpu_count() or 1)]
    if " avx512f " in flags:
        details.append("AVX-512")
    elif " avx2 " in flags:
        details.append("AVX2")
    return "%s (%s)" % (model or platform.processor() or "an unknown CPU", ", ".join(details))


def commit():
    try:
        head = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(ROOT), "diff", "--quiet", "HEAD", "--"]).returncode != 0
        return head + (" with local changes" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "an unknown commit"


def measured(name, detail=""):
    return "Measured %s at %s on %s by `tools/update_performance.py %s`%s." % (
        datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d"), commit(), cpu(), name, detail)


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return "\n".join(lines + ["| " + " | ".join(row) + " |" for row in rows])


def minus(text):
    return text.replace("-", "−")


def need_executable(path, how):
    if not os.access(path, os.X_OK):
        raise Failure("%s not found; %s" % (path, how))
    return path


def markers_of(text, marker, doc):
    begin, end = "<!-- begin %s -->" % marker, "<!-- end %s -->" % marker
    if text.count(begin) != 1 or text.count(end) != 1 or text.index(end) < text.index(begin):
        raise Failure("%s needs exactly one '%s' followed by one '%s'" % (doc, begin, end))
    return begin, end


def replace_block(doc, marker, block, dry_run):
    text = doc.read_text()
    begin, end = markers_of(text, marker, doc)
    i, j = text.index(begin) + len(begin), text.index(end)
    text = text[:i] + "\n\n" + block.strip("\n") + "\n\n" + text[j:]
    if dry_run:
        print("%s\n%s\n%s\n" % (begin, block.strip("\n"), end))
        return
    tmp = doc.with_name(doc.name + ".tmp")
    tmp.write_text(text)
    tmp.replace(doc)
    print("updated %s: %s" % (doc, marker), file=sys.stderr)


# --------------------------------------------------------------------------- equal error against Cycles
CYCLES_ASSETS = ["Box", "MetalRoughSpheresNoTextures", "AttenuationTest", "TransmissionTest", "TransmissionRoughnessTest",
                 "GlassVaseFlowers", "EmissiveStrengthTest", "LightsPunctualLamp", "lamp_hall"]
CYCLES_ARGS = ["--equal-error", "--repeat", "3", "--width", "160", "--max-depth", "12", "--env", "0.5,0.5,0.5"]


def bench_cycles(a):
    out = a.out / "cycles"
    for asset in CYCLES_ASSETS:  # no result of an earlier run may stand in for this one's
        (out / asset / "equal_error.json").unlink(missing_ok=True)
    cmd = [ROOT / "tools" / "compare_cycles.py"] + CYCLES_ARGS + [
        "--assets", ",".join(CYCLES_ASSETS), "--out", out, "--prism", a.prism]
    r = run(cmd + (["--reuse-references"] if a.reuse_references else []))
    if "SKIPPED" in r.stdout:
        raise Failure("compare_cycles.py skipped: " + r.stdout.strip().splitlines()[-1])
    rows, top = [], set()
    for asset in CYCLES_ASSETS:
        path = out / asset / "equal_error.json"
        try:
            with open(path) as f:
                j = json.load(f)
            rows.append([asset, j["size"].replace("x", "×"), str(j["ref_spp"]),
                         "%.2f%s" % (j["ratio"], " (extrapolated)" if j["extrapolated"] else ""),
                         "%.2f" % j["error_ratio"], "%.2f" % j["sample_time_ratio"]])
            top.add(j["top_spp"])
        except (OSError, ValueError, KeyError) as e:
            raise Failure("could not read compare_cycles.py's result %s: %s" % (path, e))
    detail = " (`%s`; ratios at the top rung, %s spp)" % (
        " ".join(["tools/compare_cycles.py"] + CYCLES_ARGS), ", ".join(map(str, sorted(top))))
    return {"cycles": measured("cycles", detail) + "\n\n" + table(
        ["asset", "size", "reference spp", "equal-error time Prism/Cycles", "error at equal spp Prism/Cycles",
         "time per sample Prism/Cycles"], rows)}


# --------------------------------------------------------------------------- rays against Embree
RAY_SCENES = ["TransmissionTest", "MetalRoughSpheresNoTextures", "procedural"]


def bench_rays(a, avx2):
    prism = a.avx2_prism if avx2 else a.prism
    need_executable(prism, "build it first (%s)" % ("an x86-64-v3 build: cmake -S . -B build-avx2 "
                                                    "-DCMAKE_BUILD_TYPE=Release -DPRISM_ARCH=x86-64-v3"
                                                    if avx2 else "make build"))
    env = dict(os.environ, PRISM=str(prism))
    env.setdefault("ROUNDS", "3")
    env.setdefault("REPEAT", "3")
    if avx2:
        env["EMBREE_CONFIG"] = "isa=avx2"
    header, rows = None, []
    for scene in RAY_SCENES:  # one scene per run, as the documented tables were made
        env["SCENES"] = scene
        r = run([ROOT / "tools" / "bench_rays.sh"], env)
        lines = [l for l in r.stdout.splitlines() if l.startswith("|")]
        if len(lines) < 3 or any(l.count("|") != 12 for l in lines):
            raise Failure("could not parse tools/bench_rays.sh's table for %s:\n%s"
                          % (scene, (r.stdout + r.stderr).strip()))
        header, rows = lines[:2], rows + lines[2:]
    detail = " (Prism %s, Embree %s; ROUNDS=%s REPEAT=%s, one scene per run)" % (
        "-DPRISM_ARCH=x86-64-v3" if avx2 else "-march=native", "isa=avx2" if avx2 else "its own choice of kernels",
        env["ROUNDS"], env["REPEAT"])
    name = "rays-avx2" if avx2 else "rays"
    return {name: measured(name, detail) + "\n\n" + "\n".join(header + rows)}


# --------------------------------------------------------------------------- instructions per sample
def instructions(prism, scene, spp, tmp):
    r = run(["valgrind", "--tool=callgrind", "--callgrind-out-file=%s/callgrind.out" % tmp, prism, "render", scene,
             "--integrator", "path", "--spp", str(spp), "--width", "48", "--height", "36", "--threads", "1", "-q",
             "-o", "%s/image.exr" % tmp])
    return int(search(r"Collected\s*:\s*(\d+)", r.stderr, "callgrind's instruction count").group(1))


def bench_callgrind(a):
    need_executable(a.avx2_prism, "an x86-64-v3 build: cmake -S . -B build-avx2 -DCMAKE_BUILD_TYPE=Release "
                                  "-DPRISM_ARCH=x86-64-v3")
    per_spp = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name in ("lobes_plain", "lobes_all"):
            scene = SCENES / (name + ".gltf")
            per_spp[name] = (instructions(a.avx2_prism, scene, 6, tmp) - instructions(a.avx2_prism, scene, 2, tmp)) / 4
    version = run(["valgrind", "--version"]).stdout.strip()
    rows = [[n, "48×36", "%.2f M" % (per_spp[n] / 1e6)] for n in ("lobes_plain", "lobes_all")]
    rows.append(["lobes_all / lobes_plain", "", "%.3f×" % (per_spp["lobes_all"] / per_spp["lobes_plain"])])
    return {"callgrind": measured("callgrind", " (%s, x86-64-v3 build, (6 − 2)/4 spp, one thread)" % version) +
            "\n\n" + table(["scene", "size", "instructions per sample"], rows)}


# --------------------------------------------------------------------------- samples per second
def features_line(prism, scene, options):
    r = run([prism, "bench", "features", scene] + options)
    m = search(r"^features needed_sps=(\S+) media_sps=(\S+) dispersion_sps=(\S+) full_sps=(\S+)", r.stdout,
               "prism bench features' summary line")
    n = search(r"as the scene needs \(media (on|off), dispersion (on|off)\)", r.stdout, "prism bench features' table")
    return [float(x) for x in m.groups()], (n.group(1) == "on", n.group(2) == "on")


def bench_lobes(a):
    sps = {"lobes_plain": [], "lobes_all": []}
    for _ in range(5):  # the two scenes alternated, so that the machine's load meets both alike
        for name in sps:
            sps[name].append(features_line(a.prism, SCENES / (name + ".gltf"), ["--width", "160"])[0][0])
    median = {name: statistics.median(v) for name, v in sps.items()}
    rows = [[name, "%.3g M" % (median[name] / 1e6), "%.3g–%.3g M" % (min(sps[name]) / 1e6, max(sps[name]) / 1e6),
             "%.2f×" % (median["lobes_plain"] / median[name])] for name in sps]
    return {"lobes": measured("lobes", " (`prism bench features data/scenes/NAME.gltf --width 160`, best of 3 "
                                       "16-spp renders, five alternations)") + "\n\n" +
            table(["scene", "samples/s, median", "range", "time per sample × lobes_plain"], rows)}


FEATURE_SCENES = [("stress/room.gltf", "Lambert room, area light"),
                  ("cornell.gltf", "volumes, dispersion, metals"),
                  ("dispersion.gltf", "volumes, dispersion")]


def bench_features(a):
    rows = []
    for path, what in FEATURE_SCENES:
        (needed, media, dispersion, full), (has_media, has_dispersion) = features_line(
            a.prism, SCENES / path, ["--width", "256", "--height", "256", "--spp", "16"])
        cost = lambda sps, on: "(needed)" if on else minus("%+.1f%%" % (100 * (needed / sps - 1)))
        rows.append(["`data/scenes/%s` (%s)" % (path, what), "%.4g M" % (needed / 1e6), cost(media, has_media),
                     cost(dispersion, has_dispersion), cost(full, has_media and has_dispersion)])
    return {"features": measured("features", " (`prism bench features SCENE --width 256 --height 256 --spp 16`)") +
            "\n\n" + table(["scene (its features)", "as needed: samples/s", "+ medium stack", "+ dispersion check",
                            "+ both"], rows)}


def stats_line(stderr):
    m = search(r"(\d+) samples in ([0-9.]+) s \(([0-9.e+]+) samples/s\)", stderr, "prism render's statistics")
    return float(m.group(2)), float(m.group(3))


def bench_default(a):
    cases = [("cornell.gltf", "path", 1), ("cornell.gltf", "path", 2), ("cornell.gltf", "whitted", 2),
             ("dispersion.gltf", "path", 2)]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene, integrator, threads in cases:
            r = run([a.prism, "render", SCENES / scene, "-o", "%s/image.exr" % tmp, "--integrator", integrator,
                     "--width", "512", "--height", "512", "--spp", "64", "--threads", str(threads)])
            seconds, sps = stats_line(r.stderr)
            rows.append(["`%s --integrator %s`" % (scene, integrator), str(threads), "%.1f s" % seconds,
                         "%.3g M" % (sps / 1e6)])
    return {"default": measured("default", " (`prism render data/scenes/SCENE --width 512 --height 512 --spp 64`)") +
            "\n\n" + table(["scene and integrator", "threads", "seconds", "samples/s"], rows)}


# --------------------------------------------------------------------------- integrators at equal time
EQUAL_TIME = {  # scene: (image side, seconds per integrator, reference integrator, reference seconds)
    "cornell": (128, 30, "bdpt", 150),
    "glass_of_water": (128, 30, "vcm", 90),
    "dispersion": (256, 60, "vcm", 300),
    "prism_rainbow": (128, 30, "vcm", 150),
    "diamond": (128, 30, "vcm", 150),
}


def read_equal_time(folder):
    path = folder / "equal_time.csv"
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        return {r["configuration"]: {k: float(v) for k, v in r.items() if k != "configuration"} for r in rows}
    except (OSError, KeyError, ValueError) as e:
        raise Failure("could not read prism converge's %s: %s" % (path, e))


def times(x):
    return "%.2f×" % x if x >= 0.1 else "%.2g×" % x


def bench_integrators(a):
    blocks = {}
    for name in a.scenes:
        side, seconds, ref_integrator, ref_seconds = EQUAL_TIME[name]
        scene, work = SCENES / (name + ".gltf"), a.out / "integrators" / name
        work.mkdir(parents=True, exist_ok=True)
        reference = work / "reference.exr"
        common = ["--width", str(side), "--height", str(side), "--threads", "2"]
        run([a.prism, "render", scene, "-o", reference, "--integrator", ref_integrator, "--spp", "1000000",
             "--time-limit", str(ref_seconds), "--seed", "777", "-q"] + common)
        # The reference's own error: a second one (seed 778) measured against it holds both's noise.
        run([a.prism, "converge", scene, "--reference", reference, "--out", work / "reference_noise", "--integrators",
             ref_integrator, "--seconds", str(ref_seconds), "--seed", "778"] + common)
        noise = read_equal_time(work / "reference_noise")
        if ref_integrator not in noise:
            raise Failure("prism converge wrote no row for %s in %s" % (ref_integrator, work / "reference_noise"))
        ref_error = noise[ref_integrator]["relative_rmse"] / math.sqrt(2)
        run([a.prism, "converge", scene, "--reference", reference, "--out", work / "equal_time", "--integrators",
             "path,bdpt,vcm", "--seconds", str(seconds)] + common)
        result = read_equal_time(work / "equal_time")
        summary = (work / "equal_time" / "summary.md").read_text()
        mean = search(r"\(mean ([0-9.e+-]+)\)", summary, "the reference's mean in prism converge's summary.md")
        pick = search(r"Use \*\*(\w+)\*\*", summary, "prism converge's choice in its summary.md")
        if any(k not in result for k in ("path", "bdpt", "vcm")):
            raise Failure("prism converge's %s lacks path, bdpt or vcm" % (work / "equal_time" / "equal_time.csv"))
        corrected = {k: math.sqrt(max(v["relative_rmse"] ** 2 - ref_error ** 2, 0.0)) for k, v in result.items()}
        rows = []
        for k in ("path", "bdpt", "vcm"):
            v, ratio = result[k], corrected[k] / corrected["path"] if corrected["path"] > 0 else float("nan")
            rows.append([k, "%.1f" % v["seconds"], "%.0f" % v["spp"], "%.4f" % v["relative_rmse"],
                         "%.4f" % corrected[k], "%.3f" % ratio, times(ratio ** 2), minus("%+.5f" % v["mean_error"])])
        detail = (" (%d×%d, 2 threads, %d s each; reference `%s` for %d s, seed 777, mean %s, its own relative RMSE "
                  "%.4f). `prism converge` picks **%s**" % (side, side, seconds, ref_integrator, ref_seconds,
                                                            mean.group(1), ref_error, pick.group(1)))
        blocks["integrators-" + name] = measured("integrators --scenes " + name, detail) + "\n\n" + table(
            ["integrator", "seconds", "samples per pixel", "relative RMSE", "less the reference's error", "× path",
             "equal-error time × path", "mean error"], rows)
    return blocks


def bench_convergence(a):
    blocks = {}
    for name in ("cornell", "dispersion"):
        work = a.out / "convergence" / name
        work.mkdir(parents=True, exist_ok=True)
        reference = work / "reference.exr"
        if not a.reuse_references:
            reference.unlink(missing_ok=True)  # prism converge renders it again at --reference-spp
        run([a.prism, "converge", SCENES / (name + ".gltf"), "--reference", reference, "--out", work, "--width", "128",
             "--height", "128", "--threads", "2", "--max-spp", "256", "--reference-spp", "4096"])
        summary = (work / "summary.md").read_text()
        stated = search(r"Stated error: RMSE ([0-9.e+-]+)", summary, "prism converge's stated error")
        mean = search(r"\(mean ([0-9.e+-]+)\)", summary, "the reference's mean in prism converge's summary.md")
        lines = [l for l in summary.splitlines() if l.startswith("|")]
        if len(lines) < 3:
            raise Failure("could not parse the table of %s" % (work / "summary.md"))
        detail = (" (128×128, 2 threads, budgets 1 to 256 spp, reference 4096 spp with the baseline, mean %s; "
                  "the stated error is the baseline's RMSE at 256 spp, %s)" % (mean.group(1), stated.group(1)))
        blocks["convergence-" + name] = measured("convergence", detail) + "\n\n" + "\n".join(lines)
    return blocks


# --------------------------------------------------------------------------- memory, farm
def bench_instances(a):
    runs = []
    for _ in range(3):
        r = run([a.prism, "bench", "instances", "--threads", "2"])
        m = search(r"^instances count=(\d+) triangles=(\d+) build_s=(\S+) instances_mb=(\S+) accel_mb=(\S+) "
                   r"rss_before_mb=(\S+) rss_after_mb=(\S+) peak_mb=(\S+)", r.stdout, "prism bench instances' line")
        runs.append([float(x) for x in m.groups()])
    count, triangles, _, instances_mb, accel_mb, before, after, peak = runs[-1]
    build = [r[2] for r in runs]
    row = ["%d × %d" % (count, triangles), "%.2f–%.2f s" % (min(build), max(build)), "%.0f MB" % instances_mb,
           "%.0f MB" % accel_mb, "%.0f / %.0f MB" % (before, after), "%.0f MB" % peak]
    return {"instances": measured("instances", " (`prism bench instances --threads 2`, three runs; memory of the "
                                               "last)") + "\n\n" +
            table(["instances × triangles", "World build", "instances", "accel", "resident before / after the build",
                   "peak resident"], [row])}


def bench_farm(a):
    if os.geteuid() != 0:
        raise Failure("farm: tools/slurm/bench_farm.sh needs root (it starts a local Slurm cluster)")
    r = run([ROOT / "tools" / "slurm" / "bench_farm.sh", a.prism, "512", "80"])
    single = search(r"single render \(all cores\):\s*([0-9.]+) s wall, ([0-9.]+) s CPU", r.stdout, "the single render")
    farm = search(r"4-part Slurm render \(submit to merged image\):\s*([0-9.]+) s wall", r.stdout, "the farm render")
    parts = search(r"4 parts, one after another:\s*([0-9.]+) s CPU in total", r.stdout, "the parts' CPU seconds")
    sw, sc, fw, pc = (float(x) for x in (single.group(1), single.group(2), farm.group(1), parts.group(1)))
    rows = [["single render (all cores)", "%.1f" % sw, "%.1f" % sc],
            ["4-part `prism farm slurm` render, submission to merged image", "%.1f" % fw, ""],
            ["the 4 parts one after another, one thread each", "", "%.1f" % pc],
            ["ratio", "%.2f×" % (fw / sw), "%.2f×" % (pc / sc)]]
    return {"farm": measured("farm", " (`tools/slurm/bench_farm.sh build/apps/prism 512 80`: cornell.gltf, "
                                     "512 wide, 80 spp, seed 1)") + "\n\n" + table(["", "wall s", "CPU s"], rows)}


# --------------------------------------------------------------------------- main
BENCHMARKS = {
    "cycles": (bench_cycles, lambda a: ["cycles"]),
    "rays": (lambda a: bench_rays(a, False), lambda a: ["rays"]),
    "rays-avx2": (lambda a: bench_rays(a, True), lambda a: ["rays-avx2"]),
    "callgrind": (bench_callgrind, lambda a: ["callgrind"]),
    "lobes": (bench_lobes, lambda a: ["lobes"]),
    "default": (bench_default, lambda a: ["default"]),
    "integrators": (bench_integrators, lambda a: ["integrators-" + s for s in a.scenes]),
    "convergence": (bench_convergence, lambda a: ["convergence-cornell", "convergence-dispersion"]),
    "features": (bench_features, lambda a: ["features"]),
    "instances": (bench_instances, lambda a: ["instances"]),
    "farm": (bench_farm, lambda a: ["farm"]),
}
NEEDS_PRISM = {"cycles", "rays", "lobes", "default", "integrators", "convergence", "features", "instances", "farm"}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("names", nargs="+", metavar="NAME", choices=sorted(BENCHMARKS), help="benchmarks to run")
    ap.add_argument("--prism", type=pathlib.Path, default=ROOT / "build" / "apps" / "prism",
                    help="the Prism executable (default build/apps/prism)")
    ap.add_argument("--avx2-prism", type=pathlib.Path, default=ROOT / "build-avx2" / "apps" / "prism",
                    help="an x86-64-v3 build, for rays-avx2 and callgrind (default build-avx2/apps/prism)")
    ap.add_argument("--scenes", default=",".join(EQUAL_TIME),
                    help="integrators: the scenes, comma-separated (default: %(default)s)")
    ap.add_argument("--reuse-references", action="store_true",
                    help="cycles, convergence: keep the references an earlier run left in --out")
    ap.add_argument("--out", type=pathlib.Path, default=ROOT / "out" / "performance",
                    help="scratch folder (default out/performance)")
    ap.add_argument("--doc", type=pathlib.Path, default=ROOT / "docs" / "performance.md")
    ap.add_argument("--dry-run", action="store_true", help="print the new blocks instead of writing them")
    a = ap.parse_args()
    a.scenes = [s for s in (x.strip() for x in a.scenes.split(",")) if s]
    unknown = [s for s in a.scenes if s not in EQUAL_TIME]
    if unknown:
        ap.error("--scenes: unknown %s; choose from %s" % (", ".join(unknown), ", ".join(EQUAL_TIME)))
    a.prism, a.avx2_prism, a.out = a.prism.absolute(), a.avx2_prism.absolute(), a.out.absolute()
    try:
        text = a.doc.read_text()
        for name in a.names:  # every marker first: a long benchmark must not run for a table that has no place
            for marker in BENCHMARKS[name][1](a):
                markers_of(text, marker, a.doc)
        if NEEDS_PRISM & set(a.names):
            need_executable(a.prism, "build it first (make build) or name it with --prism")
        a.out.mkdir(parents=True, exist_ok=True)
        for name in a.names:
            for marker, block in BENCHMARKS[name][0](a).items():
                replace_block(a.doc, marker, block, a.dry_run)
    except (Failure, OSError) as e:
        print("update_performance: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
