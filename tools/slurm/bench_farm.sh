#!/bin/sh
# Scheduling overhead and cost of splitting: wall time of a 4-part `prism farm slurm` render on a
# local single-node cluster (local_cluster.sh; as many CPUs as the machine, one thread per part)
# against the single-process render of the same image (all cores), and the CPU seconds of the 4
# parts (the same commands, run one after another under /usr/bin/time, since the local cluster
# keeps no accounting) against the single render's. Needs root. Run it on an otherwise idle
# machine; 512 80 takes about 30 s single-process on 2 cores (AVX-512).
# Usage: bench_farm.sh PRISM [WIDTH SPP]
set -eu
prism=$(realpath "$1"); width=${2:-128}; spp=${3:-64}
here=$(dirname "$(realpath "$0")"); scene=$(realpath "$here/../../data/scenes/cornell.gltf")
dir=$(mktemp -d); trap '"$here/local_cluster.sh" stop "$dir/cluster"; rm -rf "$dir"' EXIT
eval "export $("$here/local_cluster.sh" start "$dir/cluster")"
opts="--width $width --spp $spp --seed 1"
echo "cornell.gltf $opts; $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))"

# Wall and CPU seconds of a command, as "WALL USER+SYS".
timed() { /usr/bin/time -f "%e %U %S" "$@" 2>&1 >/dev/null | tail -n 1 | awk '{ print $1, $2 + $3 }'; }

set -- $(timed "$prism" render "$scene" $opts -q -o "$dir/single.exr")
single_wall=$1 single_cpu=$2
echo "single render (all cores):      $single_wall s wall, $single_cpu s CPU"

start=$(date +%s.%N)
"$prism" farm slurm "$scene" --parts 4 $opts --threads 1 --out "$dir/farm" >/dev/null
while [ -n "$(squeue -h)" ]; do sleep 0.1; done
end=$(date +%s.%N)
[ -f "$dir/farm/image.exr" ] || { echo "farm render failed; logs:" >&2; cat "$dir"/farm/logs/* >&2; exit 1; }
farm_wall=$(echo "$end - $start" | bc)
echo "4-part Slurm render (submit to merged image): $farm_wall s wall"

parts_cpu=0
for i in 0 1 2 3; do
  set -- $(timed "$prism" render "$scene" $opts --threads 1 --samples "$((i * spp / 4)):$(((i + 1) * spp / 4))" -q \
    -o "$dir/p$i")
  parts_cpu=$(echo "$parts_cpu + $2" | bc)
done
echo "4 parts, one after another:     $parts_cpu s CPU in total"
echo "ratios: Slurm wall / single wall = $(echo "scale=3; $farm_wall / $single_wall" | bc)," \
  "parts CPU / single CPU = $(echo "scale=3; $parts_cpu / $single_cpu" | bc)"
