"""Memory of a ladarsim.render stream: a run holds one frame at a time, whatever its length.

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/python_render_memory.py [SCENARIO]

Each variant runs in a fresh process (so that its peak RSS is its own), named <frames>_<variant>:
  stream  iterate ladarsim.render(SCENARIO, frames=N), keeping nothing;
  list    list(ladarsim.render(...)), holding every frame, for comparison.
Printed per variant: seconds; the largest frame's arrays (points and range image); the peak of
Python's traced allocations during the iteration (tracemalloc, which sees NumPy's arrays); and
the growth of the process's peak RSS over the iteration (VmHWM, from after the scene is loaded).
For a stream the traced peak stays at about one frame's arrays from 30 frames to 300."""
import os
import pathlib
import subprocess
import sys
import time
import tracemalloc

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[1]
DEFAULT_SCENARIO = SOURCE_DIR / "assets" / "scenarios" / "default.json"
VARIANTS = [(30, "stream"), (300, "stream"), (30, "list"), (100, "list")]


def status_kib(key):
    for line in pathlib.Path("/proc/self/status").read_text().splitlines():
        if line.startswith(key + ":"):
            return int(line.split()[1])
    raise KeyError(key)


def frame_bytes(frame):
    return frame.points.nbytes + sum(a.nbytes for a in frame.range_image.values())


def child(scenario, frames, variant):
    import numpy  # noqa: F401 (imported by the first frame otherwise, and counted as if it were one)

    import ladarsim

    stream = ladarsim.render(scenario, frames=frames)  # loads the scene and builds the renderer
    rss_before = status_kib("VmHWM")
    tracemalloc.start()
    started = time.perf_counter()
    largest = 0
    if variant == "stream":
        for frame in stream:
            largest = max(largest, frame_bytes(frame))
            del frame
    else:
        held = list(stream)
        largest = max(frame_bytes(f) for f in held)
    seconds = time.perf_counter() - started
    _, traced_peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    peak_rss = status_kib("VmHWM")
    print(f"{frames}_{variant:<6} {seconds:7.2f} s  largest frame {largest / 1e6:6.2f} MB  "
          f"traced peak {traced_peak / 1e6:7.2f} MB  peak RSS {peak_rss / 1e3:6.1f} MB, "
          f"{(peak_rss - rss_before) / 1e3:+5.1f} MB over the iteration")


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--child":
        child(sys.argv[2], int(sys.argv[3]), sys.argv[4])
        return
    scenario = sys.argv[1] if len(sys.argv) > 1 else str(DEFAULT_SCENARIO)
    print(f"ladarsim.render memory, {scenario}")
    for frames, variant in VARIANTS:
        subprocess.run([sys.executable, __file__, "--child", scenario, str(frames), variant], check=True,
                       env=os.environ)


if __name__ == "__main__":
    main()
