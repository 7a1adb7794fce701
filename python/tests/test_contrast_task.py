"""`polbrdf.contrast` and `polbrdf.hemisphere` are the CLI's `contrast` and `map` from Python:
the README's three contrast examples (visible sun, daylight scene, LWIR scene) give the CLI's
`contrast.csv` and `best.json` bit for bit, `map.csv` likewise; bad arguments raise ValueError
naming the keyword; a material against itself has no contrast anywhere."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from support import NO_CLI, REPO, cli_binary

import polbrdf

CLI = cli_binary()
needs_cli = pytest.mark.skipif(CLI is None, reason=NO_CLI)
EXAMPLES = REPO / "examples"
OLIVE = str(EXAMPLES / "olive-paint.toml")
SOIL = str(EXAMPLES / "dry-soil.toml")


def run_cli(args: list[str], out: Path) -> None:
    assert CLI is not None
    r = subprocess.run(
        [str(CLI), *args, "--out", str(out)], capture_output=True, text=True, check=False
    )
    assert r.returncode == 0, r.stderr


def read_csv(path: Path) -> tuple[list[str], np.ndarray]:
    with path.open() as f:
        header = f.readline().strip().split(",")
    return header, np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


def assert_same_bits(a: np.ndarray, b: np.ndarray) -> None:
    assert a.shape == b.shape
    nan = np.isnan(a)
    assert np.array_equal(nan, np.isnan(b))
    assert np.array_equal(a[~nan].view(np.uint64), b[~nan].view(np.uint64))


#: The README's contrast examples: the CLI's arguments and the same study from Python. The
#: scenes on a 5°×10° grid (as the CLI's own adapter test), to keep the suite fast.
CASES = {
    "visible-sun": (
        ["--target", OLIVE, "--background", SOIL, "--sun-zenith-deg", "50"],
        lambda: polbrdf.contrast(OLIVE, SOIL, polbrdf.Illumination(sun_zenith_deg=50)),
    ),
    "daylight-scene": (
        ["--scene", str(EXAMPLES / "daylight-scene.toml"), "--grid-deg", "5,10"],
        lambda: polbrdf.contrast(None, None, EXAMPLES / "daylight-scene.toml", grid=(5, 10)),
    ),
    "lwir-scene": (
        ["--scene", str(EXAMPLES / "lwir-scene.toml"), "--grid-deg", "5,10"],
        lambda: polbrdf.contrast(None, None, str(EXAMPLES / "lwir-scene.toml"), grid=(5, 10)),
    ),
}


@needs_cli
@pytest.mark.parametrize("case", list(CASES))
def test_the_readme_examples_give_the_cli_s_files_bit_for_bit(case: str, tmp_path: Path) -> None:
    args, study_of = CASES[case]
    run_cli(["contrast", *args], tmp_path / "out")
    study = study_of()
    header, table = read_csv(tmp_path / "out" / "contrast.csv")
    assert tuple(header) == study.columns
    assert_same_bits(table, study.table)
    best = json.loads((tmp_path / "out" / "best.json").read_text())
    assert best == study.best
    assert study.top == best["top"]
    assert study.null_loci == best.get("polarization_null")
    # The maps are the table's columns on the grid, zenith-major.
    n_theta, n_phi = study["delta_dolp"].shape
    assert n_theta * n_phi == len(table) == best["grid"]["directions"]
    assert np.array_equal(np.repeat(study.theta_r_deg, n_phi), table[:, 0])
    assert np.array_equal(np.tile(study.phi_r_deg, n_theta), table[:, 1])
    for k, name in enumerate(header[2:], start=2):
        assert_same_bits(study[name].reshape(-1), table[:, k])


def test_a_scene_object_gives_the_study_of_its_file() -> None:
    path = EXAMPLES / "lwir-scene.toml"
    from_file = polbrdf.contrast(None, None, path, grid=(10, 30))
    from_object = polbrdf.contrast(None, None, polbrdf.Scene.from_toml(path), grid=(10, 30))
    assert_same_bits(from_file.table, from_object.table)
    a, b = dict(from_file.best), dict(from_object.best)
    assert a.pop("scene").pop("file") == str(path)
    assert b.pop("scene").pop("file") == "<polbrdf.Scene>"
    assert a == b
    assert "radiance_difference" in from_file.columns


def test_a_material_against_itself_has_no_contrast_anywhere() -> None:
    s = polbrdf.contrast(OLIVE, OLIVE, polbrdf.Illumination(sun_zenith_deg=40), grid=(5, 10))
    assert np.all(s["delta_dolp"] == 0)
    assert np.all(s["polarization_contrast"] == 0)
    assert np.all(s["aolp_difference_deg"] == 0)
    lit = s["intensity_target"] > 0
    assert lit.any()
    assert np.all(s["intensity_ratio"][lit] == 1)
    assert np.array_equal(s["dolp_target"], s["dolp_background"])
    assert s.best["best"]["delta_dolp"] == 0
    assert s.null_loci is None and s.warnings == ()


def test_the_hemisphere_map_is_the_contrast_s_target() -> None:
    sun = polbrdf.Illumination(sun_zenith_deg=50, sun_azimuth_deg=30)
    m = polbrdf.hemisphere(OLIVE, sun, grid=(5, 10))
    s = polbrdf.contrast(OLIVE, SOIL, sun, grid=(5, 10))
    assert np.array_equal(m.theta_r_deg, s.theta_r_deg)
    assert np.array_equal(m.phi_r_deg, s.phi_r_deg)
    assert np.allclose(m["s0"], s["intensity_target"], rtol=1e-12, atol=0)
    assert np.allclose(m["dolp"], s["dolp_target"], rtol=1e-12, atol=1e-15)
    # DoLP of the map's own Stokes vector, and its peak lies in the plane of incidence's
    # forward half (φr = φi + 180°).
    s0, s1, s2 = m["s0"], m["s1"], m["s2"]
    lit = s0 > 0
    assert np.allclose(m["dolp"][lit], np.hypot(s1, s2)[lit] / s0[lit], rtol=1e-12)
    _, j = np.unravel_index(np.argmax(np.where(lit, m["dolp"], -1)), m["dolp"].shape)
    assert m.phi_r_deg[j] == 210


@needs_cli
def test_the_hemisphere_map_is_the_cli_s_map_csv(tmp_path: Path) -> None:
    run_cli(
        ["map", "--material", SOIL, "--sun-zenith-deg", "35", "--stokes", "1,0.5,0,0",
         "--grid-deg", "5,10"],
        tmp_path / "out",
    )  # fmt: skip
    header, table = read_csv(tmp_path / "out" / "map.csv")
    m = polbrdf.hemisphere(
        SOIL, polbrdf.Illumination(sun_zenith_deg=35, stokes=(1, 0.5, 0, 0)), grid=(5, 10)
    )
    assert tuple(header) == m.columns
    assert_same_bits(table, m.table)


def flagged(name: str) -> np.ndarray:
    """The 1° grid zeniths where `name`'s emissivity leaves [0, 1] (its validity flag)."""
    t = np.arange(90.0)
    return t[~polbrdf.emissivity(polbrdf.Material.preset(name), t).valid]


