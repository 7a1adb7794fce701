"""`polbrdf.check`, `emissivity(..., band=...)`, `export_pbsdf`, `read_pbsdf`, `fit_pbsdf`,
`read_measurements` and `fit_measurements` are `polbrdf check`, `emission`, `export` and `fit`
from Python: each compared with the CLI's output file bit for bit (the CLI run from the test);
the task layer's limits bound Python as they bound the CLI, a `ValueError` naming the keyword."""

from __future__ import annotations

import csv
import json
import subprocess
from pathlib import Path

import numpy as np
import pytest
from support import NO_CLI, REPO, cli_binary

import polbrdf

CLI = cli_binary()
EXAMPLES = REPO / "examples"
SOIL = str(EXAMPLES / "dry-soil.toml")
LWIR_PAINT = str(EXAMPLES / "painted-aluminium-lwir.toml")
LWIR = str(EXAMPLES / "lwir-8-12um.csv")
GONIOMETER = str(EXAMPLES / "paint-goniometer.csv")
PAINT_INIT = str(EXAMPLES / "paint-init.toml")

needs_cli = pytest.mark.skipif(CLI is None, reason=NO_CLI)


def run_cli(*args: str, codes: tuple[int, ...] = (0,)) -> subprocess.CompletedProcess[str]:
    r = subprocess.run([str(CLI), *args], capture_output=True, text=True, check=False)
    assert r.returncode in codes, r.stderr
    return r


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))


# --- check ------------------------------------------------------------------------------------


@needs_cli
@pytest.mark.parametrize(
    ("material", "spectral", "python"),
    [
        (SOIL, [], {}),
        (LWIR_PAINT, ["--band", LWIR, "--band-step-um", "2"], {"band": LWIR, "band_step_um": 2}),
    ],
)
def test_check_is_the_cli_s_document_bit_for_bit(
    tmp_path: Path, material: str, spectral: list[str], python: dict
) -> None:
    out = tmp_path / "check.json"
    run_cli("check", "--material", material, "--grid-deg", "15", "--output", str(out), *spectral,
            codes=(0, 6))  # fmt: skip
    cli = json.loads(out.read_text())
    report = polbrdf.check(material, grid_deg=15, **python)
    # JSON floats are written shortest-round-trip: equal dicts are equal bits.
    assert report.document == cli
    assert report.passes == cli["passes"]
    assert report.geometries == 6 * 6 * 12  # 15° zenith steps, 30° relative azimuth steps
    assert len(report.nodes) == (1 if not spectral else cli["spectrum"]["nodes"])
    # The same numbers from a Material object as from its file (named by its `name` key).
    m = polbrdf.Material.from_toml(material)
    assert polbrdf.check(m, grid_deg=15, **python).nodes == report.nodes


def test_check_physics_the_albedo_is_the_albedo_job_s() -> None:
    # The check's albedo at θi = 0°, 5°, …, 85° is polbrdf.albedo's at the same angles.
    report = polbrdf.check(SOIL, grid_deg=15)
    albedo = polbrdf.albedo(SOIL)
    rows = report.nodes[0]["albedo"]
    assert [r["theta_i_deg"] for r in rows] == pytest.approx(list(albedo.theta_i_deg), abs=1e-12)
    assert [r["albedo"] for r in rows] == pytest.approx(list(albedo.albedo), rel=1e-12)
    assert report.nodes[0]["conserves_energy"] == bool(np.all(albedo.albedo <= 1.0))


# --- band emissivity --------------------------------------------------------------------------


