"""Python and `polbrdf eval` (the CLI) agree on the same geometries and materials.

Needs the CLI binary: `cargo build -p polbrdf-cli` (.ci/run builds it first), or the path of a
`polbrdf` binary in $POLBRDF_CLI. Skipped with that reason when there is none.
"""

from __future__ import annotations

import csv
import io
import subprocess
from pathlib import Path

import numpy as np
import pytest
from support import NO_CLI, cli_binary

import polbrdf

CLI = cli_binary()
pytestmark = pytest.mark.skipif(CLI is None, reason=NO_CLI)


def geometries() -> np.ndarray:
    rng = np.random.default_rng(7)
    n = 300
    g = np.column_stack(
        [
            rng.uniform(0, 89, n),
            rng.uniform(-180, 360, n),
            rng.uniform(0, 89, n),
            rng.uniform(-180, 360, n),
        ]
    )
    special: list[list[float]] = [
        [0, 0, 0, 0],  # normal incidence and view
        [60, 0, 60, 180],  # specular
        [45, 30, 45, 30],  # backscatter (beta = 0)
        [89.9, 0, 89.9, 180],  # grazing
        [95, 0, 30, 180],  # below the horizon: zero
        [30, 0, 180, 0],  # below the horizon: zero
        [56.5, 10, 56.5, 190],  # near Brewster
    ]
    return np.vstack([g, special])


