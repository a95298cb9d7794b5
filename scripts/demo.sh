#!/usr/bin/env bash
# Installs what is missing, builds, and renders the bundled default scenario into out/default.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/apps/ladarsim render assets/scenarios/default.json --out out/default
