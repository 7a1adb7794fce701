"""`polbrdf.detect` and `polbrdf.detect_frame` are the CLI's `detect` and `detect --frame` from
Python: the example scenes with the example sensors on a coarse grid give `detect.csv` and
`best.json` bit for bit (the CSV's floats are printed shortest round-trip, so `float(text)` is
the value exactly), the frame's `.npy` arrays likewise for the same seed; bad arguments raise
ValueError naming the keyword."""

from __future__ import annotations

import csv
import importlib.util
import json
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
DAYLIGHT = EXAMPLES / "detect-daylight-scene.toml"
LWIR = EXAMPLES / "detect-lwir-scene.toml"
SONY = EXAMPLES / "sensors" / "sony-imx250mzr-dofp.toml"
BOLOMETER = EXAMPLES / "sensors" / "lwir-microbolometer-dofp.toml"


def run_cli(args: list[str], out: Path) -> None:
    assert CLI is not None
    r = subprocess.run(
        [str(CLI), "detect", *args, "--out", str(out)], capture_output=True, text=True, check=False
    )
    assert r.returncode == 0, r.stderr


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    if a.shape != b.shape or not np.array_equal(np.isnan(a), np.isnan(b)):
        return False
    keep = ~np.isnan(a)
    return bool(np.array_equal(a[keep].view(np.uint64), b[keep].view(np.uint64)))


