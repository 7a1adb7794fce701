"""polbrdf.fit: the fitting engine from NumPy, against data made by the model itself."""

from __future__ import annotations

import numpy as np
import pytest

import polbrdf


def _truth() -> polbrdf.Material:
    return polbrdf.Material(n=1.58, sigma_deg=11.0, rho_d=0.025, rho_v=0.012)


def _geometry() -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(7)
    n = 400
    return (
        rng.uniform(0, 75, n),
        rng.uniform(0, 360, n),
        rng.uniform(0, 75, n),
        rng.uniform(0, 360, n),
    )


def test_recovers_known_parameters_within_their_errors() -> None:
    ti, pi, tr, pr = _geometry()
    e = polbrdf.evaluate(_truth(), ti, pi, tr, pr)
    rng = np.random.default_rng(1)
    s_brdf = 0.03 * e.brdf + 1e-4
    s_dolp = np.full_like(e.dolp, 0.01)
    data = {"brdf": e.brdf + s_brdf * rng.standard_normal(ti.size),
            "dolp": e.dolp + s_dolp * rng.standard_normal(ti.size)}
    start = polbrdf.Material(n=1.4, sigma_deg=20.0, rho_d=0.01, rho_v=0.0)
    r = polbrdf.fit(start, ti, pi, tr, pr, data, "n,sigma_deg,rho_d,rho_v",
                    sigma={"brdf": s_brdf, "dolp": s_dolp})
    assert r.converged, r.message
    assert r.names == ["n", "sigma_deg", "rho_d", "rho_v"]
    truth = np.array([1.58, 11.0, 0.025, 0.012])
    assert np.all(np.abs(r.values - truth) < 4 * r.stderr), (r.values, r.stderr)
    assert r.covariance.shape == (4, 4) and r.correlation.shape == (4, 4)
    assert np.allclose(np.sqrt(np.diag(r.covariance)), r.stderr)
    assert np.allclose(np.diag(r.correlation), 1.0)
    assert 0.7 < r.reduced_chi2 < 1.4
    assert not r.uncertainty_from_residuals
    assert r.dof == 2 * ti.size - 4
    assert r.residuals.shape == (2 * ti.size,)
    assert r.material.n == pytest.approx(r.values[0])
    assert "n=" in repr(r)


def test_nan_means_not_measured_and_mueller_entries_fit_with_dolp() -> None:
    truth = polbrdf.Material(n=1.55, k=0.8, sigma_deg=12.0)
    ti, pi, tr, pr = _geometry()
    F = polbrdf.mueller(truth, ti, pi, tr, pr)
    m23 = F[..., 2, 3].copy()
    m23[::2] = np.nan  # half of the rows did not measure F23
    dolp = polbrdf.dolp(truth, ti, pi, tr, pr)
    start = polbrdf.Material(n=1.9, k=0.3, sigma_deg=12.0)
    r = polbrdf.fit(start, ti, pi, tr, pr, {"dolp": dolp, "m23": m23}, ["n", "k"])
    assert r.dof == ti.size + ti.size // 2 - 2
    assert r.values == pytest.approx([1.55, 0.8], rel=1e-5)
    assert r.uncertainty_from_residuals


def test_broadcasting_of_angles_and_data() -> None:
    truth = polbrdf.Material(n=1.6, sigma_deg=9.0)
    theta_r = np.linspace(0, 70, 15)
    phi_r = np.array([[0.0], [90.0], [180.0]])
    brdf = polbrdf.brdf(truth, 30, 0, theta_r, phi_r)  # shape (3, 15)
    r = polbrdf.fit(polbrdf.Material(n=1.6, sigma_deg=20.0), 30, 0, theta_r, phi_r,
                    {"brdf": brdf}, ["sigma_deg"])
    assert r.values[0] == pytest.approx(9.0, rel=1e-6)
    assert r.dof == 45 - 1


