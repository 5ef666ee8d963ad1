#!/usr/bin/env bash
# Installs the Debian 12 packages opencv_shading needs, only those missing (apt-get; run as root
# or with sudo available). Extra package names may be passed as arguments.
set -euo pipefail
packages=(build-essential cmake libopencv-dev libgtest-dev libbenchmark-dev libassimp-dev
          pybind11-dev python3-dev python3-numpy python3-pytest python3-opencv "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "Installing: ${missing[*]}"
  sudo=""
  [[ $(id -u) -eq 0 ]] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi
