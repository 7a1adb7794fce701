"""`polbrdf.daytime` is the CLI's `daytime` from Python: the example scene swept through a day,
with and without a sensor, gives `daytime.csv` bit for bit (its floats are printed shortest
round-trip, so `float(text)` is the value exactly); bad arguments raise ValueError naming the
keyword."""

from __future__ import annotations

import csv
import subprocess
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from support import NO_CLI, REPO, cli_binary

import polbrdf

CLI = cli_binary()
needs_cli = pytest.mark.skipif(CLI is None, reason=NO_CLI)
EXAMPLES = REPO / "examples"
SCENE = EXAMPLES / "daytime-scene.toml"
SONY = EXAMPLES / "sensors" / "sony-imx250mzr-dofp.toml"


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    if a.shape != b.shape or not np.array_equal(np.isnan(a), np.isnan(b)):
        return False
    keep = ~np.isnan(a)
    return bool(np.array_equal(a[keep].view(np.uint64), b[keep].view(np.uint64)))


#: The CLI's arguments and the same sweep from Python, on coarse grids to keep the suite fast.
CASES: dict[str, tuple[list[str], Any]] = {
    "contrast-range": (
        ["--from", "04:00", "--to", "21:00", "--step-min", "120", "--grid-deg", "10,30",
         "--fixed-view-deg", "30,90"],
        lambda: polbrdf.daytime(
            SCENE, from_="04:00", to="21:00", step_min=120, grid_deg=(10, 30),
            fixed_view_deg=(30, 90),
        ),
    ),
    "detect-times": (
        ["--sensor", str(SONY), "--times", "07:15,12:00,17:45", "--grid-deg", "15,45",
         "--date", "2026-12-21", "--pfa", "1e-4", "--range-limit-m", "30000"],
        lambda: polbrdf.daytime(
            str(SCENE), sensor=SONY, times=["07:15", "12:00", "17:45"], grid_deg=(15, 45),
            date="2026-12-21", pfa=1e-4, range_limit_m=30000,
        ),
    ),
    # No options: the defaults (06:00–18:00 every 30 min, the 5°×10° grid, nadir, the best
    # view unrefined) are the task layer's for both.
    "defaults": ([], lambda: polbrdf.daytime(SCENE)),
}  # fmt: skip


@needs_cli
@pytest.mark.parametrize("case", list(CASES))
def test_daytime_gives_the_cli_s_csv_bit_for_bit(case: str, tmp_path: Path) -> None:
    args, study_of = CASES[case]
    assert CLI is not None
    out = tmp_path / "out"
    r = subprocess.run(
        [str(CLI), "daytime", "--scene", str(SCENE), *args, "--out", str(out)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert r.returncode == 0, r.stderr
    with (out / "daytime.csv").open(newline="") as f:
        rows = list(csv.reader(f))
    study = study_of()
    assert rows[0] == ["date_time", *study.columns]
    assert [r[0] for r in rows[1:]] == list(study.date_time)
    cli = np.array([[float(t) for t in r[1:]] for r in rows[1:]])
    assert same_bits(cli, study.table)
    assert len(study) == len(rows) - 1


def test_the_sun_is_down_at_night_and_the_rows_then_empty() -> None:
    study = polbrdf.daytime(SCENE, times=["01:00", "13:00"], grid_deg=(15, 45))
    assert list(study["sun_up"]) == [0.0, 1.0]
    assert np.isnan(study["best_delta_dolp"][0]) and study["best_delta_dolp"][1] > 0
    assert list(study["local_time_h"]) == [1.0, 13.0]


@pytest.mark.parametrize(
    ("kwargs", "argument"),
    [
        ({"pfa": 1e-3}, "pfa"),
        ({"from_": "25:00"}, "from_"),
        ({"fixed_view_deg": (95.0, 0.0)}, "fixed_view_deg"),
        ({"fixed_view_deg": (10.0,)}, "fixed_view_deg"),
        ({"date": "2026-02-30"}, "date"),
    ],
)
def test_bad_arguments_name_the_keyword(kwargs: dict[str, Any], argument: str) -> None:
    with pytest.raises(ValueError) as e:
        polbrdf.daytime(SCENE, grid_deg=(15, 45), **kwargs)
    assert e.value.argument == argument  # type: ignore[attr-defined]