@needs_cli
def test_the_invalid_zeniths_are_those_the_cli_marks(tmp_path: Path) -> None:
    # Paint reflects more than it receives seen near grazing; glass does not.
    paint, glass = flagged("paint"), flagged("glass")
    assert paint.size > 0 and paint[0] > 80
    light = polbrdf.Illumination(sun_zenith_deg=40)
    m = polbrdf.hemisphere("paint", light, grid=(1, 30))
    assert np.array_equal(m.invalid_zeniths_deg, paint)
    s = polbrdf.contrast("paint", "glass", light, grid=(1, 30))
    assert np.array_equal(s.invalid_zeniths_target_deg, paint)
    assert np.array_equal(s.invalid_zeniths_background_deg, glass)
    assert np.array_equal(s.invalid_zeniths_deg, np.union1d(paint, glass))
    # The CLI's summary of both jobs (on standard error) names the same zeniths.
    assert CLI is not None
    for args, line in [
        (["map", "--material", "paint"], "model flagged"),
        (["contrast", "--target", "paint", "--background", "glass"], "target model flagged"),
    ]:
        r = subprocess.run(
            [str(CLI), *args, "--sun-zenith-deg", "40", "--grid-deg", "1,30",
             "--out", str(tmp_path / args[0])],
            capture_output=True, text=True, check=True,
        )  # fmt: skip
        assert (
            f"{line} invalid (emissivity outside [0, 1]) at {paint.size} zenith(s) from "
            f"θr = {paint[0]:g}°"
        ) in r.stderr, r.stderr
        assert r.stdout == "", "the summary is on standard error, the results in --out"


