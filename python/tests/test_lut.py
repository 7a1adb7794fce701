"""polbrdf.lut: lookup tables as xarray Datasets (the optional extra polbrdf[xarray]).

Skipped with a message when xarray or dask is absent; CI installs them (scripts/test)."""

from __future__ import annotations

import itertools
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import polbrdf

xr = pytest.importorskip("xarray", reason="xarray is not installed (pip install polbrdf[xarray])")
pytest.importorskip("dask.array", reason="dask is not installed (pip install polbrdf[xarray])")

from polbrdf.xarray import lut

WL = np.array([0.55, 0.6328, 1.0])
TI = np.array([0.0, 30.0, 60.0, 85.0])
TR = np.array([0.0, 20.0, 45.0, 70.0, 95.0])
DP = np.array([0.0, 45.0, 180.0, 270.0])


@pytest.fixture(scope="module")
def materials() -> dict[str, polbrdf.Material]:
    return {
        "paint": polbrdf.Material.preset("paint"),
        "gold": polbrdf.Material(index="library:Au/Johnson", sigma_deg=8.0, rho_d=0.01),
    }


def bits(a: np.ndarray) -> np.ndarray:
    """The exact bit patterns (so that -0.0 and 0.0, and NaN payloads, count as different)."""
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint64)


def direct(m: polbrdf.Material) -> polbrdf.Evaluation:
    """Direct calls on the broadcast table coordinates (phi_i = 0, phi_r = dphi)."""
    return polbrdf.evaluate(
        m,
        TI[None, :, None, None],
        0.0,
        TR[None, None, :, None],
        DP[None, None, None, :],
        wavelength_um=WL[:, None, None, None],
        with_mueller=True,
    )


def test_import_polbrdf_does_not_import_xarray() -> None:
    code = (
        "import sys, polbrdf; assert 'xarray' not in sys.modules; assert 'dask' not in sys.modules"
    )
    subprocess.run([sys.executable, "-c", code], check=True, cwd=os.path.dirname(__file__))
    assert polbrdf.lut is lut


@pytest.mark.parametrize("chunks", [None, {"theta_r": 2}])
def test_values_are_direct_calls_bit_for_bit(materials, chunks) -> None:
    ds = lut(materials, WL, TI, TR, DP, quantities=polbrdf.xarray.QUANTITIES, chunks=chunks)
    assert ds.mueller.dims == ("material", "wavelength", "theta_i", "theta_r", "dphi", "row", "col")
    assert ds.brdf.dims == ("material", "wavelength", "theta_i", "theta_r", "dphi")
    assert list(ds.material.values) == ["paint", "gold"]
    ds = ds.compute()
    for name, m in materials.items():
        e = direct(m)
        one = ds.sel(material=name)
        np.testing.assert_array_equal(bits(one.mueller.values), bits(e.mueller))
        np.testing.assert_array_equal(bits(one.brdf.values), bits(e.brdf))
        np.testing.assert_array_equal(bits(one.dolp.values), bits(e.dolp))
        np.testing.assert_array_equal(bits(one.aolp.values), bits(e.aolp))
        # and the functions one would call for each: mueller, brdf, dolp
        args = (TI[None, :, None, None], 0.0, TR[None, None, :, None], DP[None, None, None, :])
        kw = {"wavelength_um": WL[:, None, None, None]}
        np.testing.assert_array_equal(
            bits(one.mueller.values), bits(polbrdf.mueller(m, *args, **kw))
        )
        np.testing.assert_array_equal(bits(one.dolp.values), bits(polbrdf.dolp(m, *args, **kw)))
    # the physics is there: a direction below the horizon reflects nothing, the spectral
    # material differs between wavelengths, the constant one does not
    assert (ds.mueller.sel(theta_r=95.0) == 0).all()
    gold = ds.brdf.sel(material="gold", theta_i=30.0, theta_r=20.0, dphi=180.0).values
    assert len(set(gold)) == len(WL)
    paint = ds.brdf.sel(material="paint", theta_i=30.0, theta_r=20.0, dphi=180.0).values
    assert len(set(paint)) == 1


