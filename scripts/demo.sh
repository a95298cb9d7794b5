#!/usr/bin/env bash
# Installs what is missing, builds, renders the bundled default scenario into out/default and
# draws out/default/preview.png (frames with their ground-truth boxes).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --plots
bash scripts/build.sh
rm -rf out/default
./build/apps/ladarsim render assets/scenarios/default.json --out out/default
# Debian's own interpreter: its matplotlib is the one setup.sh installed.
/usr/bin/python3 scripts/preview.py out/default