def assert_study_is_the_cli_s(study: polbrdf.DetectStudy, out: Path) -> None:
    with (out / "detect.csv").open(newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    assert tuple(header) == study.columns
    assert len(body) == len(study) > 0
    columns = {name: [r[k] for r in body] for k, name in enumerate(header)}
    numeric = [*header[:11], "max_range_sigma_m", "max_range_lo95_m", "max_range_hi95_m"]
    for name in numeric:
        cli = np.array([float(t) if t else np.nan for t in columns[name]])
        assert same_bits(cli, study[name]), name
    assert columns["feature"] == list(study["feature"])
    assert columns["max_range_feature"] == list(study["max_range_feature"])
    assert [t == "1" for t in columns["saturated"]] == list(study["saturated"])
    assert columns["max_range_m"] == list(study.max_range_text)
    # The numeric detection range: the number, +inf beyond the limit, NaN when not detectable.
    expected = [
        float(t) if t not in ("beyond", "not detectable", "") else
        (np.inf if t == "beyond" else np.nan)
        for t in columns["max_range_m"]
    ]  # fmt: skip
    assert same_bits(np.array(expected), study["max_range_m"])
    best = json.loads((out / "best.json").read_text())
    assert best == study.best
    ranked = [v["max_range_m"] for v in best["views"]]
    assert len(ranked) == len(study.view_max_range_m)


#: The CLI's arguments and the same study from Python: the example scenes with the example
#: sensors, coarse grids (to keep the suite fast), ranges and a search.
CASES: dict[str, tuple[list[str], Any]] = {
    "daylight-sony-grid": (
        ["--scene", str(DAYLIGHT), "--sensor", str(SONY), "--grid-deg", "10,30",
         "--ranges-m", "500,3000"],
        lambda: polbrdf.detect(DAYLIGHT, SONY, grid_deg=(10, 30), ranges_m=[500, 3000]),
    ),
    "daylight-sony-views": (
        ["--scene", str(DAYLIGHT), "--sensor", str(SONY), "--theta-deg", "0,40,70",
         "--phi-deg", "0,180", "--features", "dolp", "--pfa", "1e-4", "--pd", "0.5",
         "--area-m2", "0.25", "--range-limit-m", "20000", "--sun-deg", "60,90"],
        lambda: polbrdf.detect(
            str(DAYLIGHT), str(SONY), theta_deg=[0, 40, 70], phi_deg=[0, 180],
            features=["dolp"], pfa=1e-4, pd=0.5, area_m2=0.25, range_limit_m=20000,
            sun_deg=(60, 90),
        ),
    ),
    "lwir-bolometer-grid": (
        ["--scene", str(LWIR), "--sensor", str(BOLOMETER), "--grid-deg", "15,45"],
        lambda: polbrdf.detect(LWIR, BOLOMETER, grid_deg=(15, 45)),
    ),
    "lwir-bolometer-no-search": (
        ["--scene", str(LWIR), "--sensor", str(BOLOMETER), "--theta-deg", "20,60",
         "--no-search", "--ranges-m", "100,1000,5000"],
        lambda: polbrdf.detect(
            LWIR, BOLOMETER, theta_deg=[20, 60], no_search=True, ranges_m=[100, 1000, 5000]
        ),
    ),
}  # fmt: skip


@needs_cli
@pytest.mark.parametrize("case", list(CASES))
def test_detect_gives_the_cli_s_files_bit_for_bit(case: str, tmp_path: Path) -> None:
    args, study_of = CASES[case]
    run_cli(args, tmp_path / "out")
    assert_study_is_the_cli_s(study_of(), tmp_path / "out")


@needs_cli
def test_a_call_without_options_is_the_cli_s_run_without_options(tmp_path: Path) -> None:
    # The defaults (rows at 1000 m, the 1°×2° grid, the criteria) are the task layer's, for
    # both: a call with none given is the same study.
    sun_only = EXAMPLES / "sun-only-scene.toml"
    run_cli(["--scene", str(sun_only), "--sensor", str(SONY)], tmp_path / "out")
    study = polbrdf.detect(sun_only, SONY)
    assert_study_is_the_cli_s(study, tmp_path / "out")
    assert study.ranges_m == (1000.0,) and study.grid == (90, 180)


def fitted_paint(tmp_path: Path) -> tuple[Path, Path, polbrdf.FitResult]:
    """The example paint fitted to the example goniometer data by the CLI (fit.json and the
    fitted material) and by Python (a FitResult, equal to the CLI's fit bit for bit)."""
    assert CLI is not None
    fit_json, fitted = tmp_path / "fit.json", tmp_path / "fitted.toml"
    r = subprocess.run(
        [str(CLI), "fit", "--material", str(EXAMPLES / "paint-init.toml"), "--data",
         str(EXAMPLES / "paint-goniometer.csv"), "--free", "n,sigma_deg,rho_d,rho_v",
         "--output", str(fit_json), "--material-out", str(fitted)],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    result = polbrdf.fit_measurements(
        polbrdf.Material.from_toml(EXAMPLES / "paint-init.toml"),
        EXAMPLES / "paint-goniometer.csv",
        "n,sigma_deg,rho_d,rho_v",
    )
    return fit_json, fitted, result


@needs_cli
def test_the_range_s_interval_from_a_fit_is_the_cli_s(tmp_path: Path) -> None:
    fit_json, fitted, result = fitted_paint(tmp_path)
    args = ["--scene", str(DAYLIGHT), "--sensor", str(SONY), "--target", str(fitted),
            "--target-fit", str(fit_json), "--theta-deg", "10,24,60", "--phi-deg", "0,180",
            "--range-limit-m", "50000", "--uncertainty-views", "4"]  # fmt: skip
    run_cli(args, tmp_path / "out")
    kw: dict[str, Any] = {"target": fitted, "theta_deg": [10, 24, 60], "phi_deg": [0, 180],
                          "range_limit_m": 50000, "uncertainty_views": 4}  # fmt: skip
    from_file = polbrdf.detect(DAYLIGHT, SONY, target_fit=fit_json, **kw)
    from_result = polbrdf.detect(DAYLIGHT, SONY, target_fit=result, **kw)
    best = json.loads((tmp_path / "out" / "best.json").read_text())
    assert_study_is_the_cli_s(from_file, tmp_path / "out")
    for name in ("max_range_m", "max_range_sigma_m", "max_range_lo95_m", "max_range_hi95_m"):
        assert same_bits(from_result[name], from_file[name]), name
    # Four views have an interval, around their range; the others none.
    sigma = from_file["max_range_sigma_m"]
    assert np.isfinite(sigma).sum() == 4 and np.all(sigma[np.isfinite(sigma)] > 0)
    r, hi = from_file["max_range_m"], from_file["max_range_hi95_m"]
    has = np.isfinite(sigma)
    assert np.allclose(hi[has] - r[has], 1.959963984540054 * sigma[has], rtol=1e-12)
    assert best["uncertainty"]["target_fit"]["parameters"] == ["n", "sigma_deg", "rho_d", "rho_v"]
    assert best["best"]["uncertainty"] == "interval"


def test_a_fit_of_another_material_is_refused_naming_the_key(tmp_path: Path) -> None:
    doc = {"parameter_order": ["n"], "parameters": {"n": {"value": 1.9, "bound": "interior"}},
           "covariance": [[1e-4]]}  # fmt: skip
    (tmp_path / "fit.json").write_text(json.dumps(doc))
    with pytest.raises(ValueError, match=r"`parameters.n.value` = 1.9 of the fit"):
        polbrdf.detect(DAYLIGHT, SONY, theta_deg=[30], target_fit=tmp_path / "fit.json")
    with pytest.raises(TypeError, match="FitResult or the path of a fit.json"):
        polbrdf.detect(DAYLIGHT, SONY, theta_deg=[30], target_fit=3)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="uncertainty_views") as e:
        polbrdf.detect(DAYLIGHT, SONY, theta_deg=[30], uncertainty_views=0)
    assert e.value.argument == "uncertainty_views"  # type: ignore[attr-defined]


def test_the_rows_are_views_by_ranges_and_the_ranking_is_by_range() -> None:
    study = polbrdf.detect(DAYLIGHT, SONY, grid_deg=(10, 30), ranges_m=[500, 3000])
    n_views = len(study.view_max_range_m)
    assert study.grid is not None and study.grid[0] * study.grid[1] == n_views
    assert len(study) == 2 * n_views
    assert list(study["range_m"][:2]) == [500.0, 3000.0]
    # P_d falls with range at every view (the path only attenuates and adds radiance).
    pd = study["pd"].reshape(n_views, 2)
    assert np.all(pd[:, 1] <= pd[:, 0])
    # best.json ranks the views by detection range, largest first, beyond the limit first.
    key = [np.inf if v["max_range_m"] == "beyond" else
           -np.inf if v["max_range_m"] == "not detectable" else v["max_range_m"]
           for v in study.best["views"]]  # fmt: skip
    assert key == sorted(key, reverse=True)
    finite = study.view_max_range_m[np.isfinite(study.view_max_range_m)]
    if finite.size:
        assert study.best["views"][0]["max_range_m"] in ("beyond", float(finite.max()))


def test_a_scene_object_gives_the_scene_file_s_study() -> None:
    scene = polbrdf.Scene.from_toml(DAYLIGHT)
    a = polbrdf.detect(scene, SONY, theta_deg=[10, 50], phi_deg=[0, 90], ranges_m=[800])
    b = polbrdf.detect(DAYLIGHT, SONY, theta_deg=[10, 50], phi_deg=[0, 90], ranges_m=[800])
    for name in a.columns[:11]:
        assert same_bits(a[name], b[name]), name


@pytest.mark.parametrize(
    ("kwargs", "argument", "message"),
    [
        ({"features": ["dolp", "contrast"]}, "features", 'unknown feature "contrast"'),
        ({"pfa": 1.5}, "pfa", r"`pfa` = 1.5: must lie in \(0, 1\)"),
        ({"area_m2": -1.0}, "area_m2", "`area_m2` = -1: must be finite and > 0"),
        ({"ranges_m": [100, -5]}, "ranges_m", "-5: a range must be finite and > 0"),
        ({"ranges_m": [], "no_search": True}, "ranges_m", "give ranges, or a range search"),
        ({"phi_deg": [0, 90], "theta_deg": None}, "phi_deg", "phi_deg needs theta_deg"),
        ({"grid_deg": 10, "theta_deg": 20}, "grid_deg", "not both"),
        ({"sun_deg": [40]}, "sun_deg", "expected two numbers"),
    ],
)
def test_bad_arguments_name_the_keyword(
    kwargs: dict[str, Any], argument: str, message: str
) -> None:
    kwargs.setdefault("theta_deg", None if "grid_deg" in kwargs else [30])
    with pytest.raises(ValueError, match=message) as e:
        polbrdf.detect(DAYLIGHT, SONY, **kwargs)
    assert e.value.argument == argument  # type: ignore[attr-defined]


@needs_cli
@pytest.mark.parametrize("seed", [0, 12345])
def test_detect_frame_gives_the_cli_s_npy_files_bit_for_bit(seed: int, tmp_path: Path) -> None:
    args = ["--scene", str(DAYLIGHT), "--sensor", str(SONY), "--grid-deg", "15,45",
            "--ranges-m", "2000", "--frame", "--seed", str(seed)]  # fmt: skip
    run_cli(args, tmp_path / "out")
    f = polbrdf.detect_frame(DAYLIGHT, SONY, seed=seed, grid_deg=(15, 45), ranges_m=[2000])
    assert_study_is_the_cli_s(f.study, tmp_path / "out")
    for name, array in [
        ("raw_counts", f.raw_counts),
        ("saturated", f.raw_saturated),
        ("s0", f.s0),
        ("dolp", f.dolp),
        ("aolp_deg", f.aolp_deg),
    ]:
        npy = np.load(tmp_path / "out" / f"frame_{name}.npy")
        assert npy.dtype == array.dtype and npy.shape == array.shape, name
        if array.dtype == np.bool_:
            assert np.array_equal(npy, array), name
        else:
            assert same_bits(npy, array), name
    assert f.raw_counts.shape == (2 * f.side, 2 * f.side)
    assert f.s0.shape == (f.side, f.side) and 0 < f.target_side <= f.side


def test_a_different_seed_draws_a_different_frame_and_the_same_seed_the_same() -> None:
    kw: dict[str, Any] = {"theta_deg": [30], "ranges_m": [1500], "no_search": True}
    a = polbrdf.detect_frame(DAYLIGHT, SONY, seed=1, **kw)
    b = polbrdf.detect_frame(DAYLIGHT, SONY, seed=1, **kw)
    c = polbrdf.detect_frame(DAYLIGHT, SONY, seed=2, **kw)
    assert same_bits(a.raw_counts, b.raw_counts)
    assert not same_bits(a.raw_counts, c.raw_counts)


def test_a_thermal_sensor_has_no_frame_and_says_so() -> None:
    with pytest.raises(ValueError, match="photon-counting") as e:
        polbrdf.detect_frame(LWIR, BOLOMETER, theta_deg=[30], no_search=True)
    assert e.value.argument == "frame"  # type: ignore[attr-defined]


@pytest.mark.skipif(importlib.util.find_spec("xarray") is None, reason="xarray not installed")
def test_to_xarray_puts_the_rows_on_the_grid_and_the_ranges() -> None:
    study = polbrdf.detect(DAYLIGHT, SONY, grid_deg=(10, 30), ranges_m=[500, 3000])
    ds = study.to_xarray()
    assert ds["pd"].dims == ("theta_r_deg", "phi_r_deg", "range_m")
    assert list(ds["range_m"].values) == [500.0, 3000.0]
    assert same_bits(ds["pd"].values.reshape(-1), study["pd"])
    assert same_bits(ds["max_range_m"].values.reshape(-1), study.view_max_range_m)
    assert json.loads(ds.attrs["best_json"]) == study.best
    listed = polbrdf.detect(DAYLIGHT, SONY, theta_deg=[10, 50], ranges_m=[800]).to_xarray()
    assert listed["d_prime"].dims == ("view", "range_m")
