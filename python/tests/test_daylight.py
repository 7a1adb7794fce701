"""Daylight scenes from Python: ``polbrdf.radiance`` with a sun (``sun=``), the CIE clear sky
(``sky="cie-clear"``) and a tabulated Stokes sky (``sky="table"``) — each against physics
computed here from other public functions (``polbrdf.mueller``, ``polbrdf.emissivity``, the
uniform and profile skies) or against a symmetry of the scene (superposition, rotation about
the normal, mirror in the sun's plane), never against hard-coded outputs; plus the errors."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import polbrdf
from polbrdf import Material

PAINT = Material.preset("paint")  # a dielectric with volume terms (rho_d, rho_v > 0)
METAL = Material(n=1.4, k=7.5, sigma_deg=6.0)  # a rough conductor: circular polarization too
#: A surface that reflects only through its volume term: n = 1 has no Fresnel reflection.
LAMBERT = Material(n=1.0, sigma_deg=10.0, rho_d=0.1)
AT10: dict[str, Any] = {"wavelength_um": 10.0}
E0 = np.array([1.0, 0.0, 0.0, 0.0])

#: A grid of views (degrees) over the hemisphere, 2-D to exercise the broadcast shape.
VIEW_T, VIEW_P = np.meshgrid([0.0, 15.0, 40.0, 62.0, 84.0], [0.0, 37.0, 151.0, 200.0, 333.0])
#: Sun Stokes vectors, not normalized (the function normalizes them to s0 = 1).
SUN_STOKES = [
    (1.0, 0.0, 0.0, 0.0),
    (2.0, 0.6, -0.8, 0.5),
    (0.5, 0.0, 0.0, -0.5),
    (3.0, -3.0, 0.0, 0.0),
]


def clear_sky(**kw: Any) -> dict[str, Any]:
    return {"sky": "cie-clear", **AT10, **kw}


def sun_term(
    m: Material,
    sun: tuple[float, float, float],
    stokes: Any,
    theta_r: Any,
    phi_r: Any,
    degrees: bool = True,
) -> np.ndarray:
    """``E·cosθs·F(w_s, w_r)·s`` with ``s`` normalized to s0 = 1, from ``polbrdf.mueller``."""
    zenith, azimuth, e = sun
    s = np.asarray(stokes, dtype=float)
    s = s / s[0]
    f = polbrdf.mueller(m, zenith, azimuth, theta_r, phi_r, degrees=degrees, **AT10)
    cos_s = np.cos(np.radians(zenith) if degrees else zenith)
    return e * cos_s * (f @ s)


# --- The sun ---------------------------------------------------------------------------------


@pytest.mark.parametrize("stokes", SUN_STOKES)
@pytest.mark.parametrize("sun", [(0.0, 0.0, 700.0), (35.0, 20.0, 900.0), (72.0, 250.0, 40.0)])
@pytest.mark.parametrize("m", [PAINT, METAL], ids=["paint", "metal"])
def test_sun_at_the_specular_direction_is_e_cos_f_s(
    m: Material, sun: tuple[float, float, float], stokes: Any
) -> None:
    zenith, azimuth, _ = sun
    r = polbrdf.radiance(m, zenith, azimuth + 180.0, sun=(*sun, stokes), **AT10)
    expected = sun_term(m, sun, stokes, zenith, azimuth + 180.0)
    np.testing.assert_allclose(r.reflected, expected, rtol=1e-12, atol=1e-12 * expected[0])
    # No emission, no atmosphere: the sensor sees the reflected sun.
    np.testing.assert_array_equal(r.emitted, np.zeros(4))
    np.testing.assert_array_equal(r.stokes, r.reflected)
    assert r.dolp == pytest.approx(polbrdf.stokes_dolp(expected), rel=1e-10, abs=1e-14)


@pytest.mark.parametrize("stokes", SUN_STOKES)
def test_sun_term_at_every_view_of_a_grid(stokes: Any) -> None:
    sun = (48.0, 130.0, 500.0)
    r = polbrdf.radiance(METAL, VIEW_T, VIEW_P, sun=(*sun, stokes), **AT10)
    assert r.stokes.shape == VIEW_T.shape + (4,)
    expected = sun_term(METAL, sun, stokes, VIEW_T, VIEW_P)
    scale = expected[..., 0].max()
    np.testing.assert_allclose(r.reflected, expected, rtol=1e-12, atol=1e-13 * scale)


def test_sun_angles_follow_degrees() -> None:
    sun_deg = (35.0, 20.0, 900.0, SUN_STOKES[1])
    sun_rad = (np.radians(35.0), np.radians(20.0), 900.0, SUN_STOKES[1])
    a = polbrdf.radiance(PAINT, VIEW_T, VIEW_P, sun=sun_deg, **AT10)
    b = polbrdf.radiance(
        PAINT, np.radians(VIEW_T), np.radians(VIEW_P), degrees=False, sun=sun_rad, **AT10
    )
    np.testing.assert_allclose(b.stokes, a.stokes, rtol=1e-12, atol=1e-12 * a.stokes[..., 0].max())
    np.testing.assert_allclose(np.degrees(b.aolp), a.aolp, rtol=1e-9, atol=1e-9)


def test_sun_without_polarization_equals_the_default_and_scales_with_stokes_norm() -> None:
    a = polbrdf.radiance(PAINT, VIEW_T, VIEW_P, sun=(35.0, 20.0, 900.0), **AT10)
    b = polbrdf.radiance(PAINT, VIEW_T, VIEW_P, sun=(35.0, 20.0, 900.0, [4, 0, 0, 0]), **AT10)
    np.testing.assert_array_equal(a.stokes, b.stokes)
    # Only the polarization of the given Stokes vector matters: (2, 0.6, ...) ≡ (1, 0.3, ...).
    c = polbrdf.radiance(PAINT, VIEW_T, VIEW_P, sun=(35.0, 20.0, 900.0, SUN_STOKES[1]), **AT10)
    half = np.array(SUN_STOKES[1]) / 2.0
    d = polbrdf.radiance(PAINT, VIEW_T, VIEW_P, sun=(35.0, 20.0, 900.0, half), **AT10)
    np.testing.assert_allclose(c.stokes, d.stokes, rtol=1e-15, atol=1e-300)


def test_fully_polarized_sun_tolerates_rounding() -> None:
    # A degree of polarization a rounding above 1 is taken as 1 (as in a scene file).
    psi = np.radians(np.arange(0.0, 180.0, 7.0))
    for p in psi:
        over = (1.0, np.cos(2 * p) * (1 + 1e-11), np.sin(2 * p) * (1 + 1e-11), 0.0)
        a = polbrdf.radiance(METAL, VIEW_T, VIEW_P, sun=(30.0, 0.0, 5.0, over), **AT10)
        exact = (1.0, np.cos(2 * p), np.sin(2 * p), 0.0)
        b = polbrdf.radiance(METAL, VIEW_T, VIEW_P, sun=(30.0, 0.0, 5.0, exact), **AT10)
        np.testing.assert_allclose(a.stokes, b.stokes, rtol=1e-10, atol=1e-12)


def test_sun_adds_to_emission_and_the_atmosphere_acts_on_both() -> None:
    sun = (30.0, 45.0, 800.0, SUN_STOKES[1])
    tau, path = 0.7, 1.25
    both = polbrdf.radiance(
        PAINT, VIEW_T, VIEW_P, sun=sun, temperature_k=310.0, transmittance=tau,
        path_radiance=path, **AT10,
    )  # fmt: skip
    hot = polbrdf.radiance(PAINT, VIEW_T, VIEW_P, temperature_k=310.0, **AT10)
    lit = polbrdf.radiance(PAINT, VIEW_T, VIEW_P, sun=sun, **AT10)
    np.testing.assert_array_equal(both.emitted, hot.emitted)
    np.testing.assert_array_equal(both.reflected, lit.reflected)
    np.testing.assert_allclose(
        both.stokes, tau * (hot.emitted + lit.reflected) + path * E0, rtol=1e-14, atol=1e-14
    )


def test_band_sun_is_the_response_integral_times_the_spectral_result() -> None:
    # A constant index and a sun irradiance constant across the band: the band radiance is
    # ∫R dλ (µm) times the spectral one.
    w = np.array([8.0, 9.0, 11.0, 12.0])
    resp = np.array([0.0, 1.0, 1.0, 0.5])
    integral = np.sum(0.5 * (resp[1:] + resp[:-1]) * np.diff(w))  # linear response: exact
    sun = (40.0, 10.0, 600.0, SUN_STOKES[2])
    spectral = polbrdf.radiance(METAL, VIEW_T, VIEW_P, sun=sun, **AT10)
    band = polbrdf.radiance(METAL, VIEW_T, VIEW_P, sun=sun, band=(w, resp))
    np.testing.assert_allclose(
        band.stokes, integral * spectral.stokes, rtol=1e-12,
        atol=1e-12 * spectral.stokes[..., 0].max(),
    )  # fmt: skip


def test_lambertian_surface_reflects_rho_d_times_the_irradiance() -> None:
    # n = 1: no Fresnel reflection, only the volume term f = ρ_D: the sun gives ρ_D·E·cosθs.
    r = polbrdf.radiance(LAMBERT, VIEW_T, VIEW_P, sun=(35.0, 20.0, 100.0), **AT10)
    np.testing.assert_allclose(r.reflected[..., 0], 0.1 * 100.0 * np.cos(np.radians(35.0)))
    np.testing.assert_allclose(r.reflected[..., 1:], 0.0, atol=1e-25)


# --- The CIE clear sky -----------------------------------------------------------------------


@pytest.mark.parametrize("stokes", SUN_STOKES[:2])
def test_clear_sky_of_zero_irradiance_is_the_sun_alone(stokes: Any) -> None:
    sun = (35.0, 20.0, 900.0, stokes)
    common = {"temperature_k": 300.0, "transmittance": 0.9, "path_radiance": 0.5, **AT10}
    alone = polbrdf.radiance(PAINT, VIEW_T, VIEW_P, sun=sun, **common)
    dark = polbrdf.radiance(
        PAINT, VIEW_T, VIEW_P, sun=sun, sky="cie-clear", sky_irradiance=0.0, **common
    )
    for name in ("stokes", "emitted", "reflected", "dolp", "aolp"):
        assert np.array_equal(getattr(dark, name), getattr(alone, name)), name


@pytest.mark.parametrize("rotation", [37.0, -123.4, 5.0])
@pytest.mark.parametrize("m", [PAINT, METAL], ids=["paint", "metal"])
def test_rotating_sun_and_views_together_changes_nothing(m: Material, rotation: float) -> None:
    # The model is isotropic and the sky is attached to the sun: turning the sun and every
    # view about the normal leaves each Stokes vector (in its own beam's basis) unchanged.
    common = {"temperature_k": 290.0, **clear_sky(sky_irradiance=80.0, dop_max=0.8)}
    for stokes in SUN_STOKES[:2]:
        a = polbrdf.radiance(m, VIEW_T, VIEW_P, sun=(62.0, 20.0, 900.0, stokes), **common)
        b = polbrdf.radiance(
            m, VIEW_T, VIEW_P + rotation, sun=(62.0, 20.0 + rotation, 900.0, stokes), **common
        )
        scale = a.stokes[..., 0].max()
        np.testing.assert_allclose(b.stokes, a.stokes, rtol=1e-9, atol=1e-12 * scale)
        np.testing.assert_allclose(b.reflected, a.reflected, rtol=1e-9, atol=1e-12 * scale)


def test_mirror_in_the_suns_plane_flips_s2_and_s3() -> None:
    # Unpolarized sun: the scene is symmetric about the sun's vertical plane; a mirror keeps
    # S0, S1 and flips S2 (the ±45° axes swap) and S3 (the handedness).
    common = {"sun": (35.0, 20.0, 900.0), **clear_sky(sky_irradiance=100.0)}
    theta = np.array([0.0, 20.0, 45.0, 70.0, 85.0])[:, None]
    dphi = np.array([10.0, 50.0, 120.0, 180.0])
    for m in (PAINT, METAL):
        a = polbrdf.radiance(m, theta, 200.0 + dphi, **common)
        b = polbrdf.radiance(m, theta, 200.0 - dphi, **common)
        scale = a.stokes[..., 0].max()
        np.testing.assert_allclose(
            b.stokes * [1, 1, -1, -1], a.stokes, rtol=1e-9, atol=1e-12 * scale
        )


def test_clear_sky_reflection_is_linear_in_its_irradiance() -> None:
    dark_sun = (35.0, 20.0, 0.0)  # places the sky, reflects nothing itself
    r1 = polbrdf.radiance(METAL, VIEW_T, VIEW_P, sun=dark_sun, **clear_sky(sky_irradiance=50.0))
    r3 = polbrdf.radiance(METAL, VIEW_T, VIEW_P, sun=dark_sun, **clear_sky(sky_irradiance=150.0))
    scale = r1.reflected[..., 0].max()
    assert scale > 0
    np.testing.assert_allclose(r3.reflected, 3.0 * r1.reflected, rtol=1e-12, atol=1e-14 * scale)
    # Superposition: the sun and the sky add.
    sun = (35.0, 20.0, 900.0, SUN_STOKES[1])
    both = polbrdf.radiance(METAL, VIEW_T, VIEW_P, sun=sun, **clear_sky(sky_irradiance=50.0))
    alone = polbrdf.radiance(METAL, VIEW_T, VIEW_P, sun=sun, **AT10)
    np.testing.assert_allclose(
        both.reflected, alone.reflected + r1.reflected, rtol=1e-12,
        atol=1e-14 * both.reflected[..., 0].max(),
    )  # fmt: skip


def test_clear_sky_polarization_is_linear_in_dop_max() -> None:
    # The sky's S0 does not depend on δ_max and its (S1, S2) are proportional to it, so the
    # reflected Stokes vector (all of it: F's first row couples polarization into S0) is
    # affine in δ_max.
    kw = {"sun": (50.0, 100.0, 0.0), "sky_irradiance": 60.0, **AT10}
    r = {
        d: polbrdf.radiance(METAL, VIEW_T, VIEW_P, sky="cie-clear", dop_max=d, **kw).reflected
        for d in (0.0, 0.4, 1.0)
    }
    scale = r[0.0][..., 0].max()
    np.testing.assert_allclose(
        r[0.4], r[0.0] + 0.4 * (r[1.0] - r[0.0]), rtol=1e-9, atol=1e-12 * scale
    )
    # ... and δ_max matters.
    assert np.abs(r[1.0] - r[0.0])[..., 1:].max() > 1e-3 * scale


@pytest.mark.parametrize("sun", [(0.0, 0.0), (35.0, 20.0), (70.0, 200.0), (89.0, 10.0)])
def test_clear_sky_irradiance_is_its_horizontal_irradiance(sun: tuple[float, float]) -> None:
    # A Lambertian surface reflects ρ_D·∫_H L cosθ dω = ρ_D·sky_irradiance, unpolarized. The
    # tolerance is that of the core's volume quadrature (2 × 14 points in θ) against the
    # cusp of the CIE sky at the sun.
    r = polbrdf.radiance(
        LAMBERT, VIEW_T, VIEW_P, sun=(*sun, 0.0), **clear_sky(sky_irradiance=100.0)
    )
    np.testing.assert_allclose(r.reflected[..., 0], 0.1 * 100.0, rtol=1e-3)
    np.testing.assert_allclose(r.reflected[..., 1:], 0.0, atol=1e-20)


# --- The tabulated sky -----------------------------------------------------------------------


def uniform_table(radiance: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    theta = np.array([0.0, 20.0, 45.0, 70.0, 90.0])
    phi = np.array([0.0, 45.0, 130.0, 180.0, 270.0])
    stokes = np.zeros((theta.size, phi.size, 4))
    stokes[..., 0] = radiance
    return theta, phi, stokes


@pytest.mark.parametrize("m", [PAINT, METAL], ids=["paint", "metal"])
def test_uniform_table_sky_obeys_kirchhoff(m: Material) -> None:
    # A uniform unpolarized sky L reflects L·(e0 − ε) (Kirchhoff's law), ε from emissivity.
    level = 3.7
    r = polbrdf.radiance(m, VIEW_T, VIEW_P, sky="table", sky_table=uniform_table(level), **AT10)
    eps = polbrdf.emissivity(m, VIEW_T, **AT10).eps
    expected = level * (E0 - eps)
    np.testing.assert_allclose(r.reflected, expected, rtol=1e-5, atol=1e-7 * level)
    # And the same as the closed-form uniform sky.
    u = polbrdf.radiance(m, VIEW_T, VIEW_P, sky="uniform", sky_radiance=level, **AT10)
    np.testing.assert_allclose(r.reflected, u.reflected, rtol=1e-5, atol=1e-7 * level)


def test_azimuth_independent_table_equals_the_profile_sky() -> None:
    zen = np.array([0.0, 30.0, 60.0, 75.0, 90.0])
    rad = np.array([2.0, 2.5, 4.0, 6.0, 9.0])
    phi = np.array([0.0, 120.0, 240.0])
    stokes = np.zeros((zen.size, phi.size, 4))
    stokes[..., 0] = rad[:, None]
    table = polbrdf.radiance(
        PAINT, VIEW_T, VIEW_P, sky="table", sky_table=(zen, phi, stokes), **AT10
    )
    profile = polbrdf.radiance(
        PAINT, VIEW_T, VIEW_P, sky="profile", sky_profile=(zen, rad), **AT10
    )
    np.testing.assert_allclose(table.reflected, profile.reflected, rtol=1e-9, atol=1e-12)


def test_table_sky_is_linear_and_its_angles_are_always_degrees() -> None:
    theta = np.array([0.0, 40.0, 90.0])
    phi = np.array([0.0, 90.0, 180.0, 270.0])
    rng = np.random.default_rng(7)
    s0 = rng.uniform(1.0, 3.0, (3, 4))
    lin = rng.uniform(0.0, 0.6, (3, 4))
    ang = rng.uniform(0.0, np.pi, (3, 4))
    stokes = np.stack([s0, s0 * lin * np.cos(ang), s0 * lin * np.sin(ang), 0.2 * s0], axis=-1)
    a = polbrdf.radiance(METAL, VIEW_T, VIEW_P, sky="table", sky_table=(theta, phi, stokes), **AT10)
    b = polbrdf.radiance(
        METAL, VIEW_T, VIEW_P, sky="table", sky_table=(theta, phi, 2.5 * stokes), **AT10
    )
    scale = a.reflected[..., 0].max()
    np.testing.assert_allclose(b.reflected, 2.5 * a.reflected, rtol=1e-12, atol=1e-14 * scale)
    # Views in radians, the table still in degrees.
    c = polbrdf.radiance(
        METAL, np.radians(VIEW_T), np.radians(VIEW_P), degrees=False, sky="table",
        sky_table=(theta, phi, stokes), **AT10,
    )  # fmt: skip
    np.testing.assert_allclose(c.reflected, a.reflected, rtol=1e-9, atol=1e-12 * scale)


# --- Errors ----------------------------------------------------------------------------------

TABLE = uniform_table(1.0)


def bad_node_table() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    theta, phi, stokes = uniform_table(1.0)
    stokes = stokes.copy()
    stokes[1, 2] = (1.0, 0.9, 0.9, 0.0)  # degree of polarization 1.27
    return theta, phi, stokes


@pytest.mark.parametrize(
    ("call", "pattern"),
    [
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sun=(90.0, 0.0, 100.0), **AT10),
            r"`sun\[0\] \(zenith\)` = 90: the sun must be above the horizon",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sun=(95.0, 0.0, 100.0), **AT10),
            r"`sun\[0\] \(zenith\)` = 95",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sun=(-1.0, 0.0, 100.0), **AT10),
            r"`sun\[0\] \(zenith\)` = -1",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 0.1, 0, degrees=False, sun=(1.7, 0, 100.0), **AT10),
            r"`sun\[0\] \(zenith\)`.*above the horizon.*given in radians: 1\.7",
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sun=(95.0, 0.0, 100.0), **clear_sky(sky_irradiance=10.0)
            ),
            r"`sun\[0\] \(zenith\)` = 95.*above the horizon",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sun=(30.0, np.nan, 100.0), **AT10),
            r"`sun\[1\] \(azimuth\)` = NaN",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sun=(30.0, 0.0, -5.0), **AT10),
            r"`sun\[2\] \(irradiance\)` = -5",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sun=(30.0, 0.0, 5.0, (1, 1, 1, 0)), **AT10),
            r"`sun\[3\] \(stokes\)`.*degree of polarization.*exceeds 1",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sun=(30.0, 0.0, 5.0, (0, 0, 0, 0)), **AT10),
            r"`sun\[3\] \(stokes\)`.*s0 > 0",
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sun=(30.0, 0.0, 5.0, (1, np.inf, 0, 0)), **AT10
            ),
            r"`sun\[3\] \(stokes\)`.*finite",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sun=(30.0, 0.0, 5.0, (1, 0, 0)), **AT10),
            r"`sun\[3\] \(stokes\)` must be a Stokes vector.*shape \(3,\)",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sun=(30.0, [0.0, 1.0], 5.0), **AT10),
            r"`sun\[1\] \(azimuth\)` must be a scalar",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, **clear_sky(sky_irradiance=10.0)),
            r'sky = "cie-clear" needs a `sun`',
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sun=(30.0, 0.0, 5.0), **clear_sky()),
            r'sky = "cie-clear" needs `sky_irradiance`',
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sun=(30.0, 0.0, 5.0), **clear_sky(sky_irradiance=-1.0)
            ),
            r"`sky_irradiance` = -1",
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sun=(30.0, 0.0, 5.0), **clear_sky(sky_irradiance=1.0, dop_max=1.5)
            ),
            r"`dop_max` = 1\.5: must lie in \[0, 1\]",
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sky="uniform", sky_radiance=1.0, dop_max=0.5, **AT10
            ),
            r'`dop_max` does not apply to sky = "uniform"',
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sun=(30, 0, 5), sky_irradiance=1.0, **AT10),
            r'`sky_irradiance` does not apply to sky = "none"',
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sun=(30, 0, 5), sky_table=TABLE, **clear_sky(sky_irradiance=1.0)
            ),
            r'`sky_table` does not apply to sky = "cie-clear"',
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sky="table", **AT10),
            r'sky = "table" needs `sky_table`',
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sky="tabel", **AT10),
            r"unknown sky model `tabel` \(expected \"none\", .*\"cie-clear\", \"table\"\)",
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sky="table", sky_table=(TABLE[0], TABLE[1], TABLE[2][:, :3]), **AT10
            ),
            r"`sky_table`: `stokes` must have shape .* = \(5, 5, 4\), got \(5, 3, 4\)",
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sky="table", sky_table=(TABLE[0][:-1], TABLE[1], TABLE[2][:-1]), **AT10
            ),
            r"`sky_table`: .*0° to 90°",
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sky="table", sky_table=(TABLE[0], [0, 45, 130, 180, 360], TABLE[2]),
                **AT10,
            ),
            r"`sky_table`: invalid parameter `phi_deg` = 360 \(at index 4\)",
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sky="table", sky_table=(TABLE[0], [0, 45, 45, 180, 270], TABLE[2]),
                **AT10,
            ),
            r"`sky_table`: invalid parameter `phi_deg` = 45 \(at index 2\).*increase",
        ),
        (
            lambda: polbrdf.radiance(PAINT, 10, 0, sky="table", sky_table=bad_node_table(), **AT10),
            (
                r"`sky_table`: invalid parameter `s0` = 1 \(at index 7\).*exceeds 1 "
                r"\(node 7 is stokes\[1, 2\]\)"
            ),
        ),
        (
            lambda: polbrdf.radiance(
                PAINT, 10, 0, sky="table", sky_table=(*TABLE[:2], -TABLE[2]), **AT10
            ),
            r"`sky_table`: invalid parameter `s0` = -1 \(at index 0\)",
        ),
    ],
)
def test_errors_name_the_argument(call: Any, pattern: str) -> None:
    with pytest.raises(ValueError, match=pattern):
        call()


@pytest.mark.parametrize(
    "kwargs",
    [
        {"sun": (30.0, 0.0)},
        {"sun": (30.0, 0.0, 5.0, (1, 0, 0, 0), "extra")},
        {"sun": "noon"},
        {"sun": (30.0, 0.0, "bright")},
        {"sky": "table", "sky_table": (TABLE[0], TABLE[1])},
        {"sky": "table", "sky_table": (TABLE[0], TABLE[1], TABLE[2].astype(str))},
    ],
)
def test_malformed_sun_and_table_are_type_errors(kwargs: dict[str, Any]) -> None:
    with pytest.raises(TypeError):
        polbrdf.radiance(PAINT, 10, 0, **AT10, **kwargs)
