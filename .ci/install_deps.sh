#!/usr/bin/env bash
# Installs sable's build and test dependencies from Debian packages (skips what is there).
set -euo pipefail
pkgs=(build-essential cmake libeigen3-dev libgtest-dev libhdf5-dev libgsl-dev python3-numpy python3-matplotlib python3-scipy python3-h5py python3-pytest python3-vtk9 liggghts libopenmpi-dev openmpi-bin)
missing=()
for p in "${pkgs[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi
