"""`pip install ./python` installs the `polbrdf` command: the Rust CLI's own code
(`polbrdf_cli::main_with_args` through `polbrdf._polbrdf.cli_main`), so a Python user has the
command line. Its output and exit codes are the binary's."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def command() -> list[str]:
    """The installed console script, or the module (an in-place `maturin develop` has both)."""
    exe = shutil.which("polbrdf", path=os.path.dirname(sys.executable))
    return [exe] if exe else [sys.executable, "-m", "polbrdf._cli"]


def test_the_console_script_is_installed_next_to_the_interpreter() -> None:
    assert shutil.which("polbrdf", path=os.path.dirname(sys.executable)), (
        "pip install ./python should install the `polbrdf` command into the environment"
    )


def test_eval_through_the_python_command_matches_the_core(tmp_path: Path) -> None:
    geometry = tmp_path / "g.csv"
    geometry.write_text("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n60,0,60,180\n30,0,45,90\n")
    out = subprocess.run(
        [*command(), "eval", "--material", "paint", "--input", str(geometry)],
        capture_output=True,
        text=True,
        check=True,
    )
    lines = out.stdout.strip().splitlines()
    assert lines[0].split(",")[4:7] == ["brdf", "dolp", "aolp_deg"]
    import polbrdf

    paint = polbrdf.Material.preset("paint")
    for line, (ti, pi, tr, pr) in zip(lines[1:], [(60, 0, 60, 180), (30, 0, 45, 90)]):
        brdf, dolp = (float(v) for v in line.split(",")[4:6])
        assert brdf == polbrdf.brdf(paint, ti, pi, tr, pr)
        assert dolp == polbrdf.dolp(paint, ti, pi, tr, pr)


def test_exit_codes_are_the_cli_contract(tmp_path: Path) -> None:
    # 2: usage error (unknown option); 3: invalid input data, naming the file and line.
    usage = subprocess.run(
        [*command(), "eval", "--bogus"], check=False, capture_output=True, text=True
    )
    assert usage.returncode == 2 and "--bogus" in usage.stderr
    bad = tmp_path / "bad.csv"
    bad.write_text("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n60,0,x,180\n")
    data = subprocess.run(
        [*command(), "eval", "--material", "paint", "--input", str(bad)],
        check=False,
        capture_output=True,
        text=True,
    )
    assert data.returncode == 3 and "bad.csv" in data.stderr and "bad.csv:2" in data.stderr


def test_main_exits_with_the_commands_code() -> None:
    # In a child process: the CLI installs a process's signal cleanup and panic hook.
    code = "from polbrdf import _cli; _cli.main(['materials', '--show', 'no-such-preset'])"
    unknown = subprocess.run(
        [sys.executable, "-c", code], check=False, capture_output=True, text=True
    )
    assert unknown.returncode == 3 and "no-such-preset" in unknown.stderr
    version = subprocess.run([*command(), "--version"], check=False, capture_output=True, text=True)
    assert version.returncode == 0 and version.stdout.startswith("polbrdf ")
