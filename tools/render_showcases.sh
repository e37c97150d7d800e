#!/bin/sh
# Renders the pictures of the README and the docs (docs/showcases/NAME.png), writes each one's
# command, render time, machine and measured error beside it (docs/showcases/NAME.txt), and
# gathers those into docs/showcases/README.md. The error is measured, not estimated: each scene is
# rendered a second time with another seed, and `prism compare --independent` gives either image's
# relative RMSE as displayed (clipped and sRGB-encoded, the noise a viewer sees) and in linear
# values. The sample counts were chosen to bring the displayed error to about 2% (the diamond's
# sparkles settle slowest: about 6%).
#
#   tools/render_showcases.sh [--build DIR] [NAME ...]   (default: build/, every picture)
#
# Run it on an otherwise idle machine: the times it writes are wall times. All the pictures take
# about 50 minutes on 2 cores. The EXR images are kept in a temporary folder only.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build
if [ "${1:-}" = "--build" ]; then
  build=$2
  shift 2
fi
prism=$build/apps/prism
out=$root/docs/showcases
[ -x "$prism" ] || { echo "render_showcases: no $prism (build first: make build)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)

# The pictures: NAME | caption | scene | options (the integrator is auto's unless named).
list() {
  cat <<'EOF'
default|The default scene: a Cornell box with copper and gold spheres and a dispersive flint prism|cornell|--width 320 --height 320 --spp 896
brushed|Brushed aluminium: a lathe-turned disk and a sphere brushed along its latitudes|brushed|--width 480 --spp 384
carpaint|A red metallic paint without (left) and under (right) a clear coat|carpaint|--width 480 --spp 512
iridescence|Soap bubbles 250 to 850 nm thick, and an oil film on water|iridescence|--width 480 --spp 224
glass_of_water|A glass of water throwing its caustic on the table|glass_of_water|--width 384 --spp 288
prism_rainbow|Newton's experiment: white light through a slit and a flint prism|prism_rainbow|--width 384 --spp 512
dispersion|A dispersive prism and the spectrum it casts|dispersion|--width 384 --spp 800
diamond|A brilliant-cut diamond on a dark floor under one small light: its fire|diamond|--width 384 --spp 1536
lamp_hall|A hall lit by 1,152 small lamps of six colours, its light sampled by a light tree|lamp_hall|--width 480 --spp 160
screen_room|A dark room lit only by a screen showing a city at night, sampled by its texels|screen_room|--width 480 --spp 512
depth_of_field|Seven measured metals in a row, the gold one in focus at f/1.4 through six blades|depth_of_field|--width 480 --spp 1024
metamerism_d65|Two paints under D65: they match|metamerism|--width 320 --spp 128 --env 1,1,1 --env-spectrum D65 --white-balance D65
metamerism_a|The same two paints under illuminant A: they part|metamerism|--width 320 --spp 128 --env 1,1,1 --env-spectrum A --white-balance A
metamerism_f11|The same two paints under F11: they part|metamerism|--width 320 --spp 128 --env 1,1,1 --env-spectrum F11 --white-balance F11
EOF
}

# render NAME CAPTION SCENE OPTIONS: renders data/scenes/SCENE.gltf with the options, twice.
render() {
  name=$1 caption=$2 scene=data/scenes/$3.gltf options=$4
  echo "$name: prism render $scene $options" >&2
  start=$(date +%s.%N)
  # shellcheck disable=SC2086  # the options are words
  (cd "$root" && "$prism" render "$scene" $options --seed 1 -q -o "$work/$name.1.exr" --preview "$out/$name.png") >/dev/null
  seconds=$(echo "$(date +%s.%N) - $start" | bc)
  # shellcheck disable=SC2086
  (cd "$root" && "$prism" render "$scene" $options --seed 2 -q -o "$work/$name.2.exr") >/dev/null
  errors=$("$prism" compare --independent "$work/$name.1.exr" "$work/$name.2.exr" | tail -n 1)
  display=$(echo "$errors" | sed -E 's/.*display_relative_rmse=([^ ]+).*/\1/')
  linear=$(echo "$errors" | sed -E 's/.* relative_rmse=([^ ]+).*/\1/')
  printf '| ![%s](%s.png) | %s | `prism render %s %s` | %.0f s | %.2f%% | %.3g | %s, %s threads, %s |\n' "$caption" \
    "$name" "$caption" "$scene" "$options" "$seconds" "$(echo "100 * $display" | bc -l)" "$linear" \
    "$(date -u +%Y-%m-%d)" "$(nproc)" "$cpu" >"$out/$name.txt"
}

list | while IFS='|' read -r name caption scene options; do
  if [ $# -eq 0 ] || echo " $* " | grep -q " $name "; then
    render "$name" "$caption" "$scene" "$options"
  fi
done

{
  echo "# Showcase pictures"
  echo
  echo "Written by \`tools/render_showcases.sh\`. Each picture is the sRGB preview of the render, and *seconds* that"
  echo "render's wall time. The error is measured from a second render with another seed"
  echo "(\`prism compare --independent\`): the relative RMSE of the picture as displayed (clipped to [0, 1],"
  echo "sRGB-encoded), and of its linear values (dominated by the few brightest pixels: highlights, sparkles,"
  echo "the lights). The integrator is the default (\`--integrator auto\`) unless the command names one."
  echo
  echo "| picture | what it shows | command | seconds | error as displayed | linear relative error | rendered |"
  echo "|---|---|---|---|---|---|---|"
  list | while IFS='|' read -r name caption scene options; do
    [ -f "$out/$name.txt" ] && cat "$out/$name.txt"
  done
} >"$out/README.md"
echo "wrote $out/README.md" >&2
