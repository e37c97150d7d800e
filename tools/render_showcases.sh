#!/bin/sh
# Renders the pictures of the README and the docs (docs/showcases/NAME.png) and writes
# docs/showcases/README.md beside them: each picture's command, render time, machine and measured
# error. The error is measured, not estimated: each scene is rendered a second time with another
# seed, and `prism compare --independent` gives either image's relative RMSE as displayed (clipped
# and sRGB-encoded, the noise a viewer sees) and in linear values. The sample counts were chosen to
# bring the displayed error to about 2%.
#
#   tools/render_showcases.sh [BUILD_DIR]      (default: build; run it on an otherwise idle machine)
#
# It takes about 40 minutes on 2 cores. The EXR images are kept in a temporary folder only.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
prism=$build/apps/prism
out=$root/docs/showcases
[ -x "$prism" ] || { echo "render_showcases: no $prism (build first: make build)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
rows=$work/rows.md

# showcase NAME CAPTION SCENE OPTIONS...: renders data/scenes/SCENE.gltf with the options, twice.
showcase() {
  name=$1 caption=$2 scene=data/scenes/$3.gltf
  shift 3
  echo "$name: prism render $scene $*" >&2
  start=$(date +%s.%N)
  (cd "$root" && "$prism" render "$scene" "$@" --seed 1 -q -o "$work/$name.1.exr" --preview "$out/$name.png") >/dev/null
  seconds=$(echo "$(date +%s.%N) - $start" | bc)
  (cd "$root" && "$prism" render "$scene" "$@" --seed 2 -q -o "$work/$name.2.exr") >/dev/null
  errors=$("$prism" compare --independent "$work/$name.1.exr" "$work/$name.2.exr" | tail -n 1)
  display=$(echo "$errors" | sed -E 's/.*display_relative_rmse=([^ ]+).*/\1/')
  linear=$(echo "$errors" | sed -E 's/.* relative_rmse=([^ ]+).*/\1/')
  printf '| ![%s](%s.png) | %s | `prism render %s %s` | %.0f s | %.2f%% | %.3g |\n' "$caption" "$name" "$caption" \
    "$scene" "$*" "$seconds" "$(echo "100 * $display" | bc -l)" "$linear" >>"$rows"
}

showcase default "The default scene: a Cornell box with copper and gold spheres and a dispersive flint prism" \
  cornell --width 384 --height 384 --spp 576
showcase brushed "Brushed aluminium: a lathe-turned disk and a sphere brushed along its latitudes" \
  brushed --width 480 --spp 384
showcase carpaint "A red metallic paint without (left) and under (right) a clear coat" \
  carpaint --width 480 --spp 512
showcase iridescence "Soap bubbles 250 to 850 nm thick, and an oil film on water" \
  iridescence --width 480 --spp 160
showcase glass_of_water "A glass of water throwing its caustic on the table" \
  glass_of_water --width 384 --spp 192
showcase prism_rainbow "Newton's experiment: white light through a slit and a flint prism" \
  prism_rainbow --width 384 --spp 384
showcase dispersion "A dispersive prism and the spectrum it casts" \
  dispersion --width 384 --spp 448
showcase diamond "A brilliant-cut diamond (the path tracer: its error is the sparkles)" \
  diamond --width 384 --spp 896 --integrator path

cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
commit=$(cd "$root" && git rev-parse --short HEAD 2>/dev/null || echo unknown)
{
  echo "# Showcase pictures"
  echo
  echo "Written by \`tools/render_showcases.sh\` on $(date -u +%Y-%m-%d), Prism $commit, $(nproc) threads of"
  echo "$cpu. Each picture is the sRGB preview of the render; *seconds* is that render's wall time."
  echo "The error is measured from a second render with another seed (\`prism compare --independent\`):"
  echo "the relative RMSE of the picture as displayed (clipped to [0, 1], sRGB-encoded), and of its"
  echo "linear values (dominated by the few brightest pixels: highlights, sparkles, the lights)."
  echo "The integrator is the default (\`--integrator auto\`) unless the command names one."
  echo
  echo "| picture | what it shows | command | seconds | error as displayed | linear relative error |"
  echo "|---|---|---|---|---|---|"
  cat "$rows"
} >"$out/README.md"
echo "wrote $out/README.md" >&2
