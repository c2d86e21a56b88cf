#!/usr/bin/env bash
# Installs everything Slime needs to build, run and test, from Debian 12's packages.
set -euo pipefail
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends \
  build-essential cmake ninja-build pkg-config git ca-certificates \
  libembree-dev libtbb-dev libglm-dev libstb-dev nlohmann-json3-dev libcli11-dev \
  libglfw3-dev libimgui-dev libegl-dev libopengl-dev libgl-dev libgl1 libegl1 libegl-mesa0 libgl1-mesa-dri \
  libosmesa6-dev libtinygltf-dev libassimp-dev assimp-utils \
  libgtest-dev libgmock-dev libbenchmark-dev \
  xvfb xauth xdotool x11-utils jq gnuplot-nox imagemagick ffmpeg python3 \
  clang libclang-rt-14-dev libbullet-dev libeigen3-dev >/dev/null
echo "setup: dependencies installed"
