#!/usr/bin/env bash
# Configures (once) and builds ladarsim into build/ with Ninja on two jobs.
set -euo pipefail
cd "$(dirname "$0")/.."
# With matplotlib: the preview and plot scripts have tests too.
bash scripts/setup.sh --plots
if [ ! -f build/build.ninja ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build build -j "${LADARSIM_JOBS:-2}"
