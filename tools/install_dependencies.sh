#!/usr/bin/env bash
# Installs what the package, its tests and its benchmark need from Debian, when missing.
# Run as root (or with sudo). Set SKIP_APT=1 to skip.
set -euo pipefail
[ "${SKIP_APT:-0}" = 1 ] && exit 0
packages=(cmake g++ make libcgal-dev libeigen3-dev libboost-dev libgmp-dev libmpfr-dev doxygen libopenblas0-pthread
          libtbb-dev libsuitesparse-dev libcgal-demo libopenmesh-dev python3-matplotlib python3-numpy python3-scipy python3-nibabel)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update
  # libcgal-demo brings CGAL's data meshes; its recommended Qt packages are not needed.
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi
