"""What the small Prism-against-Cycles tools share (lamp_pane.py, layering_cycles.py): their
common options, finding the Cycles harness of ../shared/tools/cycles, and rendering one glTF
with both renderers."""

import os
import shutil
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def add_common_args(ap, tool):
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", default=os.path.join(REPO, "out", tool))
    ap.add_argument("--shared", default=os.path.join(os.path.dirname(REPO), "shared"))
    ap.add_argument("--prism", default=os.path.join(REPO, "build", "apps", "prism"))


def harness(tool, shared):
    """The harness folder, with its exrstats module importable; None (saying why) if the tool skips."""
    path = os.path.join(shared, "tools", "cycles")
    if not os.path.isfile(os.path.join(path, "render_gltf.sh")):
        print("%s: SKIPPED: %s (the Cycles harness) not found" % (tool, path))
        return None
    if shutil.which("blender") is None:
        print("%s: SKIPPED: Blender not found" % tool)
        return None
    sys.path.insert(0, path)
    sys.dont_write_bytecode = True
    return path


def render_pair(tool, a, gltf, prism_args, cycles_args):
    """Renders gltf to prism.exr and cycles.exr beside it (a: the common options); their paths."""
    work = os.path.dirname(gltf)
    prism_exr, cycles_exr = os.path.join(work, "prism.exr"), os.path.join(work, "cycles.exr")
    subprocess.run([a.prism, "render", gltf, "-o", prism_exr, "-q", "--threads", str(a.threads)] + prism_args,
                   check=True, stdout=subprocess.DEVNULL)
    r = subprocess.run([os.path.join(a.harness, "render_gltf.sh"), "--in", gltf, "--out", cycles_exr,
                        "--threads", str(a.threads)] + cycles_args,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.exit("%s: Cycles failed; log: %s.log" % (tool, cycles_exr))
    return prism_exr, cycles_exr
