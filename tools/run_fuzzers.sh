#!/bin/sh
# Runs each libFuzzer target of a PRISM_FUZZ build for SECONDS on its corpus (seeded by
# fuzz/make_corpus.py, grown in BUILD/corpus/TARGET), then prints the executions per target and
# in total. Fails on the first crash, leak, timeout or sanitizer report (the input is saved in
# BUILD/artifacts/). Usage: tools/run_fuzzers.sh BUILD SECONDS
set -eu
build=$1
seconds=$2
cd "$(dirname "$0")/.."
python3 fuzz/make_corpus.py "$build/seeds"
mkdir -p "$build/artifacts"
total=0
for target in fuzz_gltf fuzz_env_map fuzz_image; do
  mkdir -p "$build/corpus/$target"
  log="$build/$target.log"
  status=0
  "$build/fuzz/$target" "$build/corpus/$target" "$build/seeds/$target" -max_total_time="$seconds" -timeout=20 \
    -rss_limit_mb=4096 -malloc_limit_mb=4096 -print_final_stats=1 -artifact_prefix="$build/artifacts/$target-" \
    >"$log" 2>&1 || status=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  corpus=$(ls "$build/corpus/$target" | wc -l)
  if [ "$status" -ne 0 ]; then
    tail -n 60 "$log"
    echo "$target: FAILED (exit $status) after ${runs:-?} executions; input in $build/artifacts/" >&2
    exit 1
  fi
  echo "$target: ${runs} executions in ${seconds} s, corpus of $corpus inputs, no findings"
  total=$((total + runs))
done
echo "fuzzing: $total executions in total"