@pytest.mark.parametrize("quantities", [("mueller",), ("dolp",), ("aolp", "brdf")])
def test_any_subset_of_quantities_is_the_direct_calls(materials, quantities) -> None:
    ds = lut(materials, WL, TI, TR, DP, quantities=quantities, chunks={"dphi": 1}).compute()
    assert set(ds.data_vars) == set(quantities)
    for name, m in materials.items():
        e = direct(m)
        for q in quantities:
            got = ds[q].sel(material=name).values
            np.testing.assert_array_equal(bits(got), bits(getattr(e, q)), err_msg=q)


def test_chunking_over_every_dimension_gives_the_same_table(materials) -> None:
    whole = lut(materials, WL, TI, TR, DP, quantities=polbrdf.xarray.QUANTITIES)
    chunked = lut(
        materials,
        WL,
        TI,
        TR,
        DP,
        quantities=polbrdf.xarray.QUANTITIES,
        chunks={"material": 1, "wavelength": 2, "theta_i": 3, "theta_r": 2, "dphi": 3},
    )
    assert chunked.mueller.chunks[:5] == ((1, 1), (2, 1), (3, 1), (2, 2, 1), (3, 1))
    chunked = chunked.compute()
    for v in whole.data_vars:
        np.testing.assert_array_equal(bits(chunked[v].values), bits(whole[v].values), err_msg=v)


def test_local_cluster_with_two_worker_processes(materials) -> None:
    distributed = pytest.importorskip("distributed", reason="dask.distributed is not installed")
    whole = lut(materials, WL, TI, TR, DP)
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        lazy = lut(materials, WL, TI, TR, DP, chunks={"wavelength": 1, "theta_i": 2})
        computed = client.compute(lazy).result()
        workers = client.run(os.getpid)
    assert len(set(workers.values())) == 2 and os.getpid() not in workers.values()
    for v in whole.data_vars:
        np.testing.assert_array_equal(bits(computed[v].values), bits(whole[v].values), err_msg=v)


def roundtrip_check(ds: xr.Dataset, back: xr.Dataset) -> None:
    assert back.attrs == ds.attrs
    for v in ds.variables:
        assert back[v].attrs == ds[v].attrs, v
        assert back[v].dims == ds[v].dims, v
    for v in ds.data_vars:
        np.testing.assert_array_equal(bits(back[v].values), bits(ds[v].values), err_msg=v)
    assert list(back.material.values) == list(ds.material.values)
    # the parameters can be rebuilt from the attribute alone
    for name, d in json.loads(back.attrs["materials_json"]).items():
        m = polbrdf.Material(**d)
        e = direct(m)
        np.testing.assert_array_equal(bits(back.mueller.sel(material=name).values), bits(e.mueller))


def test_attributes_round_trip_through_zarr(materials, tmp_path) -> None:
    pytest.importorskip("zarr", reason="zarr is not installed")
    ds = lut(materials, WL, TI, TR, DP, chunks={"theta_i": 2}, contrast=("gold", "paint"))
    ds.to_zarr(tmp_path / "t.zarr", consolidated=False)
    back = xr.open_zarr(tmp_path / "t.zarr", consolidated=False).compute()
    roundtrip_check(ds.compute(), back)
    for key in ("stokes_basis", "s3_sign", "azimuth_convention", "polbrdf_version"):
        assert back.attrs[key]
    assert back.attrs["polbrdf_version"] == polbrdf.__version__


def test_attributes_round_trip_through_netcdf(materials, tmp_path) -> None:
    pytest.importorskip("h5netcdf", reason="h5netcdf is not installed")
    ds = lut(materials, WL, TI, TR, DP)
    ds.to_netcdf(tmp_path / "t.nc", engine="h5netcdf")
    with xr.open_dataset(tmp_path / "t.nc", engine="h5netcdf") as back:
        roundtrip_check(ds, back.load())


