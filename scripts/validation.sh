#!/usr/bin/env bash
# Re-runs the figures of docs/validation*.md and prints them as the pages show them.
#
#   scripts/validation.sh [--long] [--work DIR] [BUILD_DIR]
#
# BUILD_DIR: a Release build of pliant (default: build/ in the repository). It needs
# cli/pliant, bench/filter_accuracy_bench and bench/filter_consistency_bench, and for the
# tests step the test programs in tests/. Nothing is built here.
#
# The quick part (sections 1-7 of docs/validation.md, 13 of validation-unlike-defaults.md) took
# 172-241 s in three runs on the 2-core reference machine under load (nice -n 19). It simulates
# 0.5 GB of logs into the work directory (default: a new directory under /tmp, removed at the end
# unless --work is given). --long adds the Monte Carlo studies of section 8 (validation-studies.md),
# with 2 threads: divot 16 s, known instrument 4 s, clamped 127-145 s, identify 401 s (each of its
# 200 trials simulates and identifies a calibration), families 33 s (1.5 kHz), 8 s (100 Hz) and 14 s
# (1.5 kHz without the hint), and the second generator's hit rate (2.5 min) and loop into corrected
# joints (7 min) of section 10 (validation-diagnosis.md) and its families (1 min) of section 12.
#
# The real-data score (section 3) needs clamped_cv.py (docs/real-data.md); set CLAMPED_CV
# to its path if it is not at /work/shared/tools/clamped_cv.py. Without it that step is
# skipped with the reason.
set -euo pipefail

long=0
work=""
build=""
while [ $# -gt 0 ]; do
  case "$1" in
    --long) long=1 ;;
    --work) work="$2"; shift ;;
    -h|--help) sed -n '2,21p' "$0"; exit 0 ;;
    -*) echo "scripts/validation.sh: unknown option $1 — see --help" >&2; exit 2 ;;
    *) build="$1" ;;
  esac
  shift
done
repo=$(cd "$(dirname "$0")/.." && pwd)
given=${build:-$repo/build}
build=$(cd "$given" 2>/dev/null && pwd) || {
  echo "scripts/validation.sh: build directory $given not found — give a Release build of pliant" >&2
  exit 2
}
pliant=$build/cli/pliant
for exe in "$pliant" "$build/bench/filter_accuracy_bench" "$build/bench/filter_consistency_bench"; do
  [ -x "$exe" ] || { echo "scripts/validation.sh: $exe missing — build it first" >&2; exit 2; }
done
if [ -z "$work" ]; then
  work=$(mktemp -d "${TMPDIR:-/tmp}/pliant_validation.XXXXXX")
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work"
cd "$repo"
clamped_cv=${CLAMPED_CV:-/work/shared/tools/clamped_cv.py}
start=$SECONDS

