#!/usr/bin/env bash
# Rendering or importing onto an earlier dataset replaces only what ladarsim wrote there (its
# frames, manifest, ground truth, background map and the detections derived from them: what its
# .ladarsim-owned lists); the user's own files beside them survive and the command says which it
# kept. A file of theirs inside frames/ is refused before anything is rendered.
# Usage: test_rerender_keeps_user_files.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
good="$src/tests/cli/small.json"

"$bin" render "$good" --out "$work/d" --frames 2 --quiet >/dev/null || fail "first render failed"
echo "my notes" >"$work/d/NOTES.txt"
mkdir -p "$work/d/analysis" && echo 42 >"$work/d/analysis/result.txt"
"$bin" detect "$work/d" >/dev/null 2>&1 || fail "detect failed"
"$bin" render "$good" --out "$work/d" --frames 1 --quiet >"$work/stdout" 2>"$work/stderr" || fail "re-render failed: $(cat "$work/stderr")"
[ "$(cat "$work/d/NOTES.txt" 2>/dev/null)" = "my notes" ] || fail "NOTES.txt was lost in a re-render"
[ "$(cat "$work/d/analysis/result.txt" 2>/dev/null)" = 42 ] || fail "analysis/ was lost in a re-render"
[ "$(ls "$work/d/frames" | wc -l)" -eq 2 ] || fail "the frames were not rebuilt: $(ls "$work/d/frames")"
[ -s "$work/d/manifest.json" ] || fail "no manifest after the re-render"
[ ! -e "$work/d/detections-vrbnn.json" ] || fail "detections of the earlier dataset survived beside the new frames"
grep -q "NOTES.txt" "$work/stdout" && grep -q "analysis/" "$work/stdout" || fail "the summary does not say which files were kept: $(cat "$work/stdout")"
[ ! -e "$work/d.partial" ] && [ ! -e "$work/d.old" ] || fail "staging directories left behind"

# A file of the user's inside frames/: refused before rendering, one line naming it, nothing touched.
echo mine >"$work/d/frames/mine.txt"
before=$(ls -R "$work/d" | md5sum)
"$bin" render "$good" --out "$work/d" --frames 1 >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] || fail "a user file in frames/ gave exit $rc, expected 2"
[ "$(wc -l <"$work/stderr")" -eq 1 ] && grep -q "frames/mine.txt" "$work/stderr" || fail "no one-line refusal naming frames/mine.txt: $(cat "$work/stderr")"
grep -q "^frame " "$work/stderr" && fail "rendering started before the refusal"
[ "$before" = "$(ls -R "$work/d" | md5sum)" ] || fail "the refused directory was changed"
rm -f "$work/d/frames/mine.txt"

# The importers follow the same rule, onto a recorded dataset (a rendered one they refuse: see
# test_nothing_lost.sh).
pcap="$shared_data/vlp16/velodyne_vlp16.pcap"
if [ -f "$pcap" ]; then
  "$bin" import-velodyne "$pcap" --out "$work/r" >/dev/null 2>"$work/stderr" || fail "import failed: $(cat "$work/stderr")"
  echo "my notes" >"$work/r/NOTES.txt"
  "$bin" import-velodyne "$pcap" --out "$work/r" >"$work/stdout" 2>"$work/stderr" || fail "import onto an earlier import failed: $(cat "$work/stderr")"
  [ "$(cat "$work/r/NOTES.txt" 2>/dev/null)" = "my notes" ] || fail "NOTES.txt was lost in an import"
  grep -q "NOTES.txt" "$work/stdout" || fail "the import does not say which files were kept: $(cat "$work/stdout")"
else
  skip "$pcap absent, import not checked"
fi

finish rerender
