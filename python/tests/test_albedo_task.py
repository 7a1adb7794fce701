"""`polbrdf.albedo` is `polbrdf albedo` from Python: the CLI's table bit for bit, the volume
part of a material without ρ_V is π·ρ_D at every incidence angle, bad arguments name the
keyword."""

from __future__ import annotations

import math
import subprocess
from pathlib import Path

import numpy as np
import pytest
from support import NO_CLI, REPO, cli_binary

import polbrdf

CLI = cli_binary()
SOIL = str(REPO / "examples" / "dry-soil.toml")


@pytest.mark.skipif(CLI is None, reason=NO_CLI)
def test_the_albedo_is_the_cli_s_table_bit_for_bit(tmp_path: Path) -> None:
    out = tmp_path / "albedo.csv"
    r = subprocess.run(
        [str(CLI), "albedo", "--material", SOIL, "--theta-i-deg", "0,30,60,85",
         "--output", str(out)],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    lines = out.read_text().splitlines()
    assert lines[0] == "theta_i_deg,albedo,surface,volume,exceeds_one"
    a = polbrdf.albedo(SOIL, [0, 30, 60, 85])
    for line, k in zip(lines[1:], range(4), strict=True):
        fields = line.split(",")
        got = np.array([float(x) for x in fields[:4]])
        want = np.array([a.theta_i_deg[k], a.albedo[k], a.surface[k], a.volume[k]])
        assert np.array_equal(got.view(np.uint64), want.view(np.uint64)), line
        assert fields[4] == str(bool(a.exceeds_one[k])).lower()


def test_the_volume_part_without_rho_v_is_pi_rho_d(tmp_path: Path) -> None:
    m = polbrdf.Material(n=1.5, sigma_deg=20, rho_d=0.05, rho_v=0.0)
    path = tmp_path / "m.toml"
    path.write_text(m.to_toml())
    a = polbrdf.albedo(path)
    assert list(a.theta_i_deg) == [5.0 * k for k in range(18)]
    # ∫ ρ_D cosθr dΩr = π ρ_D (the Lambertian part), to the quadrature's accuracy.
    assert np.allclose(a.volume, math.pi * 0.05, rtol=1e-9, atol=0)
    assert np.array_equal(a.albedo, a.surface + a.volume)
    assert not a.exceeds_one.any()
    assert np.all((a.surface > 0) & (a.surface < 1))


@pytest.mark.parametrize(
    ("kwargs", "argument"),
    [
        ({"theta_i_deg": 90}, "theta_i_deg"),
        ({"theta_i_deg": []}, "theta_i_deg"),
        ({"wavelength_um": 0}, "wavelength_um"),
        ({"material": "no-such-preset"}, "material"),
    ],
)
def test_a_bad_argument_names_the_keyword(kwargs: dict, argument: str) -> None:
    args = {"material": SOIL} | kwargs
    with pytest.raises(ValueError, match=f"`{argument}`") as e:
        polbrdf.albedo(**args)
    assert e.value.argument == argument  # type: ignore[attr-defined]
