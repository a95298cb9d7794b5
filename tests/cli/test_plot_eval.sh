#!/usr/bin/env bash
# scripts/plot_eval.py: with no detections the L2 panel and its title say so (no axis about 0 m, no
# "nan"), the supervised run's re-initialisations (IoU 1 by construction) do not squash the real
# IoU curve, and eval's scores, which have no supervised run, plot without one.
# Usage: test_plot_eval.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
py=/usr/bin/python3
if ! $py -c "import matplotlib" 2>/dev/null; then
  skip "python3-matplotlib absent (scripts/setup.sh --plots); plot_eval not checked"; finish plot_eval
fi
$py - "$src/scripts/plot_eval.py" "$work" <<'PY' || fail "plot_eval.py does not draw what it should"
import importlib.util, json, sys
spec = importlib.util.spec_from_file_location("plot_eval", sys.argv[1])
plot_eval = importlib.util.module_from_spec(spec); spec.loader.exec_module(plot_eval)
def scores(l2, iou, supervised, initialised):
    return {"method": "vrbnn", "mean_l2_m": None if all(v is None for v in l2) else 0.1, "mean_iou": 0.05, "eao": 0.1,
            "failures": 2, "per_frame": [{"frame": k, "found": l2[k] is not None, "predicted": False, "iou": iou[k],
                                          "l2_m": l2[k], "supervised_iou": supervised[k], "initialised": initialised[k]}
                                         for k in range(len(l2))]}
bad = []
n = 20
# No detection at all.
e = scores([None] * n, [0.0] * n, [1.0 if k % 6 == 0 else 0.0 for k in range(n)], [k % 6 == 0 for k in range(n)])
fig = plot_eval.draw(e)
l2 = fig.axes[0]
if l2.get_ylim()[0] < 0: bad.append(f"with no detections the L2 axis spans {l2.get_ylim()}")
if not any("no detections" in t.get_text() for t in l2.texts): bad.append("with no detections the L2 panel does not say so")
if "nan" in l2.get_title().lower(): bad.append(f"with no detections the title says nan: {l2.get_title()}")
# Real IoUs about 0.1, supervised resets at 1.0.
iou = [0.1 + 0.02 * (k % 3) for k in range(n)]
e = scores([0.2] * n, iou, [1.0 if k % 6 == 0 else iou[k] for k in range(n)], [k % 6 == 0 for k in range(n)])
fig = plot_eval.draw(e)
top = fig.axes[1].get_ylim()[1]
if top > 0.5: bad.append(f"the IoU axis reaches {top}: the resets squash the real curve")
json.dump(e, open(sys.argv[2] + "/eval.json", "w"))
# eval's scores of a file: no supervised run, nothing of one drawn.
del e["eao"], e["failures"]
for f in e["per_frame"]: del f["supervised_iou"], f["initialised"]
fig = plot_eval.draw(e)
if len(fig.axes[1].lines) != 1: bad.append(f"without a supervised run the IoU panel draws {len(fig.axes[1].lines)} curves")
if bad: print("\n".join(bad)); sys.exit(1)
PY
$py "$src/scripts/plot_eval.py" "$work/eval.json" "$work/eval.png" || fail "plot_eval.py failed"
[ -s "$work/eval.png" ] || fail "no eval.png"
if [ "$failures" -eq 0 ]; then echo "plot_eval: all checks passed"; else echo "plot_eval: $failures failed"; exit 1; fi
