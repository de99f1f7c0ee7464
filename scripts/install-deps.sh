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
  pybind11-dev python3-dev python3-numpy python3-pytest  # import pliant (python/)
)

# Optional: ROS 1 (Debian's own packages) for reading bags and the pliant_ros node (ros/).
# When they cannot be installed, pliant builds without them and says why.
optional_packages=(
  librosbag-dev libroscpp-dev libsensor-msgs-dev ros-core python3-rosbag python3-roslaunch
)

not_installed() {
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
  done
}
mapfile -t missing < <(not_installed "${packages[@]}")
mapfile -t missing_optional < <(not_installed "${optional_packages[@]}")

if [ ${#missing[@]} -eq 0 ] && [ ${#missing_optional[@]} -eq 0 ]; then
  echo "install-deps: all $(( ${#packages[@]} + ${#optional_packages[@]} )) packages already installed"
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then as_root=(); else as_root=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing from Debian: ${missing[*]}"
  "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
if [ ${#missing_optional[@]} -gt 0 ]; then
  echo "install-deps: installing the optional ROS 1 packages: ${missing_optional[*]}"
  "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing_optional[@]}" ||
    echo "install-deps: warning: the ROS 1 packages could not be installed; pliant builds without" \
      "bag import and the pliant_ros node (cmake says so)"
fi
echo "install-deps: done"
