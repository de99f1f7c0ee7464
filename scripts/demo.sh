#!/usr/bin/env bash
# Fresh machine to the main job on the shipped data: installs dependencies,
# builds the pliant command, then, on the real JHU 2017 recordings
# (data/real/, made by pliant import from the JHU files; docs/real-data.md):
#   R1. identifies joints 1 and 2 from the real bias sweeps and clamped beams
#       (the held friction included; the paper's Fig. 6 redrawn);
#   R2. corrects the real clamped beam of joint 1 with the identified file;
#   R3. diagnoses that real log against the paper's form (identified without
#       the held friction): which effect the real data show that it lacks;
#   R4. diagnoses it against the identified file, the held friction part of
#       the model: what is still missing;
# then the simulated showcase, where the truth is known:
#   1. identifies the instrument from the simulated calibration logs (bias
#      sweep + clamped beam), with the covariance of every parameter;
#   2. corrects the simulated divot pushes with the paper's equation (2);
#   3. filters them with the EKF and smooths them with the RTS smoother;
#   4. diagnoses a log with an effect the model lacks: which one, and the
#      error with it added, in an HTML report (out/diagnosis/index.html).
# Outputs land in out/; each step prints its tip error against the truth.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)" --target pliant
mkdir -p out
pliant=build/cli/pliant
real=data/real
echo
echo "== R1. identify: the real bias sweeps and clamped beams -> out/real.json"
$pliant identify $real/jhu2017_bias_j1.csv $real/jhu2017_bias_j2.csv \
  $real/jhu2017_clamped_j1.csv $real/jhu2017_clamped_j2.csv -o out/real.json \
  --figure out/real_fig6.png > out/real_identify.txt 2> out/real_identify_warnings.txt
sed -n -e '1,2p' -e '/held_friction/p' -e '/backlash_rad/p' -e '/compliance at depth/,/L = 0.226/p' \
  -e '/wrote/p' out/real_identify.txt
sed -n -e '/clearance/p' out/real_identify_warnings.txt
echo
echo "== R2. correct: the real clamped beam of joint 1 with the identified file"
$pliant correct --params out/real.json $real/jhu2017_clamped_j1.csv -o out/real_clamped_j1.csv
echo
echo "== R3. diagnose: the real clamped beam of joint 1 against the paper's form"
$pliant identify --no-held-friction $real/jhu2017_bias_j1.csv $real/jhu2017_clamped_j1.csv \
  -o out/real_paper_form.json > /dev/null 2>&1
$pliant diagnose --params out/real_paper_form.json $real/jhu2017_clamped_j1.csv \
  -o out/real_diagnosis | sed -n -e '1,5p' -e '/candidate effects/,/^    3\./p'
echo
echo "== R4. diagnose: the same log against the identified file (its held friction in the model)"
$pliant diagnose --params out/real.json $real/jhu2017_clamped_j1.csv \
  -o out/real_diagnosis_identified | sed -n -e '1,5p' -e '/candidate effects/,/^    2\./p'
echo
echo "== 1. identify: calibration logs -> out/identified.json"
$pliant identify data/bias_sweep.csv data/clamped_beam.csv -o out/identified.json \
  --figure out/identify_fig6.png > out/identify.txt
# The full table (every parameter ± σ, laws compared) is in out/identify.txt.
sed -n -e '1,2p' -e '/backlash_rad/p' -e '/compliance at depth/,/fit RMS joint 2/p' -e '/wrote/p' \
  out/identify.txt
echo
echo "== 2. correct: equation (2) on the divot pushes"
$pliant correct --params out/identified.json --model paper data/divot.csv -o out/divot_paper.csv
echo
echo "== 3. filter: the EKF and the RTS smoother on the same log"
$pliant filter --smooth --params out/identified.json data/divot.csv -o out/divot_filter.csv
echo
echo "== 4. diagnose: what the model lacks on data/divot_hidden_effect.csv"
$pliant diagnose --params out/identified.json data/divot_hidden_effect.csv -o out/diagnosis
echo
echo "Open the report in a browser: out/diagnosis/index.html"