def test_contrast_quantities(materials) -> None:
    ds = lut(materials, WL, TI, TR, DP, quantities=("mueller",), contrast=("gold", "paint"))
    assert "brdf" not in ds and "dolp" not in ds
    g, p = direct(materials["gold"]), direct(materials["paint"])
    np.testing.assert_array_equal(ds.delta_dolp.values, g.dolp - p.dolp)
    above = p.brdf > 0
    ratio = np.divide(g.brdf, p.brdf, out=np.full_like(g.brdf, np.nan), where=above)
    np.testing.assert_array_equal(ds.intensity_ratio.values[above], ratio[above])
    # below the horizon both reflect nothing: ratio 1 (as polbrdf contrast defines it)
    assert (ds.intensity_ratio.sel(theta_r=95.0) == 1.0).all()
    assert ds.delta_dolp.attrs["target"] == "gold"


def test_interpolation_error_falls_as_the_square_of_the_step() -> None:
    """Dataset.interp (linear) against direct evaluation at off-grid geometries, away from
    the horizon: linear interpolation's error is O(h²), so halving the step divides it by ~4."""
    m = polbrdf.Material(n=1.6, sigma_deg=20.0, rho_d=0.02)
    rng = np.random.default_rng(7)
    ti, tr, dp = rng.uniform(10, 60, 200), rng.uniform(10, 60, 200), rng.uniform(20, 160, 200)
    want = polbrdf.evaluate(m, ti, 0.0, tr, dp, with_mueller=True)
    errors = []
    for step in (8.0, 4.0, 2.0):
        axis = np.arange(0.0, 72.0 + step / 2, step)
        ds = lut(
            m,
            [0.6],
            axis,
            axis,
            np.arange(0.0, 180.0 + step / 2, step),
            quantities=("mueller", "dolp"),
        )
        at = ds.isel(material=0, wavelength=0).interp(
            theta_i=("p", ti), theta_r=("p", tr), dphi=("p", dp)
        )
        err_m = np.abs(at.mueller.values - want.mueller).max() / np.abs(want.mueller).max()
        err_d = np.abs(at.dolp.values - want.dolp).max()
        errors.append((err_m, err_d))
    for (m1, d1), (m2, d2) in itertools.pairwise(errors):
        assert 2.5 < m1 / m2 < 6.0 and 2.5 < d1 / d2 < 6.0, errors
    assert errors[-1][0] < 1e-2 and errors[-1][1] < 1e-3, errors


# --- uncertainty ---------------------------------------------------------------------------


def fitted() -> tuple[polbrdf.Material, list[str], np.ndarray]:
    m = polbrdf.Material(n=1.6, k=0.01, sigma_deg=12.0, rho_d=0.02)
    names = ["n", "sigma_deg", "rho_d"]
    sd = np.array([2e-3, 2e-2, 2e-4])
    corr = np.array([[1.0, 0.3, -0.2], [0.3, 1.0, 0.1], [-0.2, 0.1, 1.0]])
    return m, names, corr * np.outer(sd, sd)


def test_stderr_agrees_with_monte_carlo() -> None:
    """Draw parameter sets from N(θ̂, Σ), evaluate each, compare the sample standard deviation
    with the linear estimate. Σ is small (relative 1e-3), so the model is linear within it to
    ~1e-3; the sample size N = 3000 gives a relative sampling error of std of 1/sqrt(2N) = 1.3%:
    a 6% tolerance is > 4 sampling standard deviations."""
    m, names, cov = fitted()
    wl, ti, tr, dp = [0.6], [20.0, 50.0], [10.0, 40.0, 65.0], [30.0, 180.0]
    ds = lut(
        m,
        wl,
        ti,
        tr,
        dp,
        quantities=polbrdf.xarray.QUANTITIES,
        covariance={"material0": (names, cov)},
    )
    rng = np.random.default_rng(1)
    draws = rng.multivariate_normal([1.6, 12.0, 0.02], cov, size=3000)
    samples = {q: [] for q in ("mueller", "brdf", "dolp", "aolp")}
    g = np.meshgrid(ti, tr, dp, indexing="ij")
    for x in draws:
        mm = polbrdf.Material(n=x[0], k=0.01, sigma_deg=x[1], rho_d=x[2])
        e = polbrdf.evaluate(mm, g[0], 0.0, g[1], g[2], with_mueller=True)
        for q, values in samples.items():
            values.append(getattr(e, q))
    for q, s in samples.items():
        mc = np.std(np.array(s), axis=0, ddof=1)
        lin = ds[q + "_stderr"].isel(material=0, wavelength=0).values
        assert np.isfinite(lin).all(), q
        if q == "aolp":
            # For unpolarized input the reflected AoLP is the angle of the facet frame (|rs| >
            # |rp| everywhere here): geometry only, no parameter moves it. Both are rounding.
            assert lin.max() < 1e-9 and mc.max() < 1e-9, (lin.max(), mc.max())
            continue
        big = lin > 1e-6 * lin.max()  # the elements that vary at all (not F03 etc.)
        assert big.sum() >= 4, q
        np.testing.assert_allclose(mc[big], lin[big], rtol=0.06, err_msg=q)
        assert (mc[~big] <= 1e-5 * lin.max()).all(), q


