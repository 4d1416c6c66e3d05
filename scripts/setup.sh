#!/usr/bin/env bash
# Installs every dependency of granvv from Debian packages, then configures and
# builds into build/. Safe to run again: apt-get and cmake skip what is done.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake clang-format
  liblammps-dev lammps openmpi-bin libopenmpi-dev libeigen3-dev liblapacke-dev liblapack-dev libhdf5-dev libcli11-dev
  libtomlplusplus-dev nlohmann-json3-dev libspdlog-dev libmuparser-dev libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3-numpy python3-matplotlib python3-h5py python3-jinja2
  chromium chromium-driver  # the slow suite opens report.html in a real browser (scripts/check_report.py)
)
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
cmake --build build -j"$(nproc)"
