#!/usr/bin/env bash
# Prism's BVH against Embree, ray for ray. Generates raybench's ray sets (primary
# 1024x1024, diffuse and shadow 1M, seed 1) for three scenes, traces each set with
# `prism bench rays` and `raybench embree` back to back, checks Prism's hits against Embree's
# with `raybench check`, and prints a Markdown table of throughput, build time and memory.
#
# The shared assets (PRISM_SHARED_DIR; default: `python3 tools/shared_dir.py`) hold raybench and
# the two Khronos scenes.
# Environment: RAYBENCH  raybench binary (default $PRISM_SHARED_DIR/tools/raybench/build/raybench)
#              PRISM     prism binary (default build/apps/prism)
#              OUT       scratch folder for scenes, rays and hits (default build/bench_rays)
#              ROUNDS    alternations of Prism and Embree per cell; best of each (default 3)
#              REPEAT    timed passes per run (default 5)
#              THREADS   thread counts to measure (default "1 2")
#              KINDS     ray kinds to measure (default "primary diffuse shadow")
#              SCENES    scene names to measure (default all three: MetalRoughSpheresNoTextures
#                        TransmissionTest procedural)
#              EMBREE_CONFIG  extra Embree device config, e.g. isa=avx2 for its AVX2 kernels (default none)
# The AVX2 comparison on an AVX-512 machine: Prism built with -DPRISM_ARCH=x86-64-v3 (README) and
#   PRISM=build-avx2/apps/prism EMBREE_CONFIG=isa=avx2 tools/bench_rays.sh
# On a shared, noisy machine the best of several alternations is compared, as raybench's README
# recommends; rerun when a cell looks off.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${PRISM_SHARED_DIR:-$(python3 "$root/tools/shared_dir.py")}
raybench=${RAYBENCH:-$shared/tools/raybench/build/raybench}
prism=${PRISM:-$root/build/apps/prism}
out=${OUT:-$root/build/bench_rays}
rounds=${ROUNDS:-3}
repeat=${REPEAT:-5}
threads=${THREADS:-1 2}
kinds=${KINDS:-primary diffuse shadow}
only=${SCENES:-}
embree_config=()
[ -n "${EMBREE_CONFIG:-}" ] && embree_config=(--embree-config "$EMBREE_CONFIG")

if [ ! -x "$raybench" ]; then
  echo "bench_rays: raybench not found at $raybench; skipping (build it as its README says, or set RAYBENCH)"
  exit 0
fi
if [ ! -x "$prism" ]; then
  echo "bench_rays: $prism not found; run 'make build' first (or set PRISM)" >&2
  exit 1
fi
mkdir -p "$out"
[ -f "$out/procedural.glb" ] || python3 "$shared/tools/raybench/make_test_scene.py" "$out/procedural.glb" >/dev/null
scenes=(
  "$shared/assets/gltf/MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb"
  "$shared/assets/gltf/TransmissionTest/glTF/TransmissionTest.gltf"
  "$out/procedural.glb"
)

field() { sed -n "s/.* $1=\([^ ]*\).*/\1/p" <<<"$2"; }
best() { awk -v a="$1" -v b="$2" -v hi="$3" 'BEGIN { if (a == "" || (hi ? b > a : b < a)) print b; else print a }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }

echo "| scene | rays | threads | Prism Mrays/s | Embree Mrays/s | ratio | Prism build ms | Embree build ms | build ratio | Prism bytes/tri | check |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for scene in "${scenes[@]}"; do
  if [ ! -f "$scene" ]; then
    echo "bench_rays: $scene not found; skipping it" >&2
    continue
  fi
  name=$(basename "${scene%.*}")
  [ -n "$only" ] && [[ " $only " != *" $name "* ]] && continue
  for kind in $kinds; do
    rays=$out/$name.$kind.rays
    if [ ! -f "$rays" ]; then
      size=(--count 1048576)
      [ "$kind" = primary ] && size=(--width 1024 --height 1024)
      "$raybench" gen "$scene" --kind "$kind" "${size[@]}" --seed 1 --out "$rays" >/dev/null 2>&1
    fi
    mode=()
    [ "$kind" = shadow ] && mode=(--occluded)
    for t in $threads; do
      p_mrays="" e_mrays="" p_build="" e_build="" bytes=""
      for ((r = 0; r < rounds; ++r)); do
        p_hits=() e_hits=()  # the last round's hits are the ones checked
        if ((r == rounds - 1)); then
          p_hits=(--hits "$out/$name.$kind.prism.hits") e_hits=(--hits "$out/$name.$kind.embree.hits")
        fi
        p=$(nice -n 10 "$prism" bench rays "$scene" "$rays" --threads "$t" --repeat "$repeat" "${mode[@]}" \
              "${p_hits[@]}" 2>/dev/null | tail -1) ||
          { echo "bench_rays: prism bench rays failed on $rays" >&2; exit 1; }
        e=$(nice -n 10 "$raybench" embree "$scene" "$rays" --threads "$t" --repeat "$repeat" "${mode[@]}" \
              "${embree_config[@]}" "${e_hits[@]}" 2>/dev/null | tail -1) ||
          { echo "bench_rays: raybench embree failed on $rays" >&2; exit 1; }
        p_mrays=$(best "$p_mrays" "$(field mrays_best "$p")" 1)
        e_mrays=$(best "$e_mrays" "$(field mrays_best "$e")" 1)
        p_build=$(best "$p_build" "$(field build_ms "$p")" 0)
        e_build=$(best "$e_build" "$(field build_ms "$e")" 0)
        bytes=$(field bytes_per_tri "$p")
      done
      check=$("$raybench" check "$rays" "$out/$name.$kind.embree.hits" "$out/$name.$kind.prism.hits" | tail -1) || true  # a FAIL is a row, not the end
      echo "| $name | $kind | $t | $p_mrays | $e_mrays | $(ratio "$p_mrays" "$e_mrays") | $p_build | $e_build |" \
           "$(ratio "$p_build" "$e_build") | $bytes | $(field result "$check") (bad $(field bad_frac "$check")) |"
    done
  done
done
