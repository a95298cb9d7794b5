"""The README's Python example runs as written, from the checkout, and draws its plot."""
import os
import re
import subprocess
import sys

from conftest import SOURCE_DIR


def test_the_readme_example_runs_as_written():
    readme = (SOURCE_DIR / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", readme, flags=re.S)
    assert blocks, "README.md has no ```python example"
    example = blocks[0]
    plot = re.search(r'savefig\("([^"]+)"', example).group(1)
    target = SOURCE_DIR / plot
    if target.exists():
        target.unlink()
    env = dict(os.environ, MPLBACKEND="Agg")
    result = subprocess.run([sys.executable, "-c", example], cwd=SOURCE_DIR, env=env, capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stderr
    assert target.stat().st_size > 10_000  # a drawn PNG
    target.unlink()
