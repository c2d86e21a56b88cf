#!/usr/bin/env bash
# Installs the dependencies, builds the release preset and runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release -G Ninja >/dev/null
cmake --build --preset release
ctest --preset release -j2 --timeout 600
