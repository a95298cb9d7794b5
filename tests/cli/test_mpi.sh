#!/usr/bin/env bash
# Frames shared among MPI ranks: byte-identical to one process for 1 and 2 ranks, several
# scenarios in one run, and a failing frame that stops every rank, exits non-zero, leaves no
# partial file and can be resumed.
# Usage: test_mpi.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
# As root Open MPI needs to be told; two ranks may exceed the slots of a small machine; inside
# containers the shared-memory transport's cross-memory attach is often not permitted.
export OMPI_MCA_btl_vader_single_copy_mechanism=none
mpirun=(mpirun --allow-run-as-root --oversubscribe)
good="$src/tests/cli/small.json"

same_dataset() {
  for f in "$1"/frames/* "$1/ground_truth.json" "$1/background.pcd"; do
    cmp -s "$f" "$2/${f#"$1"/}" || fail "$(basename "$f") differs between $1 and $2"
  done
  [ "$(ls "$1/frames" | wc -l)" -eq "$(ls "$2/frames" | wc -l)" ] || fail "$1 and $2 hold different frame counts"
}

"$bin" render "$good" --out "$work/plain" --frames 7 --quiet >/dev/null || fail "plain render failed"
for n in 1 2; do
  "${mpirun[@]}" -n "$n" "$bin" render "$good" --out "$work/mpi$n" --frames 7 --quiet >/dev/null 2>"$work/stderr" ||
    fail "mpirun -n $n failed: $(cat "$work/stderr")"
  same_dataset "$work/plain" "$work/mpi$n"
  [ -z "$(find "$work/mpi$n" -name '*.tmp' -o -name '*.log.json' -o -name 'run.json')" ] || fail "-n $n left working files"
done

# Two scenarios in one run: one dataset each, named after the files.
cp "$good" "$work/second.json"
sed -i 's#"../../assets/#"'"$src"'/assets/#g' "$work/second.json"
"${mpirun[@]}" -n 2 "$bin" render "$good" "$work/second.json" --out "$work/batch" --frames 3 --quiet >/dev/null 2>"$work/stderr" ||
  fail "batch render failed: $(cat "$work/stderr")"
[ -s "$work/batch/small/manifest.json" ] && [ -s "$work/batch/second/manifest.json" ] || fail "batch datasets missing"

# Frame 3 fails on rank 1: every rank stops, the run exits non-zero naming the frame, no
# temporary file is left, nothing is published, and one process resumes to the same dataset.
"${mpirun[@]}" -n 2 "$bin" render "$good" --out "$work/broken" --frames 7 --quiet --fail-at-frame 3 >/dev/null 2>"$work/stderr"
[ $? -ne 0 ] || fail "a failed frame did not fail the run"
grep -q "frame 3: failure injected" "$work/stderr" || fail "the failure does not name the frame: $(cat "$work/stderr")"
[ ! -e "$work/broken" ] || fail "a failed run published a dataset"
[ -z "$(find "$work/broken.partial" -name '*.tmp')" ] || fail "a failed run left a temporary file"
"$bin" render "$good" --out "$work/broken" --frames 7 --quiet --resume >/dev/null || fail "resume after a failure failed"
same_dataset "$work/plain" "$work/broken"

# Ctrl-C on mpirun: every rank stops after its current frame, and --resume under mpirun finishes
# the same dataset.
"$bin" render "$good" --out "$work/long" --frames 150 --quiet >/dev/null || fail "plain long render failed"
"${mpirun[@]}" -n 2 "$bin" render "$good" --out "$work/cut" --frames 150 --quiet >/dev/null 2>&1 &
pid=$!
sleep 1
kill -INT "$pid" 2>/dev/null
wait "$pid"
if [ -d "$work/cut.partial" ]; then
  [ -z "$(find "$work/cut.partial" -name '*.tmp')" ] || fail "an interrupted MPI run left a temporary file"
  [ ! -e "$work/cut" ] || fail "an interrupted MPI run published a dataset"
fi
"${mpirun[@]}" -n 2 "$bin" render "$good" --out "$work/cut" --frames 150 --quiet --resume >/dev/null 2>&1 || fail "MPI resume failed"
same_dataset "$work/long" "$work/cut"

if [ "$failures" -eq 0 ]; then echo "mpi: all checks passed"; else echo "mpi: $failures failed"; exit 1; fi
