#!/usr/bin/env bash
# Builds ladarsim with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/ and runs the
# whole test suite under it (about 3x slower than the plain suite).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLADARSIM_SANITIZE=ON -DLADARSIM_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-asan -j "${LADARSIM_JOBS:-2}"
# Embree and TBB keep thread-local caches until exit; leaks there are theirs, not ours.
ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1 ctest --test-dir build-asan --output-on-failure -j 2
