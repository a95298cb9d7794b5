#!/usr/bin/env bash
# `cmake --install` gives a program that needs neither its source nor its build tree. Installed into
# a prefix, the prefix then moved elsewhere, and run from an empty directory that is also HOME, it
# renders, detects, evaluates with a plot to a path holding a quote and a space, draws the preview,
# renders the installed campaign spec with its card and serves the viewer's page and three.js;
# under strace it touches no file of the source or build tree, and no string of its own names them.
# A failing plot script is one line of error.
# Usage: test_install.sh LADARSIM_BINARY SOURCE_DIR BUILD_DIR
source "$(dirname "$0")/harness.sh"
build=$(realpath "$3")
src=$(realpath "$src")
py=/usr/bin/python3
if ! $py -c "import matplotlib" 2>/dev/null; then
  echo "note: python3-matplotlib absent (scripts/setup.sh); the installed program not checked"; exit 0
fi
command -v strace >/dev/null || { fail "strace is missing (scripts/setup.sh installs it)"; exit 1; }

cmake --install "$build" --prefix "$work/prefix" >"$work/install.log" 2>&1 || fail "cmake --install failed: $(tail -3 "$work/install.log")"
mkdir -p "$work/elsewhere"
mv "$work/prefix" "$work/elsewhere/p q"
prefix="$work/elsewhere/p q"
prog="$prefix/bin/ladarsim"
[ -x "$prog" ] || { fail "no bin/ladarsim in the prefix: $(cat "$work/install.log")"; exit 1; }

# No path of the source or build tree compiled in (the debugging information names sources, and
# is not what the program reads).
objcopy -O binary --only-section=.rodata "$prog" "$work/rodata"
grep -qaF "$src" "$work/rodata" && fail "the program's constants name the source tree $src"

run="$work/empty"
mkdir -p "$run"
cd "$run" || exit 1
export HOME=$run
# The small test scenario, naming the installed models.
$py - "$src/tests/cli/small.json" "$prefix/share/ladarsim/models" "$run/small.json" <<'PY'
import json, os, sys
scenario = json.load(open(sys.argv[1]))
for o in scenario["objects"]:
    o["model"] = os.path.join(sys.argv[2], os.path.basename(o["model"]))
json.dump(scenario, open(sys.argv[3], "w"))
PY
plot_dir="$run/it's here \$HOME"
mkdir -p "$plot_dir"
# Every file the program and its scripts open, stat or run, from here on.
traced() { strace -f -qq -e trace=%file -o "$work/trace.$1" "$prog" "$@"; }
traced render small.json --out d --frames 3 --quiet >/dev/null 2>"$work/stderr" || fail "render failed: $(cat "$work/stderr")"
traced detect d --method vrbnn --lambda 180 >/dev/null 2>"$work/stderr" || fail "detect failed: $(cat "$work/stderr")"
traced eval d --detections d/detections-vrbnn.json --plot "$plot_dir/e.png" >/dev/null 2>"$work/stderr" ||
  fail "eval --plot failed: $(cat "$work/stderr")"
head -c 8 "$plot_dir/e.png" 2>/dev/null | grep -qa PNG || fail "eval --plot wrote no PNG to $plot_dir/e.png"
[ "$(ls "$plot_dir")" = e.png ] || fail "eval --plot left more than its PNG: $(ls "$plot_dir")"
traced preview d --frames 2 >/dev/null 2>"$work/stderr" || fail "preview failed: $(cat "$work/stderr")"
head -c 8 d/preview.png 2>/dev/null | grep -qa PNG || fail "preview wrote no d/preview.png"
traced campaign "$prefix/share/ladarsim/campaigns/drones.json" --out c --sequences 1 --frames 1 --quiet >/dev/null 2>"$work/stderr" ||
  fail "campaign of the installed spec failed: $(cat "$work/stderr")"
head -c 8 c/card-targets.png 2>/dev/null | grep -qa PNG || fail "campaign drew no card plot c/card-targets.png"
"$prog" bench --help >"$work/bench-help" 2>&1
grep -qF "$prefix/share/ladarsim/scenarios/default.json" "$work/bench-help" ||
  fail "bench's default scenario is not the installed one: $(grep -A1 -- --scenario "$work/bench-help")"
[ -f "$prefix/share/ladarsim/scenarios/default.json" ] || fail "the default scenario is not installed"

# The viewer: its page, its script and three.js with the addon it imports.
strace -f -qq -e trace=%file -o "$work/trace.view" "$prog" view d --no-browser >"$work/view.log" 2>&1 &
server=$!
trap 'pkill -P $server 2>/dev/null; wait $server 2>/dev/null; rm -rf "$work"' EXIT
for _ in $(seq 100); do grep -q http "$work/view.log" && break; sleep 0.1; done
url=$(grep -o 'http://[^ ]*' "$work/view.log")
[ -n "$url" ] || fail "view printed no URL: $(cat "$work/view.log")"
[ -n "$url" ] && $py - "$url" <<'PY' || fail "the viewer's files are not served"
import sys, urllib.request
url = sys.argv[1]
for path, text in (("", b"importmap"), ("viewer/viewer.js", b"OrbitControls"),
                   ("three/build/three.module.js", b"REVISION"),
                   ("three/examples/jsm/controls/OrbitControls.js", b"class OrbitControls")):
    body = urllib.request.urlopen(url + path, timeout=10).read()
    if text not in body:
        sys.exit(f"{url}{path}: {len(body)} bytes without {text!r}")
PY
# strace holds off fatal signals while it traces: the program itself is stopped.
pkill -P $server 2>/dev/null
wait $server 2>/dev/null

# Nothing of the source or build tree was touched.
if grep -hF -e "\"$src/" -e "\"$src\"" -e "\"$build/" "$work"/trace.* >"$work/touched"; then
  fail "the installed program touched the source or build tree: $(head -3 "$work/touched")"
fi
grep -qF "$prefix/share/ladarsim/scripts/plot_eval.py" "$work/trace.eval" || fail "eval ran no installed plot script"
grep -qF "$prefix/share/ladarsim/scripts/plot_campaign.py" "$work/trace.campaign" || fail "campaign ran no installed plot script"

# A failing script: one line naming it and its last message.
mkdir -p "$work/broken/matplotlib"
echo 'raise ImportError("this matplotlib is broken")' >"$work/broken/matplotlib/__init__.py"
PYTHONPATH="$work/broken" "$prog" eval d --detections d/detections-vrbnn.json --plot "$run/x.png" >/dev/null 2>"$work/stderr"
rc=$?
[ "$rc" -ne 0 ] || fail "a failing plot script exited 0"
[ "$(wc -l <"$work/stderr")" -eq 1 ] && grep -q "^error: plot_eval.py failed.*this matplotlib is broken" "$work/stderr" ||
  fail "a failing plot script is not one line naming it: $(cat "$work/stderr")"

if [ "$failures" -eq 0 ]; then echo "install: all checks passed"; else echo "install: $failures failed"; exit 1; fi