def run_cli(material: str, g: np.ndarray, tmp_path: Path) -> dict[str, np.ndarray]:
    geo = tmp_path / "g.csv"
    with geo.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["theta_i_deg", "phi_i_deg", "theta_r_deg", "phi_r_deg"])
        w.writerows([[repr(float(x)) for x in row] for row in g])
    assert CLI is not None
    out = subprocess.run(
        [str(CLI), "eval", "--material", material, "--input", str(geo)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert out.returncode == 0, out.stderr
    rows = list(csv.reader(io.StringIO(out.stdout)))
    header, body = rows[0], rows[1:]
    assert len(body) == len(g)
    return {h: np.array([float(r[k]) for r in body]) for k, h in enumerate(header)}


def compare(mat: polbrdf.Material, cli: dict[str, np.ndarray], g: np.ndarray) -> None:
    e = polbrdf.evaluate(mat, *g.T, with_mueller=True)
    assert e.mueller is not None
    scale = np.abs(e.brdf)[:, None, None] + 1e-300
    want = np.stack([cli[f"m{i}{j}"] for i in range(4) for j in range(4)], axis=-1)
    want = want.reshape(-1, 4, 4)
    assert np.all(np.abs(e.mueller - want) <= 1e-12 * scale + 1e-15)
    np.testing.assert_allclose(e.brdf, cli["brdf"], rtol=1e-12, atol=0)
    np.testing.assert_allclose(e.dolp, cli["dolp"], rtol=0, atol=1e-12)
    # AoLP: equal modulo 180° (±90° are the same orientation).
    diff = (e.aolp - cli["aolp_deg"] + 90.0) % 180.0 - 90.0
    assert np.all(np.abs(diff) <= 1e-9)
    np.testing.assert_array_equal(polbrdf.mueller(mat, *g.T), e.mueller)


def test_preset_agrees_with_cli(tmp_path: Path) -> None:
    g = geometries()
    compare(polbrdf.Material.preset("paint"), run_cli("paint", g, tmp_path), g)


@pytest.mark.parametrize(
    "mat",
    [
        polbrdf.Material(n=1.5, k=0.2, b=6.0, a=1.7, form="paper", azimuth_term="eq3", rho_v=0.02),
        polbrdf.Material(n=0.181, k=3.07, sigma_deg=10, shadowing=False, tau_deg=10, omega_deg=30),
        polbrdf.Material.preset("aluminium"),
    ],
    ids=["paper-eq3", "gold-like-no-shadowing", "aluminium"],
)
def test_material_file_agrees_with_cli(mat: polbrdf.Material, tmp_path: Path) -> None:
    """to_toml() writes a file the CLI reads to the same material."""
    path = tmp_path / "m.toml"
    path.write_text(mat.to_toml(), encoding="utf-8")
    assert polbrdf.Material.from_toml(path) == mat
    g = geometries()
    compare(mat, run_cli(str(path), g, tmp_path), g)


def test_eval_npy_matches_python_and_numpy_reads_it(tmp_path: Path) -> None:
    """`eval --output x.npy` is a structured array numpy loads, equal to the Python package's
    values, and a structured array saved by numpy is an `eval` input."""
    g = geometries()[:50]
    names = ["theta_i_deg", "phi_i_deg", "theta_r_deg", "phi_r_deg"]
    table = np.rec.fromarrays(g.T, names=names)
    src = tmp_path / "g.npy"
    np.save(src, table)
    out = tmp_path / "out.npy"
    assert CLI is not None
    subprocess.run(
        [str(CLI), "eval", "--material", "paint", "--input", str(src), "--output", str(out)],
        check=True,
    )
    a = np.load(out)
    assert a.dtype.names[:4] == tuple(names)
    assert a.shape == (50,)
    f = polbrdf.mueller(polbrdf.Material.preset("paint"), *g.T)
    m = np.stack([a[f"m{k // 4}{k % 4}"] for k in range(16)], axis=-1).reshape(-1, 4, 4)
    np.testing.assert_allclose(m, f, rtol=1e-12, atol=1e-300)
    np.testing.assert_array_equal(a["brdf"], a["m00"])


def test_eval_arrow_output_read_by_pyarrow_equals_csv(tmp_path: Path) -> None:
    """`eval --output x.arrow` (Arrow IPC file) and `x.arrows` (stream) are tables pyarrow reads,
    equal to the CSV output's values (CSV writes −0 as 0); a table written by pyarrow (Float32,
    integer and text columns, several batches) is an `eval` input."""
    pa = pytest.importorskip("pyarrow", reason="pyarrow is not installed (pip install pyarrow)")
    ipc = pytest.importorskip("pyarrow.ipc")
    g = geometries()[:200]
    names = ["theta_i_deg", "phi_i_deg", "theta_r_deg", "phi_r_deg"]
    src = tmp_path / "g.csv"
    with open(src, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow([*names, "label"])
        w.writerows([*map(repr, row), f"r{k}"] for k, row in enumerate(g.tolist()))
    assert CLI is not None

    def run(inp: Path, out: Path) -> None:
        subprocess.run(
            [str(CLI), "eval", "--material", "paint", "--input", str(inp), "--output", str(out)],
            check=True,
        )

    run(src, tmp_path / "out.csv")
    run(src, tmp_path / "out.arrow")
    run(src, tmp_path / "out.arrows")
    with open(tmp_path / "out.csv", newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    for table in (
        ipc.open_file(tmp_path / "out.arrow").read_all(),
        ipc.open_stream(tmp_path / "out.arrows").read_all(),
    ):
        assert table.column_names == header
        assert table.num_rows == 200
        assert table.schema.field("label").type == pa.string()
        for i, name in enumerate(header):
            col = table.column(name)
            if name == "label":
                assert col.to_pylist() == [r[i] for r in body]
                continue
            assert col.type == pa.float64(), name
            got = np.asarray(col.to_numpy(), dtype=np.float64) + 0.0
            want = np.array([float(r[i]) for r in body])
            np.testing.assert_array_equal(got.view(np.uint64), want.view(np.uint64), err_msg=name)

    # pyarrow's own table, in batches of 64 rows, with other column types, as input.
    t = pa.table(
        {
            "theta_i_deg": pa.array(g[:, 0], pa.float64()),
            "phi_i_deg": pa.array(g[:, 1].astype(np.float32)),
            "theta_r_deg": pa.array(np.round(g[:, 2]).astype(np.int32)),
            "phi_r_deg": pa.array(g[:, 3]),
            "label": pa.array([f"r{k}" for k in range(200)]),
        }
    )
    with ipc.new_file(tmp_path / "py.feather", t.schema) as w:
        for b in t.to_batches(max_chunksize=64):
            w.write_batch(b)
    run(tmp_path / "py.feather", tmp_path / "py.arrow")
    out = ipc.open_file(tmp_path / "py.arrow").read_all()
    assert out.num_rows == 200
    assert out.column("label").to_pylist() == [f"r{k}" for k in range(200)]
    np.testing.assert_array_equal(
        out.column("phi_i_deg").to_numpy(), g[:, 1].astype(np.float32).astype(np.float64)
    )
    f = polbrdf.mueller(
        polbrdf.Material.preset("paint"),
        g[:, 0],
        g[:, 1].astype(np.float32).astype(np.float64),
        np.round(g[:, 2]),
        g[:, 3],
    )
    m = np.stack([out.column(f"m{k // 4}{k % 4}").to_numpy() for k in range(16)], axis=-1)
    np.testing.assert_allclose(m.reshape(-1, 4, 4), f, rtol=1e-12, atol=1e-300)