@needs_cli
@pytest.mark.parametrize("temperature", [None, 300.0])
def test_band_emissivity_is_the_cli_s_table_bit_for_bit(
    tmp_path: Path, temperature: float | None
) -> None:
    out = tmp_path / "emission.csv"
    extra = [] if temperature is None else ["--temperature-k", str(temperature)]
    run_cli("emission", "--material", LWIR_PAINT, "--band", LWIR, "--band-step-um", "2",
            "--theta-deg", "0,60,85", "--output", str(out), *extra)  # fmt: skip
    with out.open() as f:
        rows = list(csv.DictReader(f))
    m = polbrdf.Material.from_toml(LWIR_PAINT)
    e = polbrdf.emissivity(m, [0, 60, 85], band=LWIR, band_step_um=2, temperature_k=temperature)

    def col(name: str) -> np.ndarray:
        return np.array([float(r[name]) for r in rows])

    assert same_bits(col("theta_deg"), [0, 60, 85])
    for k in range(4):
        assert same_bits(col(f"eps{k}"), e.eps[:, k]), k
    for name in ("eps_s", "eps_p", "dolp", "reciprocity_residual"):
        assert same_bits(col(name), getattr(e, name)), name
    assert [r["valid"] for r in rows] == [str(bool(v)).lower() for v in e.valid]


