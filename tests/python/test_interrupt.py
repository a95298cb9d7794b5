"""Ctrl-C stops a render cleanly: render(out=DIR) leaves its finished frames in DIR.partial, raises
KeyboardInterrupt and continues with resume=True; a stream of frames stops between frames and can
still be iterated afterwards. Run in a child process, whose SIGINT cannot reach pytest."""
import os
import subprocess
import sys
import textwrap

import ladarsim
from conftest import SMALL


def run_python(code, *args):
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code), *map(str, args)], capture_output=True,
                          text=True, timeout=300, env=os.environ)


INTERRUPT_AFTER = """
    import os, pathlib, signal, sys, threading, time
    import ladarsim

    def interrupt_once(path):
        def watch():
            while not path.exists():
                time.sleep(0.002)
            os.kill(os.getpid(), signal.SIGINT)
        threading.Thread(target=watch, daemon=True).start()
"""


def test_ctrl_c_stops_a_render_into_a_directory_which_resume_finishes(tmp_path):
    out = tmp_path / "run"
    result = run_python(INTERRUPT_AFTER + """
    out = pathlib.Path(sys.argv[2])
    interrupt_once(pathlib.Path(str(out) + ".partial") / "frames" / "000000.log.json")
    try:
        ladarsim.render(sys.argv[1], frames=40, out=out, threads=1)
    except KeyboardInterrupt as stopped:
        print(stopped)
        sys.exit(3)
    sys.exit(0)
    """, SMALL, out)
    assert result.returncode == 3, result.stderr
    # It says where the finished frames are and how to continue.
    assert "run.partial" in result.stdout and "resume=True" in result.stdout, result.stdout
    assert not out.exists()
    finished = sorted((tmp_path / "run.partial" / "frames").glob("*.pcd"))
    assert 1 <= len(finished) < 40
    assert not list((tmp_path / "run.partial").rglob("*.tmp"))  # only complete files
    summary = ladarsim.render(SMALL, frames=40, out=out, threads=2, resume=True)
    assert summary["frames"] == 40
    assert len(list((out / "frames").glob("*.pcd"))) == 40
    assert not (tmp_path / "run.partial").exists()


def test_ctrl_c_stops_a_stream_of_frames_between_frames(tmp_path):
    result = run_python(INTERRUPT_AFTER + """
    flag = pathlib.Path(sys.argv[2])
    interrupt_once(flag)
    stream = ladarsim.render(sys.argv[1], frames=40, threads=1)
    seen = []
    try:
        for frame in stream:
            seen.append(frame.index)
            flag.touch()
    except KeyboardInterrupt:
        after = next(stream)  # the stream is intact: the next frame follows the last one handed over
        print(len(seen), seen == list(range(len(seen))), after.index)
        sys.exit(3)
    """, SMALL, tmp_path / "first-frame-seen")
    assert result.returncode == 3, result.stderr
    count, in_order, after = result.stdout.split()
    assert 1 <= int(count) < 40 and in_order == "True"
    assert int(after) >= int(count)
