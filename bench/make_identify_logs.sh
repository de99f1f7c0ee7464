#!/bin/sh
# Simulated logs for the identification coverage study (bench/identify_bench.cpp):
# the paper's bias sweep and clamped-beam protocols, one pair per seed.
#   bench/make_identify_logs.sh OUT_DIR [FIRST_SEED] [LAST_SEED]
# About 25 s of one core per seed.
set -eu
out=${1:?usage: make_identify_logs.sh OUT_DIR [FIRST_SEED] [LAST_SEED]}
first=${2:-1}
last=${3:-50}
pliant=${PLIANT:-build/cli/pliant}
mkdir -p "$out"
seed=$first
while [ "$seed" -le "$last" ]; do
  [ -f "$out/beam_$seed.csv" ] || "$pliant" simulate experiments/scenarios/clamped_beam.json \
    -o "$out/beam_$seed.csv" --seed "$seed" >/dev/null
  [ -f "$out/sweep_$seed.csv" ] || "$pliant" simulate experiments/scenarios/bias_sweep.json \
    -o "$out/sweep_$seed.csv" --seed "$seed" >/dev/null
  seed=$((seed + 1))
done
