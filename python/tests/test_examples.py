"""The example scripts run (the plot is made when matplotlib is installed)."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

from support import REPO

EXAMPLES = REPO / "python" / "examples"


def test_dolp_map(tmp_path: Path) -> None:
    out = tmp_path / "map.png"
    r = subprocess.run(
        [sys.executable, str(EXAMPLES / "dolp_map.py"), "--theta-i", "45", "--out", str(out)],
        capture_output=True,
        text=True,
        check=False,
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    if importlib.util.find_spec("matplotlib") is None:
        assert "matplotlib is not installed" in r.stdout
    else:
        assert out.stat().st_size > 10_000


def test_bench_script_runs_small() -> None:
    r = subprocess.run(
        [sys.executable, str(EXAMPLES / "bench.py"), "2000", "1"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert r.returncode == 0, r.stderr
    assert "python mueller" in r.stdout
