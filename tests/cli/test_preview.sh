#!/usr/bin/env bash
# scripts/preview.py: one colour scale per dataset (one colour bar), false alarms neither stretch
# the scale nor the axes, objects and their labels in their class's colour on a legible backing.
# A false alarm far out (2900 m, outside the field) is added to a rendered frame.
# Usage: test_preview.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
py=/usr/bin/python3
if ! $py -c "import matplotlib, numpy" 2>/dev/null; then
  skip "python3-matplotlib absent (scripts/setup.sh --plots); preview not checked"; finish preview
fi
"$bin" render "$src/tests/cli/small.json" --out "$work/d" --frames 4 --quiet >/dev/null 2>&1 || fail "render failed"
$py - "$src/scripts" "$work/d" <<'PY' || fail "preview.py does not draw what it should"
import importlib.util, sys
import numpy as np
spec = importlib.util.spec_from_file_location("preview", sys.argv[1] + "/preview.py")
preview = importlib.util.module_from_spec(spec); spec.loader.exec_module(preview)
dataset = sys.argv[2]
# A false alarm 2900 m away, 20 deg off the field, into frame 1.
path = f"{dataset}/frames/000001.pcd"
points = preview.read_pcd(path)
extra = np.zeros(1, dtype=points.dtype)
extra["x"], extra["y"], extra["z"] = 2725.0, 990.0, 0.0
extra["range_m"], extra["beam_az"], extra["source"], extra["object_id"] = 2900.0, np.radians(20), 2, 4294967295
both = np.concatenate([points, extra])
raw = open(path, "rb").read()
head = raw[:raw.index(b"DATA binary\n")].decode()
head = head.replace(f"WIDTH {len(points)}", f"WIDTH {len(both)}").replace(f"POINTS {len(points)}", f"POINTS {len(both)}")
open(path, "wb").write(head.encode() + b"DATA binary\n" + both.tobytes())

fig = preview.draw(dataset, 4)
bad = []
bars = [a for a in fig.axes[8:] if "range" in a.get_ylabel()]
if len(bars) != 1 or len(fig.axes) != 9: bad.append(f"{len(bars)} colour bars, expected one for the dataset")
norms = {(c.norm.vmin, c.norm.vmax) for a in fig.axes[:8] for c in a.collections if c.get_array() is not None}
if len(norms) != 1: bad.append(f"several colour scales: {norms}")
elif max(v for _, v in norms) > 1000: bad.append(f"the false alarm stretches the scale: {norms}")
whole = [r[0] for r in np.array(fig.axes[:8]).reshape(4, 2)]
for a in whole:
    lo, hi = sorted(a.get_xlim())
    if hi - lo > 5: bad.append(f"the azimuth axis spans {lo:.1f} to {hi:.1f} deg")
labels = [t for a in whole for t in a.texts]
for t in labels:
    cls = t.get_text().split()[0]
    colour = preview.CLASS_COLOURS.get(cls)
    if colour is None or t.get_color() != colour: bad.append(f"label '{t.get_text()}' not in its class's colour")
    if t.get_bbox_patch() is None or t.get_fontsize() < 9: bad.append(f"label '{t.get_text()}' not legible")
if not any(t.get_text().startswith("building") for t in labels): bad.append("the building is not labelled")
if bad: print("\n".join(sorted(set(bad)))); sys.exit(1)
PY
# And as a user runs it: the program runs its own copy of the script.
rm -f "$work/d/preview.png"
"$bin" preview "$work/d" >/dev/null 2>"$work/stderr" || fail "ladarsim preview failed: $(cat "$work/stderr")"
[ -s "$work/d/preview.png" ] || fail "no preview.png"
grep -qx "preview.png" "$work/d/.ladarsim-owned" || fail "preview.png is not listed as ladarsim's: a re-render would keep it stale"
$py "$src/scripts/preview.py" "$work/d" >/dev/null 2>"$work/stderr" || fail "preview.py could not replace its own preview.png"

# What goes wrong is one line in the user's terms, never a traceback.
one_line() {
  local what=$1 rc=$2
  [ "$rc" -ne 0 ] || fail "$what: exit 0"
  [ "$(wc -l <"$work/stderr")" -eq 1 ] && ! grep -q Traceback "$work/stderr" || fail "$what: not one line: $(cat "$work/stderr")"
}
$py "$src/scripts/preview.py" "$work/nowhere" >/dev/null 2>"$work/stderr"
one_line "a missing directory" $?
mkdir -p "$work/recorded/frames" && cp "$work/d/frames/000000.pcd" "$work/recorded/frames/" && cp "$work/d/manifest.json" "$work/recorded/"
$py "$src/scripts/preview.py" "$work/recorded" >/dev/null 2>"$work/stderr"
one_line "a recorded dataset" $?
rm -f "$work/d/preview.png"
chmod a-w "$work/d"
if [ ! -w "$work/d" ]; then
  $py "$src/scripts/preview.py" "$work/d" >/dev/null 2>"$work/stderr"
  one_line "a read-only dataset" $?
fi
chmod u+w "$work/d"
# A preview.png of the user's in a dataset (not on its .ladarsim-owned list): kept.
"$bin" render "$src/tests/cli/small.json" --out "$work/e" --frames 1 --quiet >/dev/null 2>&1 || fail "render failed"
echo mine >"$work/e/preview.png"
$py "$src/scripts/preview.py" "$work/e" >/dev/null 2>"$work/stderr"
one_line "the user's preview.png" $?
[ "$(cat "$work/e/preview.png")" = mine ] || fail "preview.py replaced the user's preview.png"
# And through the program, which passes --force on.
"$bin" preview "$work/e" >/dev/null 2>"$work/stderr"
one_line "ladarsim preview over the user's preview.png" $?
grep -q -- "--force" "$work/stderr" || fail "the refusal does not say --force replaces it: $(cat "$work/stderr")"
[ "$(cat "$work/e/preview.png")" = mine ] || fail "ladarsim preview replaced the user's preview.png"
"$bin" preview "$work/e" --force >/dev/null 2>"$work/stderr" || fail "ladarsim preview --force failed: $(cat "$work/stderr")"
[ "$(cat "$work/e/preview.png")" != mine ] || fail "ladarsim preview --force kept the old preview.png"

if [ "$failures" -eq 0 ]; then echo "preview: all checks passed"; else echo "preview: $failures failed"; exit 1; fi
