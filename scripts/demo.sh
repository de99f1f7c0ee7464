#!/usr/bin/env bash
# Fresh machine to the main job on the shipped data: installs dependencies,
# builds the pliant command, and corrects the sample divot-push log with the
# paper's model and with the dead-zone model.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)" --target pliant
mkdir -p out
for model in paper deadzone; do
  ./build/cli/pliant correct --params data/paper.json --model "$model" \
    data/divot_push.csv -o "out/divot_push_${model}.csv"
done