def test_refusals_are_value_errors() -> None:
    m = polbrdf.Material.preset("paint")
    with pytest.raises(ValueError, match="too few"):
        polbrdf.fit(m, [10, 20], 0, [10, 20], 180, {"brdf": [1.0, 2.0]}, ["n", "sigma_deg"])
    with pytest.raises(ValueError, match="`gloss`"):
        polbrdf.fit(m, [10, 20, 30], 0, [10, 20, 30], 180, {"brdf": [1.0, 2.0, 3.0]}, ["gloss"])
    with pytest.raises(ValueError, match="unknown measured quantity `albedo`"):
        polbrdf.fit(m, [10, 20, 30], 0, [10, 20, 30], 180, {"albedo": [1.0, 2.0, 3.0]}, ["n"])
    with pytest.raises(ValueError, match="uncertainty"):
        polbrdf.fit(m, [10, 20, 30], 0, [10, 20, 30], 180, {"brdf": [1.0, 2.0, 3.0]}, ["n"],
                    sigma={"brdf": [0.1, 0.0, 0.1]})
    with pytest.raises(ValueError, match="theta_i"):
        polbrdf.fit(m, [10, np.inf, 30], 0, [10, 20, 30], 180, {"brdf": [1.0, 2.0, 3.0]}, ["n"])
    with pytest.raises(ValueError, match="cannot be determined"):
        polbrdf.fit(m, [40] * 8, 0, [40] * 8, 180, {"brdf": [3.0] * 8}, ["a", "sigma_deg"])


def _fit_at_bound() -> polbrdf.FitResult:
    """A dielectric (k = 0) without noise, k free: the best k is its bound 0."""
    truth = polbrdf.Material(n=1.5, sigma_deg=10.0, rho_d=0.02)
    ti, pi, tr, pr = _geometry()
    e = polbrdf.evaluate(truth, ti, pi, tr, pr)
    start = polbrdf.Material(n=1.45, k=0.05, sigma_deg=12.0, rho_d=0.02)
    return polbrdf.fit(start, ti, pi, tr, pr, {"brdf": e.brdf, "dolp": e.dolp},
                       ["n", "k", "sigma_deg"], sigma={"brdf": 0.02 * e.brdf, "dolp": 0.005})


def test_a_parameter_at_its_bound_has_an_upper_limit_not_a_standard_error() -> None:
    r = _fit_at_bound()
    assert r.names == ["n", "k", "sigma_deg"]
    b = r.bounds
    assert b[0] is None and b[2] is None
    assert b[1] is not None and b[1]["bound"] == "lower"
    assert r.values[1] == 0.0 and np.isnan(r.stderr[1])
    assert 0.0 < b[1]["upper_limit_95"] < 0.5
    c = b[1]["correlation_at_limit"]
    assert c.shape == (3,) and c[1] == pytest.approx(1.0)
    assert r.values[0] == pytest.approx(1.5, abs=1e-6)


def _same(a: object, b: object) -> bool:
    """Equality of attribute values, NaN equal to NaN, arrays and dicts compared element-wise."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(np.asarray(a), np.asarray(b), equal_nan=True)
    if isinstance(a, float) and isinstance(b, float):
        return a == b or (np.isnan(a) and np.isnan(b))
    return a == b


def test_a_fit_result_pickles_with_every_attribute() -> None:
    # Issue 18 (item 17): a FitResult survives pickle (and so multiprocessing and dask) with
    # every attribute bit for bit, a parameter at its bound (NaN stderr, upper limit) included.
    import pickle

    r = _fit_at_bound()
    q = pickle.loads(pickle.dumps(r))
    assert type(q) is type(r)
    names = [a for a in dir(r) if not a.startswith("_")]
    assert {"values", "stderr", "bounds", "covariance", "residuals", "material"} <= set(names)
    for a in names:
        assert _same(getattr(q, a), getattr(r, a)), a
    assert repr(q) == repr(r)
