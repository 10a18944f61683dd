#!/usr/bin/env bash
# Installs isocurv's build and run dependencies from Debian's archive when any is missing.
# Idempotent and quiet when everything is already there. Needs root (or sudo) to install.
set -euo pipefail
packages=(build-essential cmake ninja-build pkg-config zlib1g-dev libzstd-dev libblosc-dev libopenvdb-dev libboost-iostreams-dev libtbb-dev
          pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
          libeigen3-dev libvtk9-dev libgtest-dev libcli11-dev nlohmann-json3-dev xvfb xauth
          pybind11-dev python3-dev python3-numpy openmpi-bin libopenmpi-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
start=$(date +%s)
echo "isocurv setup: ${#missing[@]} Debian packages to install (${missing[*]})" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "isocurv setup: missing packages (${missing[*]}); run as root" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
echo "isocurv setup: updating the package lists" >&2
$SUDO apt-get update -qq
echo "isocurv setup: downloading and installing them (about 2-3 minutes on a fresh machine)" >&2
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "isocurv setup: installed in $(( $(date +%s) - start )) s" >&2