main() {

section() { printf '\n== %s\n' "$*"; }
# The command as the page shows it: build/ for the build directory, $W for the work directory.
say() { echo "\$ $*"; }
show() { say "$@"; "$@"; }

section "1. Equation (2) and the dead zone on data/divot_push.csv"
for model in paper deadzone; do
  show "$pliant" correct --params data/paper.json --model $model data/divot_push.csv \
    -o "$work/divot_push_$model.csv"
done

section "2. Identification on the simulated calibration logs, against the truth (data/paper.json)"
say "$pliant" identify data/bias_sweep.csv data/clamped_beam.csv -o "$work/identified.json"
"$pliant" identify data/bias_sweep.csv data/clamped_beam.csv -o "$work/identified.json" \
  | sed -n -e '1p' -e '/backlash_rad/p' -e '/variance factor/p' -e '/covariance:/p'
for depth in 0.09 0.22; do
  say "$pliant" params "$work/identified.json" --depth $depth --compare data/paper.json
  "$pliant" params "$work/identified.json" --depth $depth --compare data/paper.json \
    | sed -e '/first:/d' -e '/second:/d'
done

section "3. Identification on the real JHU 2017 data (data/real)"
real=data/real
real_logs="$real/jhu2017_bias_j1.csv $real/jhu2017_bias_j2.csv $real/jhu2017_clamped_j1.csv $real/jhu2017_clamped_j2.csv"
# shellcheck disable=SC2086
say "$pliant" identify $real_logs -o "$work/real.json"
# shellcheck disable=SC2086
"$pliant" identify $real_logs -o "$work/real.json" 2>/dev/null \
  | sed -n -e '1p' -e '/held_friction[12] /p' -e '/backlash_rad/p' -e '/compliance at depth/,/L = 0.226/p' \
        -e '/clearance δ is at its bound/p'
if [ -f "$clamped_cv" ]; then
  mkdir -p "$work/cv" "$work/cv_paper_form"
  # shellcheck disable=SC2086
  show /usr/bin/python3 "$clamped_cv" "$pliant" $real_logs --work "$work/cv"
  # shellcheck disable=SC2086
  show /usr/bin/python3 "$clamped_cv" "$pliant" $real_logs --work "$work/cv_paper_form" -- --no-held-friction
  CLAMPED_CV="$clamped_cv" && export CLAMPED_CV
  show /usr/bin/python3 experiments/real_clamp_coverage.py "$pliant" "$work/coverage"
else
  echo "(skipped: $clamped_cv not found; set CLAMPED_CV)"
fi

show /usr/bin/python3 experiments/real_split_half.py "$pliant" "$work/split"

section "4. The filter on the shipped logs"
say "$build/bench/filter_accuracy_bench" --params data/paper.json data/divot_push.csv --smooth
"$build/bench/filter_accuracy_bench" --params data/paper.json data/divot_push.csv --smooth \
  | sed -n -e '1,2p' -e '/equation (2) /p' -e '/filter /p' -e '/smoother /p'
show "$pliant" filter --smooth --params "$work/identified.json" data/divot.csv -o "$work/divot_filter.csv"

section "5. The filter on long simulated logs (calibrated on other seeds)"
scen=experiments/scenarios
sim() { "$pliant" simulate "$@" > /dev/null; }
cat <<'TXT'
$ build/cli/pliant simulate experiments/scenarios/bias_sweep.json -o $W/cal_bias.csv --seed 101
$ build/cli/pliant simulate experiments/scenarios/clamped_beam.json -o $W/cal_clamp.csv --seed 102
$ build/cli/pliant identify $W/cal_bias.csv $W/cal_clamp.csv -o $W/cal.json
$ build/cli/pliant simulate experiments/scenarios/divot.json -o $W/val_divot.csv --seed 201 \
    [--set 'hidden_effects={}' [--set 'truth.initial_shaft_offset_rad=[0.006,-0.005]']]
$ build/cli/pliant simulate experiments/scenarios/clamped_beam.json -o $W/val_clamp.csv --seed 202 \
    [--set log.mode=all]
$ build/bench/filter_accuracy_bench --params $W/cal.json $W/LOG --smooth OPTIONS   # each row below
TXT
sim $scen/bias_sweep.json -o "$work/cal_bias.csv" --seed 101
sim $scen/clamped_beam.json -o "$work/cal_clamp.csv" --seed 102
"$pliant" identify "$work/cal_bias.csv" "$work/cal_clamp.csv" -o "$work/cal.json" > /dev/null
sim $scen/divot.json -o "$work/val_divot.csv" --seed 201
sim $scen/divot.json -o "$work/val_divot_nf.csv" --seed 201 --set 'hidden_effects={}'
sim $scen/divot.json -o "$work/val_divot_off.csv" --seed 201 --set 'hidden_effects={}' \
  --set 'truth.initial_shaft_offset_rad=[0.006,-0.005]'
sim $scen/clamped_beam.json -o "$work/val_clamp.csv" --seed 202
sim $scen/clamped_beam.json -o "$work/val_clamp_all.csv" --seed 202 --set log.mode=all
accuracy() {  # LABEL LOG, then the bench's options: one row of the page's table
  local label=$1 log=$2; shift 2
  "$build/bench/filter_accuracy_bench" --params "$work/cal.json" "$work/$log" --smooth "$@" \
    | awk -v label="$label" -v opts="$*" '
        /rows/ { rows = $2 }
        /^  equation \(2\) / { eq2 = $3 }
        /^  filter  / { filter = $2; jump = ($4 == "(no") ? "—" : $4 }
        /^  smoother  / { smoother = $2 }
        /^  filter \/ equation/ { share = $(NF - 1) " %" }
        END { printf "| %s | `%s` | %s | %s | %s | %s | %s | %s |\n",
                     label, opts, rows, eq2, filter, share, smoother, jump }'
}
echo "| log | options | rows | equation (2) RMS (mm) | filter RMS (mm) | filter / eq. (2) | smoother RMS (mm) | no jumps (counts) |"
echo "|---|---|---|---|---|---|---|---|"
held="--motor-inertia 0.08 --shaft-damping 0.02"
# shellcheck disable=SC2086
{
  accuracy "divot, friction on" val_divot.csv $held
  accuracy "divot, hidden effects off" val_divot_nf.csv $held
  accuracy "clamped beam, hold means" val_clamp.csv $held
  accuracy "clamped beam, full rate" val_clamp_all.csv $held
  accuracy "divot, shafts off-centre" val_divot_off.csv $held
  accuracy "divot, friction on" val_divot.csv --free
  accuracy "divot, hidden effects off" val_divot_nf.csv --free
  accuracy "clamped beam, hold means" val_clamp.csv --free
  accuracy "clamped beam, full rate" val_clamp_all.csv --free
}
rm -f "$work"/val_*.csv "$work"/cal_*.csv

section "6. The filter's covariance on the CVODE simulator (200 runs, one sample each)"
for opts in "" "--first-seed 5000" "--paper-pushes" "--paper-pushes --first-seed 5000"; do
  # shellcheck disable=SC2086
  say "$build/bench/filter_consistency_bench" --runs 200 $opts
  # shellcheck disable=SC2086
  "$build/bench/filter_consistency_bench" --runs 200 $opts \
    | sed -n -e '/one sample per run/p' -e '/^  tip held  /p'
done

section "7. The tests that hold the stated bounds"
gtest() {  # PROGRAM FILTER
  local exe=$build/tests/$1
  if [ -x "$exe" ]; then
    echo "\$ build/tests/$1 --gtest_filter='$2'"
    "$exe" --gtest_filter="$2" 2>&1 | grep -E '^\[  (PASSED|FAILED|  SKIPPED) '
  else
    echo "(skipped: build/tests/$1 not built)"
  fi
}
gtest experiments_tests 'SimulatorPhysics.*:HiddenEffects.*'
gtest estimation_tests 'JointSmoother.*:ComplianceFilter.*:FilterRealTime.*:QuasiStaticIdentification.*'
gtest diagnostics_tests 'Catalogue/*:DiagnoseChannels.*'
gtest montecarlo_tests 'MontecarloCli.*'
gtest cli_tests 'Commands/KillDuring.*'

section "13. Do no harm: the real free-motion bag"
show /usr/bin/python3 experiments/free_motion.py "$pliant" "$work/free_motion"
echo
echo "quick part: $((SECONDS - start)) s"

if [ $long -eq 1 ]; then
  section "8. Monte Carlo studies (--long)"
  for study in divot known_instrument clamped identify; do
    t0=$SECONDS
    show "$pliant" montecarlo experiments/studies/${study}_study.json -o "$work/mc_$study" \
      --threads 2 --no-plots
    echo "  ($((SECONDS - t0)) s)"
  done
  # The families: instruments, noise and sample rates unlike the defaults; the
  # online ones without the tip_fixed hint (…_arm: the arm identified on its free motion).
  for study in families_1500hz families_100hz families_1500hz_online families_1500hz_online_arm \
      families_100hz_online families_100hz_online_arm; do
    t0=$SECONDS
    show "$pliant" montecarlo experiments/studies/${study}.json -o "$work/mc_$study" \
      --threads 2 --no-plots
    echo "  ($((SECONDS - t0)) s)"
  done
  section "10. Diagnosis on the second generator's logs, and the loop into corrected joints (--long)"
  show /usr/bin/python3 experiments/second_generator/hit_rate.py "$pliant" "$work/hit_rate"
  show /usr/bin/python3 experiments/second_generator/effect_loop.py "$pliant" "$work/loop"
  section "12. The filter on second-generator families unlike the defaults (--long)"
  show /usr/bin/python3 experiments/second_generator/filter_families.py "$pliant" "$work/families"
  echo
  echo "with --long: $((SECONDS - start)) s"
fi
}

# Paths as the page shows them: build/ for the build directory, $W for the work directory.
main | sed -u -e "s|$build/|build/|g" -e "s|$work/|\$W/|g"
