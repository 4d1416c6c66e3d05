#!/usr/bin/env bash
# Installs the dependencies of granvv from Debian packages, then configures and builds into
# build/. Safe to run again: apt-get and cmake skip what is done.
#   scripts/setup.sh            the granvv program and what it needs at run time (the report's
#                               Python packages; Pillow writes the GIF of `granvv movie`)
#   scripts/setup.sh --tests    also the test suite and the benchmarks (every target)
#   scripts/setup.sh --browser  also Chromium and chromedriver, which only the slow suite's
#                               report checks use (scripts/check_report.py)
set -euo pipefail
cd "$(dirname "$0")/.."

tests=0
browser=0
for arg in "$@"; do
  case "$arg" in
    --tests) tests=1 ;;
    --browser) browser=1 ;;
    *)
      echo "setup: unknown option '$arg'; the options are --tests and --browser" >&2
      exit 2
      ;;
  esac
done

packages=(
  build-essential cmake clang-format
  liblammps-dev lammps openmpi-bin libopenmpi-dev libeigen3-dev liblapacke-dev liblapack-dev libhdf5-dev libcli11-dev
  libtomlplusplus-dev nlohmann-json3-dev libspdlog-dev libmuparser-dev libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev # CMakeLists.txt finds them even when only granvv is built
  python3-numpy python3-matplotlib python3-h5py python3-jinja2 python3-pil
  python3-scipy # bench/single_mode_reference.py: LAPACK through scipy
)
((browser)) && packages+=(chromium chromium-driver)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""
  [[ $(id -u) -ne 0 ]] && SUDO="sudo"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
if ((tests)); then
  cmake --build build -j"$(nproc)"
else
  cmake --build build -j"$(nproc)" --target granvv
fi
