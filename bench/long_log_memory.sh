#!/usr/bin/env bash
# Peak memory of the streaming tools on a 10^7-row log (issue: reliability).
# Simulates 6,667 s of free motion at 1.5 kHz (10^7 rows, about 2 GB), then
# runs `pliant filter`, `pliant filter --smooth` and `pliant correct` on it
# under /usr/bin/time -v. (The time ratio of the smoother to the filter is
# measured by bench/filter_smooth_log_bench.cpp: PLIANT_LONG_LOG=DIR/long.csv.)
#   bench/long_log_memory.sh [DIR]        (default /tmp/pliant_long_log)
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-/tmp/pliant_long_log}
pliant=build/cli/pliant
mkdir -p "$dir"
if [ ! -f "$dir/long.csv" ]; then
  $pliant simulate experiments/scenarios/free_motion.json -o "$dir/long.csv" --seed 1 \
    --set experiment.duration_s=6666.6667
fi
echo "rows: $(($(grep -vc '^#' "$dir/long.csv") - 1)), bytes: $(stat -c %s "$dir/long.csv")"
for command in "filter --params data/paper.json" "filter --smooth --params data/paper.json" \
  "correct --params data/paper.json"; do
  /usr/bin/time -v $pliant $command "$dir/long.csv" -o "$dir/out.csv" 2> "$dir/time.txt" |
    head -n 1
  grep -E "Maximum resident set size|Elapsed \(wall clock\)" "$dir/time.txt"
done