def test_stderr_from_a_fit_result_and_from_fit_json(tmp_path) -> None:
    truth = polbrdf.Material(n=1.55, sigma_deg=15.0, rho_d=0.03)
    t = np.repeat([10.0, 30.0, 50.0, 70.0], 6)
    r = np.tile([0.0, 15.0, 35.0, 55.0, 65.0, 75.0], 4)
    p = np.where(np.arange(24) % 2 == 0, 180.0, 120.0)
    e = polbrdf.evaluate(truth, t, 0.0, r, p)
    rng = np.random.default_rng(3)
    data = {
        "brdf": e.brdf * (1 + 0.01 * rng.standard_normal(24)),
        "dolp": e.dolp + 0.005 * rng.standard_normal(24),
    }
    sigma = {"brdf": 0.01 * e.brdf, "dolp": np.full(24, 0.005)}
    start = polbrdf.Material(n=1.5, sigma_deg=12.0, rho_d=0.02)
    res = polbrdf.fit(start, t, 0.0, r, p, data, "n,sigma_deg,rho_d", sigma=sigma)
    args = (res.material, [0.6], [20.0, 60.0], [30.0, 60.0], [0.0, 180.0])
    a = lut(*args, covariance={"material0": res})
    b = lut(*args, covariance={"material0": (res.names, res.covariance)}, chunks={"theta_i": 1})
    for v in ("mueller_stderr", "brdf_stderr", "dolp_stderr"):
        np.testing.assert_array_equal(bits(a[v].values), bits(b[v].compute().values), err_msg=v)
        assert (a[v].values[..., :1, :, :] >= 0).all()
    assert (a.dolp_stderr.values > 0).all()
    info = json.loads(a.attrs["uncertainty_json"])["material0"]
    assert info["names"] == ["n", "sigma_deg", "rho_d"]

    # the same through polbrdf fit's fit.json when the CLI is at hand
    cli = os.environ.get("POLBRDF_CLI")
    if not cli:
        pytest.skip("POLBRDF_CLI not set: the fit.json half needs the polbrdf binary")
    csv = tmp_path / "meas.csv"
    rows = ["theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf,sigma_brdf,dolp,sigma_dolp"]
    columns = (t, r, p, data["brdf"], sigma["brdf"], data["dolp"], sigma["dolp"])
    rows += [
        ",".join(repr(float(c[i])) for c in columns[:1])
        + ",0,"
        + ",".join(repr(float(c[i])) for c in columns[1:])
        for i in range(24)
    ]
    csv.write_text("\n".join(rows) + "\n")
    (tmp_path / "start.toml").write_text(start.to_toml())
    subprocess.run(
        [cli, "fit", "--material", str(tmp_path / "start.toml"), "--data", str(csv), "--free",
         "n,sigma_deg,rho_d", "--output", str(tmp_path / "fit.json"), "--material-out",
         str(tmp_path / "fitted.toml")],
        check=True, capture_output=True,
    )  # fmt: skip
    fitted_m = polbrdf.Material.from_toml(tmp_path / "fitted.toml")
    c = lut({"material0": fitted_m}, *args[1:], covariance={"material0": tmp_path / "fit.json"})
    doc = json.loads((tmp_path / "fit.json").read_text())
    d = lut(
        {"material0": fitted_m},
        *args[1:],
        covariance={"material0": (doc["parameter_order"], doc["covariance"])},
    )
    np.testing.assert_array_equal(bits(c.dolp_stderr.values), bits(d.dolp_stderr.values))
    # the CLI's and the Python fit agree, so do their error bars (same data, same engine)
    np.testing.assert_allclose(c.dolp_stderr.values, a.dolp_stderr.values, rtol=1e-3)


