"""The sun's position (docs/sun-position.md): ``polbrdf.sun_position`` on SPA's published
example, the same JSON as ``polbrdf sun`` bit for bit, errors naming the keyword, and scene
files placing the sun by date and place through :class:`polbrdf.Sun`."""

from __future__ import annotations

import json
import subprocess

import pytest
from support import NO_CLI, cli_binary

import polbrdf

GOLDEN = {
    "date_time": "2003-10-17T12:30:30-07:00",
    "latitude_deg": 39.742476,
    "longitude_deg": -105.1786,
}
AIR = {"elevation_m": 1830.14, "pressure_hpa": 820.0, "temperature_c": 11.0, "delta_t_s": 67.0}


def test_the_published_example() -> None:
    # Reda & Andreas (2008), Table A5.1 as NREL's spa_tester.c prints it.
    p = polbrdf.sun_position(**GOLDEN, **AIR)
    assert abs(p["zenith_deg"] - 50.111622) < 5e-7
    assert abs(p["azimuth_deg"] - 194.340241) < 5e-7
    assert abs(p["julian_day"] - 2452930.312847) < 5e-7
    assert p["above_horizon"] is True
    # φ = phi0 − azimuth: with φ = 0 to the east, the sun (south-southwest) is near 256°.
    q = polbrdf.sun_position(**GOLDEN, **AIR, phi0_azimuth_deg=90)
    assert abs(q["phi_deg"] - (90 - p["azimuth_deg"] + 360)) < 1e-9


@pytest.mark.skipif(cli_binary() is None, reason=NO_CLI)
def test_the_cli_prints_the_same_numbers() -> None:
    args = [
        str(cli_binary()), "sun", "--date-time", GOLDEN["date_time"],
        "--latitude-deg", str(GOLDEN["latitude_deg"]),
        "--longitude-deg", str(GOLDEN["longitude_deg"]),
        "--elevation-m", "1830.14", "--pressure-hpa", "820", "--temperature-c", "11",
        "--delta-t-s", "67", "--phi0-azimuth-deg", "90",
    ]  # fmt: skip
    out = subprocess.run(args, capture_output=True, text=True, check=True).stdout
    assert json.loads(out) == polbrdf.sun_position(**GOLDEN, **AIR, phi0_azimuth_deg=90)


@pytest.mark.parametrize(
    ("kwargs", "argument"),
    [
        ({"date_time": "2003-10-17T12:30:30"}, "date_time"),
        ({"latitude_deg": 91.0}, "latitude_deg"),
        ({"longitude_deg": float("nan")}, "longitude_deg"),
        ({"pressure_hpa": -1.0}, "pressure_hpa"),
        ({"delta_t_s": float("inf")}, "delta_t_s"),
        ({"phi0_azimuth_deg": float("inf")}, "phi0_azimuth_deg"),
    ],
)
def test_errors_name_the_keyword(kwargs: dict[str, object], argument: str) -> None:
    with pytest.raises(ValueError, match=f"invalid `{argument}`") as e:
        polbrdf.sun_position(**{**GOLDEN, **kwargs})  # type: ignore[arg-type]
    assert e.value.argument == argument  # type: ignore[attr-defined]


def test_a_scene_places_its_sun_by_date_and_place(tmp_path) -> None:  # type: ignore[no-untyped-def]
    scene = polbrdf.Scene(
        wavelength_um=0.55,
        sun=polbrdf.Sun(**GOLDEN, **AIR, phi0_azimuth_deg=90, irradiance=1000),
    )
    path = tmp_path / "s.toml"
    path.write_text(scene.to_toml())
    assert polbrdf.Scene.from_toml(path) == scene
    # Both ways of giving the sun: the reader names the extra key.
    both = polbrdf.Scene(
        wavelength_um=0.55, sun=polbrdf.Sun(zenith_deg=30, **GOLDEN, irradiance=1)
    )
    path.write_text(both.to_toml())
    with pytest.raises(ValueError, match=r"sun\.zenith_deg.*not both"):
        polbrdf.Scene.from_toml(path)
