"""Polarized thermal emission from Python: Planck's law, the emissivity Stokes vector by
Kirchhoff's law, and the observed Stokes radiance of a thermal scene — each against an
independent computation written here (NumPy Fresnel, brute-force hemispherical sums, Python
``decimal``, trapezoid band integrals), plus errors, broadcasting and element-by-element
equality with single-view calls."""

from __future__ import annotations

from decimal import Decimal, getcontext
from typing import Any

import numpy as np
import pytest

import polbrdf
from polbrdf import Material

C1L = 1.191042972e8  # 2hc², W·µm⁴·m⁻²·sr⁻¹ (CODATA 2018)
C2 = 14387.76877  # hc/k, µm·K
SIGMA_SB = 5.670374419e-8  # W·m⁻²·K⁻⁴ (CODATA 2018)


@pytest.fixture(scope="module")
def gold_ir() -> Material:
    """A spectral metal with data at 10 µm (Ordal et al.)."""
    return Material(index="library:Au/Ordal", sigma_deg=5.0)


def fresnel_rs_rp(n: float, k: float, theta_deg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Fresnel reflectances of a complex index N = n + ik from vacuum (NumPy complex
    arithmetic, principal branch of the square root)."""
    big_n = n + 1j * k
    t = np.radians(theta_deg)
    ci, si = np.cos(t), np.sin(t)
    ct = np.sqrt(1 - (si / big_n) ** 2 + 0j)
    rs = (ci - big_n * ct) / (ci + big_n * ct)
    rp = (big_n * ci - ct) / (big_n * ci + ct)
    return np.abs(rs) ** 2, np.abs(rp) ** 2


# --- (a) the smooth limit ---------------------------------------------------------------------


@pytest.mark.parametrize(("n", "k"), [(1.5, 0.0), (1.37, 7.62), (2.4, 0.3)])
def test_smooth_limit_is_one_minus_fresnel(n: float, k: float) -> None:
    # σ = 0.05°, no shadowing, no volume term: ε_s → 1 − R_s, ε_p → 1 − R_p; the gap is the
    # model's own O(σ²) (2.9e-7 at 60°, 9.8e-7 at 75° for n = 1.5) plus the quadrature's 1e-6.
    theta = np.array([0.0, 10.0, 30.0, 45.0, 60.0, 70.0])
    m = Material(n=n, k=k, sigma_deg=0.05, shadowing=False)
    e = polbrdf.emissivity(m, theta)
    rs, rp = fresnel_rs_rp(n, k, theta)
    np.testing.assert_allclose(e.eps_s, 1 - rs, rtol=0, atol=1e-6)
    np.testing.assert_allclose(e.eps_p, 1 - rp, rtol=0, atol=1e-6)
    np.testing.assert_allclose(e.eps[..., 0], 1 - (rs + rp) / 2, rtol=0, atol=1e-6)
    np.testing.assert_allclose(e.eps[..., 1], (rp - rs) / 2, rtol=0, atol=1e-6)
    # Emission DoLP |R_s − R_p|/(2 − R_s − R_p), to the 1e-6 of ε propagated through ε1/ε0
    # (a metal emits little: ε0 = 0.09 at 70°); thermal emission is p-polarized (ε1 ≤ 0).
    dolp = np.abs(rs - rp) / (2 - rs - rp)
    tol = 1e-6 * (1 + dolp) / e.eps[..., 0]
    assert (np.abs(e.dolp - dolp) < tol).all(), (e.dolp - dolp, tol)
    assert (e.eps[..., 1] <= 1e-15).all()
    assert e.valid.all()
    # Toward grazing view the remaining gap is the model's σ²: ×25 from σ = 0.05° to 0.01°.
    gaps = []
    for sigma in (0.05, 0.01):
        e85 = polbrdf.emissivity(Material(n=n, k=k, sigma_deg=sigma, shadowing=False), 85.0)
        rs85, rp85 = fresnel_rs_rp(n, k, np.array(85.0))
        gaps.append(max(abs(e85.eps_s - (1 - rs85)), abs(e85.eps_p - (1 - rp85))))
    assert 15 < gaps[0] / gaps[1] < 35, gaps


# --- (b) symmetry and reciprocity --------------------------------------------------------------


def test_eps2_eps3_vanish_and_routes_agree_for_the_standard_form() -> None:
    theta = np.arange(0.0, 90.0, 7.0)
    for m in [
        Material(n=1.5, sigma_deg=10.0, rho_d=0.02, rho_v=0.01),
        Material(n=0.5, sigma_deg=30.0),
        Material(n=1.37, k=7.62, sigma_deg=3.0),
        Material.preset("paint"),
    ]:
        e = polbrdf.emissivity(m, theta)
        assert (np.abs(e.eps[..., 2:]) < 1e-15).all() and (np.abs(e.eps_b[..., 2:]) < 1e-15).all()
        assert (e.reciprocity_residual < 1e-12).all(), (m, e.reciprocity_residual.max())
        np.testing.assert_allclose(e.eps, e.eps_b, rtol=0, atol=1e-12)
        assert e.reciprocity_residual.dtype == np.float64 and e.valid.dtype == np.bool_


def test_eq3_azimuth_factor_is_not_reciprocal() -> None:
    m = Material(n=1.5, sigma_deg=20.0, azimuth_term="eq3")
    e = polbrdf.emissivity(m, [60.0, 75.0])
    assert (e.reciprocity_residual > 1e-4).all(), e.reciprocity_residual
    want = np.abs(e.eps - e.eps_b).max(axis=-1)
    np.testing.assert_array_equal(e.reciprocity_residual, want)


def test_derived_quantities_follow_from_eps() -> None:
    e = polbrdf.emissivity(Material.preset("paint"), np.arange(0.0, 90.0, 1.0))
    np.testing.assert_allclose(e.eps_s, e.eps[..., 0] + e.eps[..., 1], rtol=0, atol=1e-16)
    np.testing.assert_allclose(e.eps_p, e.eps[..., 0] - e.eps[..., 1], rtol=0, atol=1e-16)
    np.testing.assert_allclose(e.dolp, polbrdf.stokes_dolp(e.eps), rtol=1e-15, atol=1e-16)
    # The paint preset is valid up to 87° and not beyond (ε_s < 0 toward grazing view).
    assert e.valid[:88].all() and not e.valid[88:].any()
    assert (e.eps_s[88:] < 0).all()


# --- (c) against a brute-force hemispherical sum ----------------------------------------------


def test_emissivity_against_brute_force_midpoint_integrals() -> None:
    # A broad lobe (σ = 25°) and a volume term: midpoint rule over a 600 × 1200 (θ, φ) grid.
    m = Material(n=1.6, k=0.05, sigma_deg=25.0, rho_d=0.02)
    tr = 50.0
    nt, nph = 600, 1200
    dt, dp = 90.0 / nt, 360.0 / nph
    th = (np.arange(nt) + 0.5) * dt
    ph = (np.arange(nph) + 0.5) * dp
    w = (np.cos(np.radians(th)) * np.sin(np.radians(th)))[:, None] * np.radians(dt) * np.radians(dp)
    # Route B, ε_B0 = 1 − albedo: light incident from the view direction, reflected everywhere.
    albedo = float((polbrdf.brdf(m, tr, 0.0, th[:, None], ph[None, :]) * w).sum())
    # Route A: the first column of F over the incidence hemisphere, in blocks of rows.
    col = np.zeros(4)
    for rows in np.array_split(np.arange(nt), 6):
        f = polbrdf.mueller(m, th[rows, None], ph[None, :], tr, 0.0)
        col += np.einsum("ij,ijk->k", w[rows], f[..., :, 0])
    e = polbrdf.emissivity(m, tr)
    assert abs(e.eps_b[0] - (1 - albedo)) < 2e-5, (e.eps_b, albedo)
    assert abs(e.eps[0] - (1 - col[0])) < 2e-5, (e.eps, col)
    assert abs(e.eps[1] + col[1]) < 2e-5, (e.eps, col)
    assert abs(col[2]) < 1e-12 and abs(col[3]) < 1e-12


# --- (d)–(g) the observed radiance -------------------------------------------------------------


VIEWS_T = np.array([0.0, 25.0, 50.0, 70.0, 85.0])[:, None]
VIEWS_P = np.array([0.0, 57.0, 180.0, -120.0])[None, :]


@pytest.mark.parametrize(
    "material",
    [
        Material(n=1.5, sigma_deg=10.0),
        Material(n=1.37, k=7.62, sigma_deg=30.0, rho_d=0.01),
        Material.preset("paint"),
        Material(index="library:Au/Ordal", sigma_deg=5.0),
    ],
    ids=["glass", "metal", "paint", "Au/Ordal"],
)
@pytest.mark.parametrize(("lam", "t"), [(10.0, 300.0), (4.0, 350.0)])
def test_isothermal_enclosure_is_unpolarized_blackbody(
    material: Material, lam: float, t: float
) -> None:
    r = polbrdf.radiance(
        material, VIEWS_T, VIEWS_P, wavelength_um=lam, temperature_k=t, sky="thermal",
        sky_temperature_k=t,
    )  # fmt: skip
    b = polbrdf.planck(lam, t)
    assert r.stokes.shape == (5, 4, 4)
    np.testing.assert_allclose(r.stokes[..., 0] / b, 1.0, rtol=0, atol=1e-12)
    assert (np.abs(r.stokes[..., 1:]) < 1e-12 * b).all()
    # Emission and reflection each polarized, in opposite senses.
    np.testing.assert_allclose(r.emitted[..., 1], -r.reflected[..., 1], rtol=0, atol=1e-12 * b)
    assert (r.dolp < 1e-12).all()


def test_s1_flips_between_a_warm_and_a_cold_sky() -> None:
    m = Material(n=1.5, k=0.02, sigma_deg=15.0)
    common: dict[str, Any] = {"wavelength_um": 10.0, "sky": "thermal"}
    warm = polbrdf.radiance(m, 60.0, 0.0, temperature_k=280.0, sky_temperature_k=320.0, **common)
    cold = polbrdf.radiance(m, 60.0, 0.0, temperature_k=300.0, sky_temperature_k=230.0, **common)
    assert warm.stokes[1] > 0 and cold.stokes[1] < 0
    assert warm.aolp == pytest.approx(0.0, abs=1e-12)  # s-polarized: reflection wins
    assert cold.aolp == pytest.approx(90.0, abs=1e-12)  # p-polarized: emission wins
    rad = polbrdf.radiance(
        m, np.radians(60.0), 0.0, degrees=False, temperature_k=300.0, sky_temperature_k=230.0,
        **common,
    )  # fmt: skip
    assert rad.aolp == pytest.approx(np.pi / 2, abs=1e-12)
    # S = L_d·e0 + (B(T) − L_d)·ε exactly, for the uniform sky.
    e = polbrdf.emissivity(m, 60.0)
    b, ld = polbrdf.planck(10.0, 300.0), polbrdf.planck(10.0, 230.0)
    np.testing.assert_allclose(cold.stokes, ld * np.array([1, 0, 0, 0]) + (b - ld) * e.eps,
                               rtol=1e-13, atol=1e-15)  # fmt: skip
    np.testing.assert_allclose(cold.emitted, b * e.eps, rtol=1e-15)


def test_constant_profile_sky_equals_the_uniform_sky() -> None:
    m = Material(n=1.5, sigma_deg=10.0, rho_d=0.03, rho_v=0.01)
    common: dict[str, Any] = {"wavelength_um": 10.0, "temperature_k": 300.0}
    prof = polbrdf.radiance(
        m, VIEWS_T[:4], VIEWS_P, sky="profile",
        sky_profile=([0.0, 30.0, 60.0, 90.0], [5.0] * 4), **common,
    )  # fmt: skip
    uni = polbrdf.radiance(m, VIEWS_T[:4], VIEWS_P, sky="uniform", sky_radiance=5.0, **common)
    scale = uni.reflected[..., :1]
    assert (np.abs(prof.reflected - uni.reflected) < 1e-7 * scale).all()
    assert (np.abs(prof.stokes - uni.stokes) < 1e-7 * scale).all()
    np.testing.assert_array_equal(prof.emitted, uni.emitted)
    # An azimuth-independent sky over an isotropic surface: nothing depends on φr.
    slope = polbrdf.radiance(
        m, VIEWS_T[:4], VIEWS_P, sky="profile", sky_profile=([0.0, 90.0], [1.0, 4.0]), **common
    )
    np.testing.assert_allclose(
        slope.stokes, np.broadcast_to(slope.stokes[:, :1], (4, 4, 4)), rtol=1e-12, atol=1e-15
    )
    assert (slope.reflected[:, 0, 0] > prof.reflected[:, 0, 0] / 5).all()  # brighter than 1


def test_band_radiance_is_the_band_integral_of_planck() -> None:
    # A flat response over 8–12 µm and a constant index: emitted = ε·∫B dλ, reflected =
    # L_d·(e0 − ε)·∫R dλ, the path radiance ∫R dλ·L_path; W·m⁻²·sr⁻¹.
    m = Material(n=1.5, k=0.02, sigma_deg=15.0)
    band = (np.array([8.0, 12.0]), np.array([1.0, 1.0]))
    r = polbrdf.radiance(
        m, [0.0, 40.0, 75.0], 0.0, band=band, temperature_k=300.0, sky="uniform",
        sky_radiance=2.0, transmittance=0.8, path_radiance=0.5,
    )  # fmt: skip
    lam = np.linspace(8.0, 12.0, 400_001)
    integral = np.trapezoid(polbrdf.planck(lam, 300.0), lam)
    e = polbrdf.emissivity(m, [0.0, 40.0, 75.0])
    np.testing.assert_allclose(r.emitted[:, :2], integral * e.eps[:, :2], rtol=1e-6)
    assert (r.emitted[:, 2:] == 0).all()
    e0 = np.array([1.0, 0, 0, 0])
    np.testing.assert_allclose(r.reflected, 2.0 * 4.0 * (e0 - e.eps), rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(
        r.stokes, 0.8 * (r.emitted + r.reflected) + 0.5 * 4.0 * e0, rtol=1e-14, atol=1e-14
    )


def test_band_radiance_of_a_spectral_metal(gold_ir: Material) -> None:
    # ∫ B(λ, T)·ε(λ) dλ over 8–12 µm against a trapezoid sum of emissivity(λ) on 401 points.
    band = (np.array([8.0, 12.0]), np.array([1.0, 1.0]))
    r = polbrdf.radiance(gold_ir, 40.0, 0.0, band=band, temperature_k=300.0)
    lam = np.linspace(8.0, 12.0, 401)
    e = polbrdf.emissivity(gold_ir, 40.0, wavelength_um=lam)
    want = np.trapezoid(polbrdf.planck(lam, 300.0)[:, None] * e.eps, lam, axis=0)
    np.testing.assert_allclose(r.emitted[:2], want[:2], rtol=2e-6)
    fine = polbrdf.radiance(gold_ir, 40.0, 0.0, band=band, band_step_um=0.01, temperature_k=300.0)
    np.testing.assert_allclose(fine.emitted, r.emitted, rtol=1e-10)


# --- (h) Planck's law --------------------------------------------------------------------------


def planck_decimal(lam: float, t: float) -> float:
    getcontext().prec = 40
    x = Decimal(C2) / (Decimal(lam) * Decimal(t))
    return float(Decimal(C1L) / (Decimal(lam) ** 5 * (x.exp() - 1)))


def test_planck_against_decimal_evaluation() -> None:
    cases = [(10.0, 300.0), (4.0, 300.0), (0.5, 5772.0), (12.0, 250.0), (3.7, 1000.0),
             (0.3, 100.0), (1000.0, 3.0), (1e-3, 1e5), (8.5, 77.0)]  # fmt: skip
    lam = np.array([c[0] for c in cases])
    t = np.array([c[1] for c in cases])
    want = np.array([planck_decimal(*c) for c in cases])
    got = polbrdf.planck(lam, t)
    np.testing.assert_allclose(got, want, rtol=1e-13, atol=0)
    assert polbrdf.planck(10.0, 300.0) == pytest.approx(9.924033343570319, rel=1e-14)
    assert isinstance(polbrdf.planck(10, 300), np.float64)
    # Far beyond the exponential's range: 0, not an error.
    assert polbrdf.planck(0.1, 10.0) == 0.0


@pytest.mark.parametrize("t", [300.0, 1000.0, 5772.0])
def test_stefan_boltzmann_law(t: float) -> None:
    # ∫ B_λ dλ = σT⁴/π: midpoint rule in ln λ over a wide range.
    x_lo, x_hi = np.log(0.05 * 300.0 / t), np.log(5000.0 * 300.0 / t)
    n = 200_000
    h = (x_hi - x_lo) / n
    lam = np.exp(x_lo + (np.arange(n) + 0.5) * h)
    integral = float((polbrdf.planck(lam, t) * lam).sum() * h)
    assert integral / (SIGMA_SB * t**4 / np.pi) == pytest.approx(1.0, abs=1e-6)


def test_brightness_temperature_inverts_planck() -> None:
    lam = np.array([0.5, 4.0, 10.0, 12.0])[:, None]
    t = np.array([77.0, 250.0, 300.0, 1000.0, 5772.0])[None, :]
    b = polbrdf.planck(lam, t)
    got = polbrdf.brightness_temperature(lam, b)
    assert got.shape == (4, 5)
    np.testing.assert_allclose(got, np.broadcast_to(t, (4, 5)), rtol=1e-13)
    assert polbrdf.brightness_temperature(10.0, polbrdf.planck(10.0, 300.0)) == pytest.approx(300.0)


# --- (i) errors ---------------------------------------------------------------------------------


PAINT = Material.preset("paint")
AT10: dict[str, Any] = {"wavelength_um": 10.0}


@pytest.mark.parametrize(
    ("call", "pattern"),
    [
        (
            lambda: polbrdf.emissivity(PAINT, 90),
            r"`theta_r` = 90 \(at index 0\).*above the horizon",
        ),
        (lambda: polbrdf.emissivity(PAINT, [10, -1]), r"`theta_r` = -1 \(at index 1\)"),
        (lambda: polbrdf.emissivity(PAINT, [0, np.nan]), r"`theta_r` = NaN \(at index 1\)"),
        (lambda: polbrdf.emissivity(PAINT, 1.6, degrees=False), r"`theta_r` = 1\.6 \(at index 0\)"),
        (lambda: polbrdf.radiance(PAINT, [10, 90], 0, **AT10), r"`theta_r` = 90 \(at index 1\)"),
        (lambda: polbrdf.radiance(PAINT, 10, np.inf, **AT10), r"`phi_r` = inf \(at index 0\)"),
        (lambda: polbrdf.radiance(PAINT, 10, 0, temperature_k=0, **AT10), r"`temperature_k` = 0:"),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, temperature_k=-5, **AT10),
            r"`temperature_k` = -5:",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, temperature_k=np.nan, **AT10),
            r"`temperature_k` = NaN",
        ),
        (lambda: polbrdf.radiance(PAINT, 10, 0, wavelength_um=0), r"`wavelength_um` = 0"),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, wavelength_um=[8, 9]),
            r"`wavelength_um` must be a scalar",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, wavelength_um=10, band=([8, 12], [1, 1])),
            r"`wavelength_um`.*`band`.*not both",
        ),
        (lambda: polbrdf.radiance(PAINT, 10, 0), r"give `wavelength_um`.*or `band`"),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sky="uniform", **AT10),
            r'sky = "uniform" needs `sky_radiance`',
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sky="thermal", **AT10),
            r'sky = "thermal" needs `sky_temperature_k`',
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sky="profile", **AT10),
            r'sky = "profile" needs `sky_profile`',
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sky="thermal", sky_temperature_k=250, sky_radiance=3.0, **AT10
            ),
            r'`sky_radiance` does not apply to sky = "thermal"',
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sky_radiance=3.0, **AT10),
            r'`sky_radiance` does not apply to sky = "none"',
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sky="cloudy", **AT10),
            r"invalid `sky`: unknown sky model `cloudy`",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sky="uniform", sky_radiance=-1, **AT10),
            r"`sky_radiance` = -1",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sky="thermal", sky_temperature_k=0, **AT10),
            r"`sky_temperature_k` = 0",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, transmittance=1.5, **AT10),
            r"`transmittance` = 1\.5",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, path_radiance=-0.1, **AT10),
            r"`path_radiance` = -0\.1",
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sky="profile", sky_profile=([0, 50, 40, 90], [1, 1, 1, 1]), **AT10
            ),
            r"`sky_profile`: .*`zenith_deg` = 40 \(at index 2\)",
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sky="profile", sky_profile=([0, 80], [1, 1]), **AT10
            ),
            r"`sky_profile`: .*from zenith 0° to 90°",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, band=([8, 10, 12], [1, -1, 1])),
            r"`band`: invalid parameter `response` = -1 \(at index 1\)",
        ),
        (lambda: polbrdf.radiance(PAINT, 10, 0, band=([8, 12], [0, 0])), r"band.*zero everywhere"),
        (lambda: polbrdf.radiance(PAINT, 10, 0, band=([8, 12], [1, 1, 1])), r"`band`.*`response`"),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, band_step_um=0.1, **AT10),
            r"`band_step_um`.*give `band`",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, band=([8, 12], [1, 1]), band_step_um=0),
            r"`band_step_um` = 0",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, band=([8, 12], [1, 1]), band_step_um=1e-300),
            r"`band_step_um` = 1e-300.*more than",
        ),
        (lambda: polbrdf.radiance(PAINT, 10, 0, band=([[8, 12]], [1, 1])), r"`band`.*1-D"),
        (lambda: polbrdf.planck(10, 0), r"`temperature_k` = 0 \(at index 0\)"),
        (lambda: polbrdf.planck(10, [300, -5]), r"`temperature_k` = -5 \(at index 1\)"),
        (lambda: polbrdf.planck(10, [300, np.nan]), r"`temperature_k` = NaN \(at index 1\)"),
        (lambda: polbrdf.planck([10, 0], 300), r"`wavelength_um` = 0 \(at index 1\)"),
        (lambda: polbrdf.planck(np.inf, 300), r"`wavelength_um` = inf \(at index 0\)"),
        (lambda: polbrdf.brightness_temperature(10, [1.0, 0.0]), r"`radiance` = 0 \(at index 1\)"),
        (lambda: polbrdf.brightness_temperature(-1, 1.0), r"`wavelength_um` = -1 \(at index 0\)"),
    ],
)
def test_errors_name_the_argument(call: Any, pattern: str) -> None:
    with pytest.raises(ValueError, match=pattern):
        call()


def test_paper_form_has_no_emissivity() -> None:
    paper = Material(n=1.5, sigma_deg=10.0, form="paper")
    with pytest.raises(ValueError, match=r"`paper` form has no emissivity"):
        polbrdf.emissivity(paper, 30)
    with pytest.raises(ValueError, match=r"`paper` form"):
        polbrdf.radiance(paper, 30, 0, wavelength_um=10, temperature_k=300)


def test_spectral_material_errors(gold_ir: Material) -> None:
    with pytest.raises(ValueError, match=r"spectral index .*give wavelength_um="):
        polbrdf.emissivity(gold_ir, 30)
    with pytest.raises(ValueError, match=r"`wavelength_um` = 0 \(at index 1\)"):
        polbrdf.emissivity(gold_ir, 30, wavelength_um=[10, 0])
    with pytest.raises(ValueError, match=r"wavelength 500 µm \(element 2\).*Au/Ordal") as e:
        polbrdf.emissivity(gold_ir, [[30], [40]], wavelength_um=[10, 12, 500])
    assert e.value.index == 2  # type: ignore[attr-defined]
    assert any("position (0, 2) of the broadcast shape (2, 3)" in n for n in e.value.__notes__)
    with pytest.raises(ValueError, match=r"Au/Ordal"):
        polbrdf.radiance(gold_ir, 30, 0, band=([200, 300], [1, 1]), temperature_k=300)
    # A constant index does not depend on λ but a wavelength must still be one.
    with pytest.raises(ValueError, match=r"`wavelength_um` = -2 \(at index 0\)"):
        polbrdf.emissivity(PAINT, 30, wavelength_um=-2)


def test_error_positions_in_the_broadcast_shape() -> None:
    with pytest.raises(ValueError, match="theta_r") as e:
        polbrdf.radiance(PAINT, [[10.0], [90.0]], [0.0, 90.0, 180.0], wavelength_um=10)
    assert e.value.index == 3 and e.value.argument == "theta_r"  # type: ignore[attr-defined]
    assert any("position (1, 0) of the broadcast shape (2, 3)" in n for n in e.value.__notes__)
    with pytest.raises(ValueError, match="temperature_k") as e:
        polbrdf.planck([[10.0], [4.0]], [300.0, 0.0])
    assert e.value.index == 1 and e.value.argument == "temperature_k"  # type: ignore[attr-defined]
    assert any("position (0, 1) of the broadcast shape (2, 2)" in n for n in e.value.__notes__)


def test_type_errors() -> None:
    with pytest.raises(TypeError, match="Material"):
        polbrdf.emissivity("paint", 30)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="Material"):
        polbrdf.radiance("paint", 30, 0, wavelength_um=10)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="theta_r"):
        polbrdf.emissivity(PAINT, ["a"])
    with pytest.raises(TypeError, match="`band` must be a pair"):
        polbrdf.radiance(PAINT, 30, 0, band=np.ones(3))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="`sky` must be a string"):
        polbrdf.radiance(PAINT, 30, 0, wavelength_um=10, sky=3)  # type: ignore[call-overload]
    with pytest.raises(ValueError, match="broadcast"):
        polbrdf.planck([1.0, 2.0], [300.0, 200.0, 100.0])


# --- (j) broadcasting, (k) element-by-element equality ----------------------------------------


def test_broadcast_shapes(gold_ir: Material) -> None:
    r = polbrdf.radiance(
        PAINT, np.linspace(0, 80, 5)[:, None], np.array([[0.0, 90.0, 180.0]]), wavelength_um=10,
        temperature_k=300, sky="thermal", sky_temperature_k=250,
    )  # fmt: skip
    assert r.stokes.shape == r.emitted.shape == r.reflected.shape == (5, 3, 4)
    assert r.dolp.shape == r.aolp.shape == (5, 3)
    one = polbrdf.radiance(PAINT, 30, 0, wavelength_um=10, temperature_k=300)
    assert one.stokes.shape == (4,) and np.ndim(one.dolp) == 0 and np.ndim(one.aolp) == 0
    assert polbrdf.radiance(PAINT, [], 0, wavelength_um=10).stokes.shape == (0, 4)
    e = polbrdf.emissivity(gold_ir, np.array([0.0, 30, 60, 85])[:, None], wavelength_um=[[5, 10]])
    assert e.eps.shape == e.eps_b.shape == (4, 2, 4)
    for a in (e.eps_s, e.eps_p, e.dolp, e.reciprocity_residual, e.valid):
        assert a.shape == (4, 2)
    s = polbrdf.emissivity(PAINT, 30)
    assert s.eps.shape == (4,) and isinstance(s.eps_s, np.float64)
    assert isinstance(s.valid, np.bool_)
    assert polbrdf.emissivity(PAINT, np.zeros((0, 2))).eps.shape == (0, 2, 4)
    assert polbrdf.planck(np.ones((2, 1, 3)), np.ones(4)[:, None] * 300).shape == (2, 4, 3)


def test_emissivity_equals_single_calls(gold_ir: Material) -> None:
    theta = np.array([0.0, 30.0, 30.0, 72.5])[:, None]  # a repeated angle
    lam = np.array([[5.0, 10.0, 5.0]])  # a repeated wavelength
    e = polbrdf.emissivity(gold_ir, theta, wavelength_um=lam)
    for i, j in np.ndindex(4, 3):
        one = polbrdf.emissivity(gold_ir, theta[i, 0], wavelength_um=lam[0, j])
        for got, want in zip(e, one):
            np.testing.assert_array_equal(got[i, j], want)
    # Radians agree with degrees; a constant index ignores the wavelength.
    rad = polbrdf.emissivity(gold_ir, np.radians(theta), degrees=False, wavelength_um=lam)
    np.testing.assert_allclose(rad.eps, e.eps, rtol=1e-14, atol=1e-15)
    c = polbrdf.emissivity(PAINT, theta, wavelength_um=lam)
    np.testing.assert_array_equal(c.eps, np.broadcast_to(polbrdf.emissivity(PAINT, theta).eps,
                                                         (4, 3, 4)))  # fmt: skip
    # The emissivity at a wavelength is that of the constant index there.
    n = polbrdf.index(gold_ir, 10.0)
    const = Material(n=n.real, k=n.imag, sigma_deg=5.0)
    np.testing.assert_array_equal(e.eps[:, 1], polbrdf.emissivity(const, theta[:, 0]).eps)


@pytest.mark.parametrize(
    "scene",
    [
        {"sky": "thermal", "sky_temperature_k": 250.0, "temperature_k": 300.0},
        {"sky": "profile", "sky_profile": ([0.0, 45.0, 90.0], [2.0, 3.0, 6.0]),
         "temperature_k": 280.0, "transmittance": 0.7, "path_radiance": 0.3},
    ],
    ids=["thermal", "profile"],
)  # fmt: skip
def test_radiance_equals_single_view_calls(gold_ir: Material, scene: dict[str, Any]) -> None:
    theta = np.array([[0.0], [40.0], [40.0], [80.0]])
    phi = np.array([[0.0, 135.0, -90.0]])
    r = polbrdf.radiance(gold_ir, theta, phi, wavelength_um=10.0, **scene)
    for i, j in np.ndindex(4, 3):
        one = polbrdf.radiance(gold_ir, theta[i, 0], phi[0, j], wavelength_um=10.0, **scene)
        for got, want in zip(r, one):
            np.testing.assert_array_equal(got[i, j], want)
    np.testing.assert_allclose(r.dolp, polbrdf.stokes_dolp(r.stokes), rtol=1e-15, atol=1e-300)
    np.testing.assert_allclose(r.aolp, polbrdf.stokes_aolp(r.stokes), rtol=1e-14, atol=1e-12)
    rad = polbrdf.radiance(gold_ir, np.radians(theta), np.radians(phi), degrees=False,
                           wavelength_um=10.0, **scene)  # fmt: skip
    np.testing.assert_allclose(rad.stokes, r.stokes, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(np.degrees(rad.aolp), r.aolp, rtol=1e-12, atol=1e-9)
