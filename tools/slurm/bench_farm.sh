#!/bin/sh
# Scheduling overhead and cost of splitting: wall time of a 4-part `prism farm slurm` render on a
# local single-node cluster (local_cluster.sh) against the single-process render of the same
# image, and the CPU seconds of the 4 parts (the same commands, run one after another under
# /usr/bin/time) against the single render's. Needs root. Usage: bench_farm.sh PRISM [WIDTH SPP]
set -eu
prism=$(realpath "$1"); width=${2:-128}; spp=${3:-64}
here=$(dirname "$(realpath "$0")"); scene="$here/../../data/scenes/cornell.gltf"
dir=$(mktemp -d); trap '"$here/local_cluster.sh" stop "$dir/cluster"; rm -rf "$dir"' EXIT
eval "export $("$here/local_cluster.sh" start "$dir/cluster")"
opts="--width $width --spp $spp --seed 1"
/usr/bin/time -f "single render: %e s wall, %U+%S s CPU" "$prism" render "$scene" $opts -q -o "$dir/single.exr"
start=$(date +%s.%N)
"$prism" farm slurm "$scene" --parts 4 $opts --threads 1 --out "$dir/farm" >/dev/null
while [ -n "$(squeue -h)" ]; do sleep 0.1; done
end=$(date +%s.%N)
[ -f "$dir/farm/image.exr" ] || { echo "farm render failed" >&2; exit 1; }
echo "4-part Slurm render (submit to merged image): $(echo "$end - $start" | bc) s wall"
cpu=0
for i in 0 1 2 3; do
  range="$((i * spp / 4)):$(((i + 1) * spp / 4))"
  t=$(/usr/bin/time -f "%U %S" "$prism" render "$scene" $opts --threads 1 --samples "$range" -q -o "$dir/p$i" 2>&1 >/dev/null | tail -1)
  cpu=$(echo "$cpu + $(echo "$t" | tr ' ' '+')" | bc)
done
echo "4 parts: $cpu s CPU in total"
