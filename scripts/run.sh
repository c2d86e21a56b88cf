#!/usr/bin/env bash
# Installs the dependencies, builds Slime and runs it: the interactive viewer when a display is
# available, otherwise a headless snapshot written to slime.png.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release -G Ninja >/dev/null
cmake --build --preset release --target slime
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  exec build/release/app/slime "$@"
else
  build/release/app/slime snapshot -o slime.png "$@"
  echo "no display: wrote slime.png"
fi
