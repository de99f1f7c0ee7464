#!/usr/bin/env bash
# Installs what pliant needs to build and test, from Debian 12's own packages only.
# Idempotent: packages already present are skipped, so a second run changes nothing.
# Runs apt-get directly as root, through sudo otherwise.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config
  libeigen3-dev          # fixed-size linear algebra everywhere
  libceres-dev           # Jet autodiff, smoothing and identification
  libsundials-dev        # CVODE for the simulator
  libboost-dev libboost-math-dev # distributions and quantiles
  nlohmann-json3-dev     # parameters and report JSON
  libcli11-dev           # the pliant command line
  libgtest-dev libgmock-dev libbenchmark-dev
  gnuplot-nox            # report pictures
  libboost-mpi-dev openmpi-bin  # pliant montecarlo across machines (Boost.MPI over OpenMPI)
  chromium               # headless check that the diagnose report renders
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then as_root=(); else as_root=(sudo); fi
echo "install-deps: installing from Debian: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: done"