def test_contrast_stderr_adds_independent_variances(materials) -> None:
    m, names, cov = fitted()
    mats = {"t": m, "b": materials["paint"]}
    ds = lut(mats, [0.6], TI, TR, DP, covariance={"t": (names, cov)}, contrast=("t", "b"))
    assert np.isnan(ds.dolp_stderr.sel(material="b")).all()
    ds2 = lut(
        mats,
        [0.6],
        TI,
        TR,
        DP,
        covariance={"t": (names, cov), "b": (["n"], [[1e-6]])},
        contrast=("t", "b"),
    )
    want = np.hypot(ds2.dolp_stderr.sel(material="t"), ds2.dolp_stderr.sel(material="b"))
    np.testing.assert_array_equal(ds2.delta_dolp_stderr.values, want.values)


# --- bad input -----------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"quantities": ("mueller", "dop")}, "unknown quantities"),
        ({"theta_i": [0.0, 30.0, 20.0]}, "strictly increasing"),
        ({"theta_r": [0.0, 190.0]}, r"`theta_r`\[1\] = 190.0"),
        ({"dphi": [0.0, np.nan]}, r"`dphi`\[1\] = nan"),
        ({"wavelength_um": [0.0]}, "wavelength_um"),
        ({"chunks": {"theta": 2}}, "unknown dimension"),
        ({"chunks": {"theta_i": 0}}, "positive int"),
        ({"contrast": ("paint", "steel")}, "must name two"),
        ({"covariance": {"steel": (["n"], [[1.0]])}}, "unknown material"),
        ({"covariance": {"paint": (["n", "x"], [[1.0, 0], [0, 1]])}}, "x"),
        ({"covariance": {"paint": (["n"], [[1.0, 0.0]])}}, "shape"),
    ],
)
def test_bad_input_is_refused_with_a_message(kwargs, message) -> None:
    args = {
        "materials": {"paint": polbrdf.Material.preset("paint")},
        "wavelength_um": [0.6],
        "theta_i": [0.0, 30.0],
        "theta_r": [0.0, 30.0],
        "dphi": [180.0],
    }
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        lut(**args)


def test_refusals_of_materials_and_fits(tmp_path) -> None:
    gold = polbrdf.Material(index="library:Au/Johnson", sigma_deg=5.0)
    with pytest.raises(ValueError, match="material 'gold'"):
        lut({"gold": gold}, [5.0], [0.0], [0.0], [180.0])  # outside Johnson's data
    paint = polbrdf.Material.preset("paint")
    with pytest.raises(ValueError, match="two materials are named"):
        lut([paint, paint], [0.6], [0.0], [0.0], [180.0])
    with pytest.raises(TypeError, match="not a polbrdf.Material"):
        lut({"x": "paint"}, [0.6], [0.0], [0.0], [180.0])
    # a covariance whose fitted values are not the material's
    doc = {"parameter_order": ["n"], "parameters": {"n": {"value": 1.7}}, "covariance": [[1e-4]]}
    (tmp_path / "fit.json").write_text(json.dumps(doc))
    with pytest.raises(ValueError, match="give the fitted material"):
        lut({"p": paint}, [0.6], [0.0], [0.0], [180.0], covariance={"p": tmp_path / "fit.json"})
    (tmp_path / "bad.json").write_text('{"parameter_order": ["n"],\n "covariance": [[1e-4]')
    with pytest.raises(ValueError, match=r"bad.json:2:\d+: not valid JSON"):
        lut({"p": paint}, [0.6], [0.0], [0.0], [180.0], covariance={"p": tmp_path / "bad.json"})
    (tmp_path / "other.json").write_text('{"chi2": 1}')
    with pytest.raises(ValueError, match="not a fit.json"):
        lut({"p": paint}, [0.6], [0.0], [0.0], [180.0], covariance={"p": tmp_path / "other.json"})


# --- polbrdf lut (the command line) --------------------------------------------------------


