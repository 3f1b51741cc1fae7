#!/usr/bin/env bash
# Installs what vtkSAVR needs on Debian 12 (as root) and builds it into ./build (Release).
# Idempotent: packages already present are not installed again; the build is incremental.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake libvtk9-dev libtbb-dev libeigen3-dev libgtest-dev xvfb xauth
  mricron-data python3-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# Debian's python3 (whose vtkmodules match this VTK), whatever else is first on the PATH.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3
cmake --build build -j2
