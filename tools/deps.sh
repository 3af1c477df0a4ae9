#!/usr/bin/env bash
# Installs the Debian 12 packages bandlimit needs, skipping what is already there.
set -euo pipefail
pkgs=(g++ cmake make pkg-config
  libginac-dev ginac-tools libcln-dev libboost-math-dev libboost-dev
  libopenimageio-dev openimageio-tools glslang-tools glslang-dev
  libegl-dev libgles-dev libgl1-mesa-dri libosmesa6-dev
  libgtest-dev libbenchmark-dev libtbb-dev nlohmann-json3-dev libcli11-dev libfmt-dev
  libnlopt-cxx-dev gnuplot-nox python3
  libopenmpi-dev openmpi-bin  # optional MPI tuner driver (bltune_mpi)
  fonts-dejavu-core)  # labels in runtime/image reports (OpenImageIO render_text)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "[deps] installing: ${missing[*]}"
  SUDO=""; [ "$(id -u)" = 0 ] || SUDO=sudo
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "[deps] all ${#pkgs[@]} packages present"
fi
