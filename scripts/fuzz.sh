#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) into build-fuzz/ and runs each for a set
# time on the seed corpus in tests/ (scenario files, shipped glTF models).
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET]   (default 60)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLADARSIM_FUZZ=ON \
  -DLADARSIM_BUILD_TESTS=OFF -DLADARSIM_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-fuzz -j "${LADARSIM_JOBS:-2}" --target fuzz_gltf fuzz_scenario fuzz_pcd
corpus=build-fuzz/corpus
mkdir -p "$corpus/gltf" "$corpus/scenario" "$corpus/pcd"
cp assets/models/*.glb "$corpus/gltf/"
cp tests/cli/*.json tests/cli/bad/*.json assets/scenarios/*.json "$corpus/scenario/"
printf 'VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n' >"$corpus/pcd/seed.pcd"
export ASAN_OPTIONS=detect_leaks=0
for target in gltf scenario pcd; do
  echo "fuzz_$target: ${seconds} s"
  (cd "$corpus/$target" && ../../fuzz/fuzz_$target -max_total_time="$seconds" -max_len=65536 . 2>&1 | tail -n 3)
done
