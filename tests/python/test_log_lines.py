"""The module's warnings and notes are the command line's lines, word for word and on stderr (issue
#34: they came dated and bracketed on stdout): a drone beyond the sensor's max_range_m, rendered
both ways. Run in a child process, whose stderr is its own."""
import json
import os
import subprocess
import sys

from conftest import CLI, SMALL, SOURCE_DIR


def far_drone(tmp_path):
    scenario = json.loads(SMALL.read_text())
    for o in scenario["objects"]:
        o["model"] = str(SOURCE_DIR / "assets" / "models" / os.path.basename(o["model"]))
        if o["class"] == "drone":
            o["trajectory"] = {"type": "fixed", "position_m": [5000, 1, 4]}  # the paper LADAR reaches 3000 m
    path = tmp_path / "far.json"
    path.write_text(json.dumps(scenario))
    return path


def log_lines(text):
    return [line for line in text.splitlines() if line.split(":")[0] in ("warning", "info", "error")]


def test_warnings_are_the_command_lines_lines(tmp_path):
    scenario = far_drone(tmp_path)
    cli = subprocess.run([str(CLI), "render", str(scenario), "--out", str(tmp_path / "cli"), "--frames", "1"],
                         capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    expected = log_lines(cli.stderr)
    assert any("max_range_m" in line for line in expected), cli.stderr
    module = subprocess.run([sys.executable, "-c", "import sys, ladarsim; ladarsim.render(sys.argv[1], frames=1, out=sys.argv[2])",
                             str(scenario), str(tmp_path / "module")], capture_output=True, text=True, env=os.environ)
    assert module.returncode == 0, module.stderr
    assert log_lines(module.stderr) == expected, module.stderr
    assert not log_lines(module.stdout) and "[warning]" not in module.stdout, module.stdout
