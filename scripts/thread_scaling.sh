#!/usr/bin/env bash
# Whole runs' thread scaling as a user times them: process wall time of `ladarsim render` (set-up
# and writing included) for the default scenario and dataset 2 over Autzen, at each thread count.
#   scripts/thread_scaling.sh bundle BIN...   packs each BIN (stripped), the libraries they load,
#                                             their loader and the Autzen map into build-device/
#                                             (for a machine without Debian's packages or ../shared)
#   scripts/thread_scaling.sh run [T...]      times every bundled BIN (else build/apps/ladarsim) at
#                                             T threads (default 1 2 4 8 16); a table on stdout
# On a lent device: carry build-device and run `scripts/thread_scaling.sh run`.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-}; shift || true
case "$mode" in
bundle)
  [ $# -gt 0 ] || { echo "usage: $0 bundle BIN..." >&2; exit 2; }
  stage=$(mktemp -d)
  mkdir -p "$stage/bundle/bin" "$stage/bundle/lib" "$stage/bundle/data"
  for b in "$@"; do strip -o "$stage/bundle/bin/$(basename "$b")" "$b"; done
  for b in "$@"; do ldd "$b" | awk '/=>/ {print $3} !/=>/ && /^[ \t]*\// {print $1}'; done | sort -u |
    while read -r l; do cp -L "$l" "$stage/bundle/lib/"; done
  # TBB opens its allocator at run time: without it, the timings would be of another malloc.
  cp -L /usr/lib/x86_64-linux-gnu/libtbbmalloc.so.2 "$stage/bundle/lib/"
  cp ../shared/data/autzen/autzen_trim.pcd "$stage/bundle/data/"
  mkdir -p build-device
  tar -C "$stage" -cJf build-device/bundle.tar.xz.tmp bundle && mv build-device/bundle.tar.xz.tmp build-device/bundle.tar.xz
  rm -rf "$stage"
  echo "build-device/bundle.tar.xz: $(du -h build-device/bundle.tar.xz | cut -f1)"
  ;;
run)
  threads=${*:-1 2 4 8 16}
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  map=../shared/data/autzen/autzen_trim.pcd
  if [ -f build-device/bundle.tar.xz ]; then
    tar -xJf build-device/bundle.tar.xz -C "$work"
    map=$work/bundle/data/autzen_trim.pcd
    bins=$(ls "$work/bundle/bin")
    launch() { local b=$1; shift; "$work/bundle/lib/ld-linux-x86-64.so.2" --library-path "$work/bundle/lib" "$work/bundle/bin/$b" "$@"; }
  else
    bins=ladarsim
    launch() { shift; build/apps/ladarsim "$@"; }
  fi
  # Dataset 2 over Autzen with the map wherever it is here (the scenario names ../shared), written
  # in the scratch directory: nothing is written into the source tree.
  sed -e "s#\"../../../shared/data/autzen/autzen_trim.pcd\"#\"$(realpath "$map")\"#" \
      -e "s#\"extends\": \"dataset2.json\"#\"extends\": \"$(realpath assets/scenarios/dataset2.json)\"#" \
      assets/scenarios/dataset2-autzen.json >"$work/ds2-autzen.json"
  echo "cores $(nproc)"
  printf '%-16s %-16s %6s %7s %8s %8s %9s %10s\n' binary scenario frames threads wall_s user_s render_s beams_per_s
  for sc in "assets/scenarios/default.json 300" "$work/ds2-autzen.json 48"; do
    set -- $sc
    for t in $threads; do
      for b in $bins; do
        rm -rf "$work/out"
        start=$(date +%s.%N)
        TIMEFORMAT=%U
        user=$( { time launch "$b" render "$1" --out "$work/out" --threads "$t" --frames "$2" --quiet >/dev/null 2>"$work/err"; } 2>&1 ) ||
          { echo "$b $1 --threads $t failed: $(cat "$work/err")" >&2; exit 1; }
        wall=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {print b - a}')
        render_s=$(grep -o '"render_s": *[0-9.e+-]*' "$work/out/manifest.json" | tail -1 | sed 's/.*: *//')
        az=$(grep -o '"beams_az": *[0-9]*' "$work/out/manifest.json" | head -1 | sed 's/.*: *//')
        el=$(grep -o '"beams_el": *[0-9]*' "$work/out/manifest.json" | head -1 | sed 's/.*: *//')
        printf '%-16s %-16s %6s %7s %8.2f %8.2f %9.2f %10.0f\n' "$b" "$(basename "$1" .json)" "$2" "$t" "$wall" "$user" "$render_s" \
          "$(awk -v n="$((az * el * $2))" -v w="$wall" 'BEGIN {print n / w}')"
      done
    done
  done
  ;;
*) sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'; exit 2 ;;
esac
