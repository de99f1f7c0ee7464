#!/usr/bin/env bash
# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer
# (any finding fails the run). Separate build tree: build-asan. The ROS 1 parts
# are left out: Debian's roscpp, rosbag and log4cxx are not instrumented and keep
# allocations to process exit, which LeakSanitizer would report as pliant's;
# the Python module skips itself (an instrumented module cannot load into python3).
# Line tables only (-g1): the reports keep FILE:LINE and the build is faster (CI
# runs within 90 minutes on 2 cores).
# The tests listed in tests/release_only.txt (long repetitions of paths shorter
# tests drive here; it says which) run in the Release suite only.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
  -DPLIANT_SANITIZE=ON -DPLIANT_BUILD_BENCHMARKS=OFF -DPLIANT_WITH_ROS1=OFF
cmake --build build-asan -j "$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
release_only=$(grep -v '^#' tests/release_only.txt | grep . | sed 's/[.]/\\./g' | paste -sd '|')
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" -E "^(${release_only})( |\$)"
