#!/usr/bin/env bash
# Installs the Debian 12 packages ladarsim needs, only those missing; quiet and idempotent.
# Usage: setup.sh [--plots]   (matplotlib is always installed now: the Python module's tests draw
# with it; --plots is still accepted)
set -euo pipefail

# strace: tests/cli/test_install.sh watches which files the installed program opens.
packages=(
  build-essential cmake ninja-build ccache pkg-config
  libeigen3-dev libembree-dev libtinygltf-dev nlohmann-json3-dev libspdlog-dev libtbb-dev
  libopenexr-dev libhdf5-dev libcli11-dev librandom123-dev libpcl-dev catch2 libopenmpi-dev openmpi-bin libxgboost-dev
  chromium python3 strace
  pybind11-dev python3-pybind11 python3-pytest python3-numpy python3-matplotlib python3-h5py
)
# npm fetches the viewer's three.js; any Node.js that brings npm will do.
command -v npm >/dev/null 2>&1 || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# The browser viewer's one dependency, pinned in apps/viewer/package-lock.json, installed locally.
viewer="$(dirname "$0")/../apps/viewer"
if [ ! -f "$viewer/node_modules/three/build/three.module.js" ]; then
  echo "setup: installing three.js for the viewer"
  (cd "$viewer" && npm ci --no-audit --no-fund --silent)
fi
