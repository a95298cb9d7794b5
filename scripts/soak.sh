#!/usr/bin/env bash
# Soak: renders a long run and a tenth of it, and compares their peak memory. Note that the peak is
# reached at the end, in the initial-map survey, which covers every direction the gimbal swept: a
# run whose cue sweeps more sky peaks higher without leaking (valgrind --tool=massif shows the
# heap flat during the frames themselves).
# Usage: scripts/soak.sh [FRAMES] [SCENARIO]   (default 3000 frames of dataset2)
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-3000}
scenario=${2:-assets/scenarios/dataset2.json}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
peak() {  # peak resident set (kB) and wall time of one render
  /usr/bin/time -f "%M %e" ./build/apps/ladarsim render "$scenario" --out "$work/out$1" --frames "$1" --quiet \
    2>&1 >/dev/null | tail -n 1
}
read -r short_kb short_s <<<"$(peak $((frames / 10)))"
read -r long_kb long_s <<<"$(peak "$frames")"
echo "frames $((frames / 10)): peak ${short_kb} kB in ${short_s} s; frames ${frames}: peak ${long_kb} kB in ${long_s} s"
echo "peak growth over $((frames - frames / 10)) more frames: $(( (long_kb - short_kb) )) kB"