def test_cli_table_opens_as_the_python_table(tmp_path) -> None:
    cli = os.environ.get("POLBRDF_CLI")
    if not cli:
        pytest.skip("POLBRDF_CLI not set: polbrdf lut needs the polbrdf binary")
    (tmp_path / "gold.toml").write_text(
        'name = "gold"\nindex = "library:Au/Johnson"\nsigma_deg = 8\nrho_d = 0.01\n'
    )
    (tmp_path / "lut.toml").write_text(
        'materials = ["paint", "gold.toml"]\n'
        "wavelength_um = [0.55, 0.6328, 1.0]\n"
        "theta_i_deg = { start = 0, stop = 85, count = 4 }\n"
        "theta_r_deg = [0, 20, 45, 70, 95]\n"
        "dphi_deg = [0, 45, 180, 270]\n"
        'quantities = ["aolp", "mueller", "dolp", "brdf"]\n'
    )
    out = tmp_path / "table"
    run = subprocess.run(
        [cli, "lut", "--config", str(tmp_path / "lut.toml"), "--out", str(out)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert run.returncode == 0, run.stderr
    back = polbrdf.xarray.open_lut(out)
    ti = np.linspace(0, 85, 4)
    np.testing.assert_array_equal(back.theta_i.values, ti)  # a range is numpy.linspace
    paint = polbrdf.Material.preset("paint")
    mats = {
        paint.name or "paint": paint,
        "gold": polbrdf.Material.from_toml(tmp_path / "gold.toml"),
    }
    assert list(back.material.values) == list(mats)
    want = lut(mats, WL, ti, TR, DP, quantities=polbrdf.xarray.QUANTITIES)
    assert set(back.data_vars) == set(want.data_vars)
    for v in want.data_vars:
        assert back[v].dims == want[v].dims and back[v].attrs == want[v].attrs, v
        np.testing.assert_array_equal(bits(back[v].values), bits(want[v].values), err_msg=v)
    a, b = dict(back.attrs), dict(want.attrs)
    assert json.loads(a.pop("materials_json")) == json.loads(b.pop("materials_json"))
    assert a == b
    # views of one memory-mapped table, not copies
    for v in back.data_vars:
        a = back[v].values
        while a is not None and not isinstance(a, np.memmap):
            a = a.base
        assert isinstance(a, np.memmap), v
    # and it writes as any table does
    back.to_netcdf(tmp_path / "t.nc", engine="h5netcdf")
    # into an existing directory (as every command's --out DIR): the table's files replaced as a
    # set, with the marker last, and no other file touched
    (out / "notes.txt").write_text("keep")
    table = (out / "table.npy").read_bytes()
    again = subprocess.run(
        [cli, "lut", "--config", str(tmp_path / "lut.toml"), "--out", str(out)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert again.returncode == 0, again.stderr
    assert sorted(p.name for p in out.iterdir()) == [
        "_COMPLETE", "attrs.json", "notes.txt", "table.npy"
    ]
    assert (out / "notes.txt").read_text() == "keep"
    assert (out / "table.npy").read_bytes() == table
    assert (out / "_COMPLETE").read_text() == "attrs.json\ntable.npy\n"


def test_open_lut_refuses_what_is_no_table(tmp_path) -> None:
    (tmp_path / "attrs.json").write_text('{"format": "other"}')
    with pytest.raises(ValueError, match="not a polbrdf lut sidecar"):
        polbrdf.xarray.open_lut(tmp_path)
    (tmp_path / "attrs.json").write_text("{")
    with pytest.raises(ValueError, match=r"attrs.json:1:2: not valid JSON"):
        polbrdf.xarray.open_lut(tmp_path)


def _small_table(folder, theta_r=(0.0,), edit=None) -> None:
    """A valid one-material table of ``brdf`` written by hand, ``edit`` applied to attrs.json."""
    folder.mkdir(exist_ok=True)
    shape = [1, 1, 1, len(theta_r), 1]
    np.save(folder / "table.npy", np.zeros(len(theta_r), dtype=[("brdf", "<f8")]))
    meta = {
        "format": "polbrdf-lut 1",
        "dims": ["material", "wavelength", "theta_i", "theta_r", "dphi"],
        "shape": shape,
        "columns": ["brdf"],
        "coords": {"material": ["a"], "wavelength": [0.5], "theta_i": [0.0],
                   "theta_r": list(theta_r), "dphi": [0.0]},
        "attrs": {},
        "quantities": ["brdf"],
        "table": "table.npy",
    }  # fmt: skip
    if edit:
        edit(meta)
    (folder / "attrs.json").write_text(json.dumps(meta))


def test_open_lut_refuses_a_tampered_folder_naming_file_and_key(tmp_path) -> None:
    """Issue 35: a tampered folder raised EOFError, TypeError or RecursionError, opened a
    table outside the folder, and accepted NaN or unsorted coordinates; each is a ValueError
    naming the file and the key."""
    ok = tmp_path / "ok"
    _small_table(ok)
    assert float(polbrdf.xarray.open_lut(ok).brdf.values.ravel()[0]) == 0.0
    (tmp_path / "outside.npy").write_bytes((ok / "table.npy").read_bytes())
    cases = [
        ("table outside", {"table": "../outside.npy"}, "`table`"),
        ("table absolute", {"table": str(tmp_path / "outside.npy")}, "`table`"),
        ("table a number", {"table": 5}, "`table`"),
        ("shape of strings", {"shape": ["1", 1, 1, 1, 1]}, "`shape`"),
        ("shape too long", {"shape": [1, 1, 1, 1, 1, 1]}, "`shape`"),
        ("coords a string", {"coords": "x"}, "`coords`"),
        ("theta_i a string", {"coords.theta_i": "0"}, "`coords.theta_i`"),
        ("theta_r NaN", {"coords.theta_r": [float("nan")]}, "`coords.theta_r`"),
        ("dphi infinite", {"coords.dphi": [float("inf")]}, "`coords.dphi`"),
        ("material twice", {"coords.material": ["a", "a"], "shape": [2, 1, 1, 1, 1]},
         "`coords.material`"),
        ("unknown quantity", {"quantities": ["nope"]}, "`quantities`"),
        ("quantity without its column", {"quantities": ["dolp"]}, "`columns`"),
        ("attrs a list", {"attrs": []}, "`attrs`"),
        ("format missing", {"format": None}, "`format`"),
    ]  # fmt: skip

    def edit_with(changes):
        def edit(meta):
            for k, v in changes.items():
                if k.startswith("coords."):
                    meta["coords"][k[7:]] = v
                elif v is None:
                    del meta[k]
                else:
                    meta[k] = v

        return edit

    for i, (what, changes, key) in enumerate(cases):
        d = tmp_path / f"c{i}"
        _small_table(d, edit=edit_with(changes))
        with pytest.raises(ValueError, match="attrs.json") as e:
            polbrdf.xarray.open_lut(d)
        assert key in str(e.value), (what, str(e.value))
    # Unsorted coordinates (two rows).
    d = tmp_path / "unsorted"
    _small_table(d, theta_r=(20.0, 10.0))
    with pytest.raises(ValueError, match=r"attrs.json.*`coords.theta_r` must increase strictly"):
        polbrdf.xarray.open_lut(d)
    # JSON nested past the recursion limit.
    d = tmp_path / "deep"
    _small_table(d)
    (d / "attrs.json").write_text("[" * 100_000 + "]" * 100_000)
    with pytest.raises(ValueError, match=r"attrs.json: JSON nested too deeply"):
        polbrdf.xarray.open_lut(d)
    # A truncated table.
    d = tmp_path / "truncated"
    _small_table(d)
    (d / "table.npy").write_bytes((d / "table.npy").read_bytes()[:20])
    with pytest.raises(ValueError, match=r"table.npy: not a .npy table"):
        polbrdf.xarray.open_lut(d)


def test_benchmark_script_runs_small(tmp_path) -> None:
    pytest.importorskip("zarr", reason="zarr is not installed")
    script = os.path.join(os.path.dirname(__file__), "..", "examples", "lut_bench.py")
    r = subprocess.run(
        [sys.executable, script, "table", "--wavelengths", "2", "--n", "6", "--chunk-theta-i", "2",
         "--out", str(tmp_path / "b.zarr")],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert "8.640e+02 Mueller matrices" in r.stdout and "peak RSS" in r.stdout
    assert not (tmp_path / "b.zarr").exists()  # deleted after the run