def sun() -> polbrdf.Illumination:
    return polbrdf.Illumination(sun_zenith_deg=50)


@pytest.mark.parametrize(
    ("call", "argument"),
    [
        (lambda: polbrdf.contrast(OLIVE, SOIL, sun(), top=0), "top"),
        (lambda: polbrdf.contrast(OLIVE, SOIL, sun(), rank_by="x"), "rank_by"),  # type: ignore
        (lambda: polbrdf.contrast(OLIVE, SOIL, sun(), max_zenith_deg=90), "max_zenith_deg"),
        (
            lambda: polbrdf.contrast(OLIVE, SOIL, sun(), min_separation_deg=-1),
            "min_separation_deg",
        ),
        (lambda: polbrdf.contrast(OLIVE, SOIL, sun(), wavelength_um=-1), "wavelength_um"),
        (lambda: polbrdf.contrast(None, SOIL, sun()), "target"),
        (lambda: polbrdf.contrast(OLIVE, "no-such-preset", sun()), "background"),
        (
            lambda: polbrdf.contrast(None, None, EXAMPLES / "lwir-scene.toml", band_step_um=0.1),
            "band_step_um",
        ),
        (lambda: polbrdf.hemisphere("no-such-preset", sun()), "material"),
    ],
)
def test_a_bad_argument_raises_value_error_naming_the_keyword(call, argument: str) -> None:
    with pytest.raises(ValueError, match=f"`{argument}`") as e:
        call()
    assert e.value.argument == argument  # type: ignore[attr-defined]


def test_a_bad_source_or_grid_raises_value_error() -> None:
    with pytest.raises(ValueError, match="zenith"):
        polbrdf.contrast(OLIVE, SOIL, polbrdf.Illumination(sun_zenith_deg=95))
    with pytest.raises(ValueError, match="step"):
        polbrdf.contrast(OLIVE, SOIL, sun(), grid=(0, 2))
    with pytest.raises(ValueError, match="`stokes`"):
        polbrdf.contrast(OLIVE, SOIL, polbrdf.Illumination(sun_zenith_deg=50, stokes=(1, 0)))
    with pytest.raises(TypeError, match="`source`"):
        polbrdf.contrast(OLIVE, SOIL, 50)  # type: ignore[arg-type]
    with pytest.raises(FileNotFoundError):
        polbrdf.contrast(None, None, "no-such-scene.toml")


@pytest.mark.skipif(importlib.util.find_spec("xarray") is None, reason="xarray is not installed")
def test_to_xarray_holds_the_maps_on_the_grid() -> None:
    s = polbrdf.contrast(OLIVE, SOIL, sun(), grid=(10, 30))
    ds = s.to_xarray()
    assert dict(ds.sizes) == {"theta_r_deg": len(s.theta_r_deg), "phi_r_deg": len(s.phi_r_deg)}
    assert set(ds.data_vars) == set(s.columns[2:])
    assert np.array_equal(ds["delta_dolp"].values, s["delta_dolp"])
    assert np.array_equal(ds["theta_r_deg"].values, s.theta_r_deg)
    assert json.loads(ds.attrs["best_json"]) == s.best
    best = s.best["best"]
    at = ds.sel(theta_r_deg=10, phi_r_deg=180)
    assert at["dolp_target"] == s["dolp_target"][1, 6]
    assert best["delta_dolp"] == s.top[0]["delta_dolp"]


@pytest.mark.skipif(
    importlib.util.find_spec("matplotlib") is None, reason="matplotlib is not installed"
)
def test_the_contrast_study_example_runs_end_to_end(tmp_path: Path) -> None:
    script = REPO / "python" / "examples" / "contrast_study.py"
    out = tmp_path / "figures"
    r = subprocess.run(
        [sys.executable, str(script), str(out), "--grid", "5,10"],
        capture_output=True, text=True, check=False, cwd=tmp_path,
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    for name in ("visible_contrast.png", "lwir_contrast.png"):
        assert (out / name).stat().st_size > 20_000, name
    # It prints the studies' best directions: the first is the task's.
    visible = polbrdf.contrast(OLIVE, SOIL, sun(), grid=(5, 10))
    assert f"{visible.top[0]['delta_dolp']:+8.4f}" in r.stdout
    assert "both lose their polarization at 250.00 K" in r.stdout
