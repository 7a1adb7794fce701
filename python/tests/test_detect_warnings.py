"""The setup warnings of a detection study and of a day's sweep are the task layer's values:
Python returns them (``study.warnings``) as the CLI prints them (``polbrdf detect: note: …``),
and best.json lists them — here a visible daylight scene seen by the 8–12 µm polarimeter (its
surfaces have no temperature, and it is written for 0.55 µm) and a camera that saturates."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from support import NO_CLI, REPO, cli_binary

import polbrdf

CLI = cli_binary()
needs_cli = pytest.mark.skipif(CLI is None, reason=NO_CLI)
EXAMPLES = REPO / "examples"
DAYLIGHT = EXAMPLES / "detect-daylight-scene.toml"
SONY = EXAMPLES / "sensors" / "sony-imx250mzr-dofp.toml"
BOLOMETER = EXAMPLES / "sensors" / "lwir-microbolometer-dofp.toml"


def notes(command: str, stderr: str) -> list[str]:
    prefix = f"polbrdf {command}: note: "
    return [line[len(prefix) :] for line in stderr.splitlines() if line.startswith(prefix)]


def test_a_visible_scene_seen_in_the_thermal_infrared_warns() -> None:
    study = polbrdf.detect(DAYLIGHT, BOLOMETER, theta_deg=30, ranges_m=[500])
    assert sum("has no temperature_k" in w for w in study.warnings) == 2
    assert sum("outside the band of the sensor" in w for w in study.warnings) == 1
    assert list(study.best["warnings"]) == list(study.warnings)


@needs_cli
def test_the_cli_prints_the_warnings_python_returns(tmp_path: Path) -> None:
    assert CLI is not None
    study = polbrdf.detect(DAYLIGHT, BOLOMETER, theta_deg=30, ranges_m=[500])
    r = subprocess.run(
        [str(CLI), "detect", "--scene", str(DAYLIGHT), "--sensor", str(BOLOMETER),
         "--theta-deg", "30", "--ranges-m", "500", "--out", str(tmp_path / "out")],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert notes("detect", r.stderr) == list(study.warnings)


def test_a_sweep_returns_its_warnings_once(tmp_path: Path) -> None:
    text = SONY.read_text()
    line = next(x for x in text.splitlines() if x.startswith("integration_time_ms"))
    long = tmp_path / "long.toml"
    long.write_text(text.replace(line, "integration_time_ms = 20"))
    day = polbrdf.daytime(
        EXAMPLES / "daytime-scene.toml", sensor=long, times=["10:00", "13:00", "23:00"],
        grid_deg=(30, 90), fixed_view_deg=(30, 0), range_limit_m=20000,
    )  # fmt: skip
    assert len(day.warnings) == 1
    assert "at some views at 2 of 3 times" in day.warnings[0]