def test_band_emissivity_of_a_constant_index_is_its_monochromatic_value() -> None:
    # A constant-index material does not depend on the wavelength: the band mean of its
    # emissivity is its emissivity (the weights sum to 1), to rounding.
    m = polbrdf.Material.preset("paint")
    band = polbrdf.emissivity(m, [[0.0, 40.0], [70.0, 85.0]], band=LWIR)
    mono = polbrdf.emissivity(m, [[0.0, 40.0], [70.0, 85.0]])
    assert band.eps.shape == (2, 2, 4)
    assert np.allclose(band.eps, mono.eps, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize(
    ("kwargs", "argument"),
    [
        ({"band": LWIR, "wavelength_um": 10.0}, "wavelength_um"),
        ({"temperature_k": 300.0}, "temperature_k"),
        ({"band": LWIR, "temperature_k": -1.0}, "temperature_k"),
        ({"band": LWIR, "band_step_um": 0.0}, "band_step_um"),
    ],
)
def test_band_emissivity_names_a_bad_keyword(kwargs: dict, argument: str) -> None:
    with pytest.raises(ValueError, match=f"`{argument}`") as e:
        polbrdf.emissivity(polbrdf.Material.preset("paint"), 30.0, **kwargs)
    assert e.value.argument == argument  # type: ignore[attr-defined]


# --- .pbsdf tables ----------------------------------------------------------------------------


@needs_cli
def test_export_read_and_fit_of_a_pbsdf_table_are_the_cli_s(tmp_path: Path) -> None:
    cli_table, py_table = tmp_path / "cli.pbsdf", tmp_path / "py.pbsdf"
    run_cli("export", "--material", "paint", "--output", str(cli_table), "--grid", "9,7,8")
    size = polbrdf.export_pbsdf(polbrdf.Material.preset("paint"), py_table, grid=(9, 7, 8))
    assert size == 9 * 7 * 8 * 5 * 64
    assert py_table.read_bytes() == cli_table.read_bytes()

    t = polbrdf.read_pbsdf(cli_table)
    assert t.wavelengths_nm == [450, 500, 550, 600, 650]
    assert t.M.shape == (9, 7, 8, 5, 4, 4) and t.M.dtype == np.float32
    assert (t.phi_d[0], t.phi_d[-1]) == (np.float32(-np.pi), np.float32(np.pi))
    # The matrices are the file's tensor, as stored (little-endian float32, C order).
    assert cli_table.read_bytes().find(t.M.astype("<f4").tobytes()) > 0

    out = tmp_path / "fit.json"
    run_cli("fit", "--material", "paint", "--data", str(cli_table), "--free", "sigma_deg,rho_d",
            "--subsample", "2", "--starts", "1", "--output", str(out))  # fmt: skip
    doc = polbrdf.fit_pbsdf("paint", cli_table, "sigma_deg,rho_d", subsample=2, starts=1)
    assert doc == json.loads(out.read_text())
    # The table of the paint fitted from the paint: its own parameters, in every band.
    paint = polbrdf.Material.preset("paint").to_dict()
    for band in doc["per_band"]:
        assert band["parameters"]["sigma_deg"]["value"] == pytest.approx(
            paint["sigma_deg"], rel=1e-4
        )


def test_export_refuses_a_table_over_its_bound_before_the_material(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="`grid`") as e:
        polbrdf.export_pbsdf("no-such-material", tmp_path / "t.pbsdf", grid=(4096, 4096, 4096))
    assert e.value.argument == "grid"  # type: ignore[attr-defined]
    assert not (tmp_path / "t.pbsdf").exists()


def test_read_pbsdf_names_the_file_of_a_bad_table(tmp_path: Path) -> None:
    bad = tmp_path / "bad.pbsdf"
    bad.write_bytes(b"not a tensor file")
    with pytest.raises(ValueError, match="bad.pbsdf"):
        polbrdf.read_pbsdf(bad)


# --- measurement files ------------------------------------------------------------------------


def test_read_measurements_holds_the_file_s_values() -> None:
    m = polbrdf.read_measurements(GONIOMETER)
    with open(GONIOMETER) as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    assert len(m.lines) == len(rows) == len(m.theta_i)
    for name in ("theta_i", "phi_i", "theta_r", "phi_r"):
        deg = np.array([float(r[f"{name}_deg"]) for r in rows])
        assert same_bits(getattr(m, name), np.radians(deg)), name
    for name, values in m.data.items():
        want = np.array([float(r[name]) if r[name].strip() else np.nan for r in rows])
        assert np.array_equal(values, want, equal_nan=True), name
    assert set(m.sigma) <= set(m.data)


@needs_cli
def test_fit_measurements_is_the_cli_s_fit_bit_for_bit(tmp_path: Path) -> None:
    out = tmp_path / "fit.json"
    free = "n,sigma_deg,rho_d,rho_v"
    run_cli("fit", "--material", PAINT_INIT, "--data", GONIOMETER, "--free", free,
            "--output", str(out))  # fmt: skip
    cli = json.loads(out.read_text())
    init = polbrdf.Material.from_toml(PAINT_INIT)
    r = polbrdf.fit_measurements(init, GONIOMETER, free)
    assert r.names == cli["parameter_order"]
    values = [cli["parameters"][n]["value"] for n in r.names]
    stderr = [cli["parameters"][n]["stderr"] for n in r.names]
    assert same_bits(r.values, values)
    assert same_bits(r.stderr, stderr)
    assert same_bits(r.chi2, cli["chi2"])
    # The reader's measurements, fitted by polbrdf.fit, reach the same minimum (the order of
    # the measurements differs, so rounding may).
    m = polbrdf.read_measurements(GONIOMETER)
    again = polbrdf.fit(init, m.theta_i, m.phi_i, m.theta_r, m.phi_r, m.data, free,
                        sigma=m.sigma, degrees=False)  # fmt: skip
    assert np.allclose(again.values, r.values, rtol=1e-6)


# --- the task layer's limits ------------------------------------------------------------------


def test_a_check_grid_over_its_limit_names_grid_deg_before_reading_the_material() -> None:
    with pytest.raises(ValueError, match=r"invalid `grid_deg` = 5e-1: .* at most 2000000") as e:
        polbrdf.check("/no/such/material.toml", grid_deg=0.5)
    assert e.value.argument == "grid_deg"  # type: ignore[attr-defined]


def test_a_contrast_top_over_its_limit_names_top() -> None:
    light = polbrdf.Illumination(sun_zenith_deg=30)
    with pytest.raises(ValueError, match="invalid `top` = 1001: at most 1000") as e:
        polbrdf.contrast("paint", "paint", light, top=1001)
    assert e.value.argument == "top"  # type: ignore[attr-defined]


def test_the_radiance_work_bound_is_a_value_error_naming_the_views() -> None:
    # 600 × 600 distinct views under an azimuth-dependent sky: 3.6e5 views × 1 node × 1000 sky
    # samples = 3.6e8 units of work, over the bound of 1e8: refused before anything is observed.
    scene = polbrdf.Scene(
        wavelength_um=0.55,
        sun=polbrdf.Sun(zenith_deg=40, irradiance=1400),
        sky=polbrdf.Sky(model="cie-clear", irradiance=200),
    )
    t, p = np.meshgrid(np.linspace(0, 89, 600), np.linspace(0, 359, 600))
    with pytest.raises(ValueError, match=r"units of work, at most 1e8") as e:
        polbrdf.radiance(polbrdf.Material.preset("paint"), scene, (t, p))
    assert e.value.argument == "theta_r"  # type: ignore[attr-defined]
