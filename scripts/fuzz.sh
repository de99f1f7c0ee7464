#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, with ASan+UBSan) and runs each from its
# seed corpus in tests/fuzz/corpus/<reader>/.
#   scripts/fuzz.sh                          30 s each
#   scripts/fuzz.sh -seed=1 -runs=100000     what CI runs: deterministic, 12-30 s each
#   scripts/fuzz.sh -runs=10000000           the long run reported in docs/validation-studies.md
# Findings are written to build-fuzz/findings/; add each as a regression test.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
CXX=clang++ CC=clang cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPLIANT_FUZZ=ON -DPLIANT_BUILD_TESTS=OFF -DPLIANT_BUILD_BENCHMARKS=OFF
limit=("${@:--max_total_time=30}")
mkdir -p build-fuzz/findings
for source in tests/fuzz/*_fuzz.cpp; do
  name=$(basename "$source" .cpp)
  reader=${name%_fuzz}
  cmake --build build-fuzz -j "$(nproc)" --target "$name"
  work=build-fuzz/corpus/$reader
  mkdir -p "$work"
  echo "fuzz: $name ${limit[*]}"
  regressions=()
  [ -d "tests/fuzz/regressions/$reader" ] && regressions=("tests/fuzz/regressions/$reader")
  build-fuzz/tests/fuzz/"$name" "$work" "tests/fuzz/corpus/$reader" "${regressions[@]}" "${limit[@]}" \
    -artifact_prefix=build-fuzz/findings/"$name"- -print_final_stats=1 2>&1 |
    grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb|==|SUMMARY|Done)" || true
  if ls build-fuzz/findings/"$name"-* >/dev/null 2>&1; then
    echo "fuzz: $name found a crash: build-fuzz/findings/"; exit 1
  fi
done
