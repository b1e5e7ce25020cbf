#!/usr/bin/env bash
# Installs the Debian 12 packages TerrainSynthesis needs to build, test and run.
# Does nothing (and needs no network) when everything is already installed.
set -euo pipefail

packages=(
  # toolchain and test frameworks
  build-essential cmake ninja-build git pkg-config googletest libgtest-dev libbenchmark-dev
  # ParaView's SDK (5.11) and what find_package(ParaView) needs to resolve VTK's dependencies
  paraview paraview-dev python3-paraview python3-numpy qtbase5-dev qttools5-dev libqt5svg5-dev
  libqt5opengl5-dev qtxmlpatterns5-dev-tools libutfcpp-dev libogg-dev libtheora-dev libavcodec-dev
  libavformat-dev libavutil-dev libswscale-dev libswresample-dev libavdevice-dev libavfilter-dev
  libnetcdf-dev libhdf5-dev libgl2ps-dev libglew-dev liblz4-dev liblzma-dev libexpat1-dev
  libfreetype-dev libjpeg-dev libpng-dev libtiff-dev libxml2-dev libdouble-conversion-dev
  mpi-default-dev libx11-dev libxt-dev
  # the project's own dependencies
  libgdal-dev gdal-bin libeigen3-dev libboost-graph-dev libfftw3-dev nlohmann-json3-dev
  libmaxflow-dev
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  # headless rendering
  xvfb xauth
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${#missing[@]} missing packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null; then SUDO=sudo; else
    echo "install-deps: run as root (or install sudo) to install packages" >&2; exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
