#!/bin/bash
# Model loading in fresh processes, Meridian against GeographicLib, alternately (docs/benchmarks.md,
# "Model loading"): task-clock of `perf stat` per run, median, min and max of RUNS runs each.
#   bench/load_timing.sh BUILD_DIR MODEL_DIR MODEL_NAME [RUNS]
# e.g. build/meridian gravity synth-model --degree 2190 --seed 2024 --out /tmp/s2190
#      bench/load_timing.sh build /tmp s2190 21
set -euo pipefail
build=$1 dir=$2 name=$3 runs=${4:-21}
for _ in $(seq "$runs"); do
  for tool in meridian geographiclib; do
    perf stat -x, -e task-clock "$build/bench/load_model_once_$tool" "$dir" "$name" 2>&1 >/dev/null |
      awk -F, -v t="$tool" '{print t, $1}'
  done
done | python3 -c '
import statistics, sys
runs = {}
for line in sys.stdin:
    tool, ms = line.split()
    runs.setdefault(tool, []).append(float(ms))
for tool, v in runs.items():
    print(f"{tool:14s} median {statistics.median(v):6.1f} ms  min {min(v):6.1f}  max {max(v):6.1f}  ({len(v)} runs)")
'
