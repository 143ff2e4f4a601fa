#!/usr/bin/env bash
# Installs every Debian 12 package fovea needs to build, test and run. Idempotent: only missing
# packages are installed, so a second run is a no-op. Must be run as root (or with sudo available).
set -euo pipefail
PACKAGES=(
  build-essential cmake pkg-config ninja-build clang-format
  libvulkan-dev vulkan-tools mesa-vulkan-drivers vulkan-validationlayers
  glslang-dev glslang-tools spirv-tools libspirv-cross-c-shared-dev spirv-cross
  libglm-dev libglfw3-dev libtinygltf-dev libstb-dev libembree-dev libopenexr-dev
  nlohmann-json3-dev libcli11-dev libimgui-dev libgtest-dev libgmock-dev libeigen3-dev
  xvfb xauth
  # The sanitizer and fuzzing tree (make sanitize-ci, make fuzz): clang with libFuzzer's runtime
  clang libclang-rt-14-dev
  # CC0 HDR environment maps (studiolights/world/*.exr) for the --env tests (docs/scenes.md)
  blender-data
  # A one-node Slurm on the loopback for the sharded reference/bench test (docs/cluster.md)
  slurm-wlm munge
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
