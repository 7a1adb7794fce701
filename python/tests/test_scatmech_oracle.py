"""polbrdf against NIST's SCATMECH (the PyPI package pySCATMECH), where their physics overlaps.

polbrdf's Stokes basis is SCATMECH's "psps" (docs/model.md §2), and SCATMECH implements the same
facet (microfacet) scattering physics, so NIST's code — written independently of this project —
is an oracle for polbrdf's Fresnel amplitudes, Jones-to-Mueller conversion, frames, signs and the
signed Priest–Meier rotations (§3–§4), and, with matched distributions, for the absolute pBRDF:

- **Smooth interface** (§3): SCATMECH's Fresnel coefficients of a bare substrate
  (``FilmStack().reflectionCoefficient``, the Jones matrix ``diag(rs, rp)``) turned into a Mueller
  matrix by pySCATMECH's ``JonesMueller`` equal polbrdf's specular pBRDF times ``4cos²θ/a``: at
  specular geometry θN = 0, D = a, β = θ and η = 0, so ``F = a·M(θ)/(4cos²θ)`` (§5–§6) with
  M the Fresnel Mueller matrix, including its M00 = R_F.
- **Facet model, normalized** (§4): ``Facet_BRDF_Model`` at arbitrary bistatic geometries; M/M00
  depends only on the Fresnel amplitudes at the facet's local angle β and the two frame
  rotations, whatever the slope distribution or shadowing.
- **Facet model, absolute** (§5–§6): SCATMECH's ``Gaussian_Angle_Distribution_Function`` is
  ``P(θN) = exp(−θN²/σ²) / (πσ²·(1 − exp(−(π/2σ)²)))`` and its facet BRDF is
  ``P(θN)·R_F(β)/(4 cosθi cosθr)`` times the normalized Mueller matrix (SCATMECH's facet.cpp:
  slope density × ``1/cos⁴θN`` × ``cosβ/cosθi`` × ``1/cosθr`` × the Jacobian ``1/(4cosβ)``), which is
  polbrdf's standard form (eq. 1) with ``b = 1/σ²`` and ``a = 1/(πσ²(1 − e^{−(π/2σ)²}))`` given
  explicitly — an exact match. polbrdf's own default ``a`` (the exact hemispherical normalization
  ``∫D cosθN dΩ = 1``, §5) differs from SCATMECH's constant, which normalizes ``∫P θN dθN dφ = 1``,
  the small-slope form of the same integral: by the factor 1 + (2/3)σ² + O(σ⁴) (0.5 % at σ = 5°),
  the same at every geometry (tested). ``Shadowed_Facet_BRDF_Model`` with the
  ``Maxwell_Beard_Shadow_Function`` is eq. 3 without the ΦN factor (polbrdf's default
  ``azimuth_term = "none"``), τ and Ω in radians; ``Lambertian_BRDF_Model`` with reflectance
  πρ_D is the ρ_D part of the volume term, added unpolarized after the normalization (§6).
- **Stokes utilities**: DoLP, DoP and AoLP of polbrdf against pySCATMECH's ``StokesVector``.

Geometry. SCATMECH's light arrives from azimuth 180° (``ki = (sinθi, 0, −cosθi)``) and its
viewer sits at azimuth ``phis`` (specular at ``phis = 0``); polbrdf's directions point away from
the surface at azimuths φi, φr (specular at ``φr = φi + 180°``). Both models are isotropic and
depend on the azimuths only through φr − φi (§9.2; SCATMECH's sample rotation only turns its
slope distribution), so ``phis = φr − φi − 180°``. Both use ``s = unit(z × k)``, ``p = k × s``.

Tolerances. Both sides evaluate the same closed forms in double precision. A convention error
(a sign of rp, a transposed rotation, a conjugated phase, the sign of S3, a wrong σ or azimuth
convention) changes entries by 1e-2…1 of F00 (mirroring the azimuths makes F12/F00 differ by
1.4, dropping the 180° by 0.07). The tolerance is TOL = 1e-12 — of F00, or absolute for the
normalized and Fresnel matrices, whose entries are at most 1 — above the rounding of both codes:
exp(−bθN²) carries ~bθN²·ε (≤ 300ε here) and the Fresnel quotient a few ε·|N|²; measured
differences are ≤ 1.3e-13 of F00 for β ≥ 5° and ≤ 3e-14 for the Fresnel matrices. Near
retro-reflection SCATMECH's facet formulas lose accuracy: they take the local angle from ``acos``
(an error ~ε/β) and divide by ``sin²2β``, so their relative error grows like ε/sin²β (measured
2.3–2.5·ε/sin²β: 1.3e-12 at β = 1.14°, 3e-5 at β = 4e-6 rad), while polbrdf's angles keep full
relative accuracy (§9.2; at β = 1.14° its F00 equals a 40-digit mpmath evaluation of §5 to one
ulp, SCATMECH's is 1.3e-12 off). So each geometry's tolerance is TOL + 16ε/sin²β (at most 5e-11
for the β ≥ 0.5° used here; observed errors stay below 0.13 of it), and exact backscatter, where
both codes take their β = 0 branch, is held to TOL alone. The dielectric with n < 1 has n = 0.6:
exactly at its critical angle both codes' amplitudes carry ~sqrt(ε) of rounding (the square-root
branch point of q, §3; 1.5e-7 for n = 0.5 at β = 30°), and no geometry here lies on it. No
tolerance was widened to hide a disagreement: polbrdf and SCATMECH agree everywhere tested.

Skipped when pySCATMECH is not installed (``pip install pySCATMECH``; it compiles SCATMECH's C++
from source, a few minutes). CI installs it (scripts/test --peers).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip(
    "pySCATMECH",
    reason="the oracle, NIST's pySCATMECH, is not installed: pip install pySCATMECH "
    "(it compiles SCATMECH's C++ sources, needs g++; scripts/test --peers installs it)",
)
from pySCATMECH.brdf import BRDF_Model
from pySCATMECH.fresnel import FilmStack, OpticalFunction
from pySCATMECH.mueller import JonesMueller, StokesVector

import polbrdf
from polbrdf import bridges

#: Relative (to F00) or absolute (normalized and Fresnel matrices) tolerance; see the docstring.
TOL = 1e-12

#: SCATMECH needs a wavelength; a bare substrate of constant index does not depend on it (µm).
WAVELENGTH_UM = 0.6328

#: (label, n, k, σ in degrees): the presets' indices and roughnesses (a dielectric paint and
#: glass; absorbing metals, among them gold and silver with n < 1) and a dielectric with n < 1,
#: which reflects totally beyond its critical angle (§8).
PRESETS = ["paint", "glass", "aluminium", "gold", "silver", "copper", "iron"]
MATERIALS = [
    (name, m.n, m.k, m.sigma_deg) for name, m in ((p, polbrdf.Material.preset(p)) for p in PRESETS)
] + [("n<1 dielectric", 0.6, 0.0, 12.0)]
IDS = [m[0] for m in MATERIALS]


def dielectric(n: float, k: float) -> str:
    """A SCATMECH dielectric_function "(n,k)" at full precision (pySCATMECH formats a Python
    complex with 6 significant digits, so it is never passed one)."""
    return f"({float(n)!r},{float(k)!r})"


def scatmech_angles(ti: float, pi: float, tr: float, pr: float) -> tuple[float, float, float]:
    """polbrdf's (θi, φi, θr, φr) in degrees -> SCATMECH's (thetai, thetas, phis) in radians,
    by the public bridge (``polbrdf.bridges.to_scatmech``, docs/bridges.md)."""
    a, s, p = bridges.to_scatmech(ti, pi, tr, pr)
    return math.radians(float(a)), math.radians(float(s)), math.radians(float(p))


def scatmech_mueller(model: BRDF_Model, g: tuple[float, float, float, float]) -> np.ndarray:
    return np.asarray(model.MuellerBRDF(*scatmech_angles(*g), coords="psps"), dtype=float)


def direction(theta_deg: float, phi_deg: float) -> np.ndarray:
    """§1's w = (sinθ cosφ, sinθ sinφ, cosθ)."""
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])


def sin2_beta(ti: float, pi: float, tr: float, pr: float) -> float:
    """sin²β of the local incidence angle β on the facet (cos2β = w_i·w_r, §1), as
    |w_i − w_r|²/4: exactly 0 at backscatter, full relative accuracy near it."""
    d = direction(ti, pi) - direction(tr, pr)
    return float(d @ d) / 4.0


def beta_deg(ti: float, pi: float, tr: float, pr: float) -> float:
    return math.degrees(math.asin(min(1.0, math.sqrt(sin2_beta(ti, pi, tr, pr)))))


def tolerance(g: tuple[float, float, float, float]) -> float:
    """TOL, plus SCATMECH's rounding near retro-reflection, 16ε/sin²β (module docstring); at
    exact backscatter (β = 0) both codes take their β = 0 branch and TOL alone applies."""
    s2 = sin2_beta(*g)
    return TOL if s2 == 0.0 else TOL + 16.0 * np.finfo(float).eps / s2


def theta_n_deg(g: tuple[float, float, float, float]) -> float:
    """θN (§1), degrees: the zenith angle of w_i + w_r."""
    t1, p1, t2, p2 = np.radians(g)
    s = np.array(
        [
            math.sin(t1) * math.cos(p1) + math.sin(t2) * math.cos(p2),
            math.sin(t1) * math.sin(p1) + math.sin(t2) * math.sin(p2),
            math.cos(t1) + math.cos(t2),
        ]
    )
    return math.degrees(math.atan2(math.hypot(s[0], s[1]), s[2]))


def scatmech_a(sigma_deg: float) -> float:
    """The constant of SCATMECH's Gaussian_Angle_Distribution_Function, sr⁻¹ (facet.cpp)."""
    s = math.radians(sigma_deg)
    return 1.0 / (math.pi * s * s * (1.0 - math.exp(-((math.pi / 2.0 / s) ** 2))))


def random_geometries(seed: int, count: int = 240) -> list[tuple[float, float, float, float]]:
    """Bistatic geometries over the whole upper hemisphere (θ up to 87°, any azimuths), β ≥ 0.5°."""
    rng = np.random.default_rng(seed)
    out: list[tuple[float, float, float, float]] = []
    while len(out) < count:
        ti, tr = rng.uniform(0.0, 87.0, 2)
        pi, pr = rng.uniform(-360.0, 360.0, 2)
        g = (float(ti), float(pi), float(tr), float(pr))
        if beta_deg(*g) >= 0.5:
            out.append(g)
    return out


#: Special geometries: specular, normal incidence and view, in and out of the plane of
#: incidence, forward and backward, crossed planes (Δ = ±90°), near grazing, near
#: retro-reflection (β ≈ 0.5°), and azimuths of the incident plane other than 0.
SPECIAL = [
    (0.0, 0.0, 0.0, 180.0),
    (0.0, 123.0, 40.0, 17.0),
    (40.0, 17.0, 0.0, 0.0),
    (30.0, 0.0, 30.0, 180.0),
    (30.0, 0.0, 31.0, 0.0),
    (30.0, 0.0, 30.0, 2.0),
    (50.0, 40.0, 52.0, 41.0),
    (60.0, 250.0, 60.0, 70.0),
    (60.0, 0.0, 20.0, 180.0),
    (60.0, 0.0, 20.0, 0.0),
    (60.0, 0.0, 60.0, 90.0),
    (60.0, 0.0, 60.0, -90.0),
    (45.0, 30.0, 70.0, 120.0),
    (45.0, 30.0, 70.0, -60.0),
    (85.0, 0.0, 85.0, 180.0),
    (85.0, 10.0, 80.0, 120.0),
    (10.0, 0.0, 80.0, 200.0),
    (75.0, 300.0, 5.0, 95.0),
]


def facet_model(n: float, k: float, sigma_deg: float, shadow: tuple[float, float] | None):
    """SCATMECH's facet model on a bare substrate, Gaussian angle distribution of σ; with
    shadow = (τ, Ω) in degrees, the Maxwell–Beard shadow function."""
    sub = dielectric(n, k)
    if shadow is None:
        m = BRDF_Model(
            "Facet_BRDF_Model", substrate=sub, sdf="Gaussian_Angle_Distribution_Function"
        )
    else:
        m = BRDF_Model(
            "Shadowed_Facet_BRDF_Model",
            substrate=sub,
            sdf="Gaussian_Angle_Distribution_Function",
            shadow="Maxwell_Beard_Shadow_Function",
        )
        m.setParameters(
            {"shadow.tau": math.radians(shadow[0]), "shadow.Omega": math.radians(shadow[1])}
        )
    m.setParameters({"sdf.sigma": float(sigma_deg), "lambda": WAVELENGTH_UM})
    return m


def matched_material(
    n: float, k: float, sigma_deg: float, shadow: tuple[float, float] | None, rho_d: float = 0.0
) -> polbrdf.Material:
    """polbrdf's material with SCATMECH's distribution: b = 1/σ², SCATMECH's constant a."""
    return polbrdf.Material(
        n=n,
        k=k,
        b=1.0 / math.radians(sigma_deg) ** 2,
        a=scatmech_a(sigma_deg),
        shadowing=shadow is not None,
        tau_deg=15.0 if shadow is None else shadow[0],
        omega_deg=40.0 if shadow is None else shadow[1],
        rho_d=rho_d,
    )


def compare(
    mat: polbrdf.Material,
    model: BRDF_Model,
    geometries: list[tuple[float, float, float, float]],
    normalized: bool,
    label: str,
) -> None:
    g = np.array(geometries)
    ours = polbrdf.mueller(mat, g[:, 0], g[:, 1], g[:, 2], g[:, 3])  # one engine call
    for row, f in zip(geometries, ours, strict=True):
        s = scatmech_mueller(model, row)
        assert f[0, 0] > 0.0 and s[0, 0] > 0.0, (label, row, f[0, 0], s[0, 0])
        if normalized:
            got, want, tol = f / f[0, 0], s / s[0, 0], tolerance(row)
        else:
            got, want, tol = f, s, tolerance(row) * f[0, 0]
        err = np.abs(got - want)
        i, j = np.unravel_index(np.argmax(err), err.shape)
        assert err[i, j] <= tol, (
            f"{label}: polbrdf and SCATMECH differ at (θi, φi, θr, φr) = {row} deg "
            f"(β = {beta_deg(*row):.3f}°) in F{i}{j}{'/F00' if normalized else ''}: "
            f"{got[i, j]!r} against {want[i, j]!r}\npolbrdf:\n{got}\nSCATMECH:\n{want}"
        )


# ---- smooth interface: Fresnel reflection (§3) and its Mueller matrix (§4) ----


@pytest.mark.parametrize(("label", "n", "k", "sigma_deg"), MATERIALS, ids=IDS)
def test_smooth_interface_fresnel_mueller(label: str, n: float, k: float, sigma_deg: float) -> None:
    """The reflection Mueller matrix of a smooth interface at 0°…89.9°, through the specular
    pBRDF: F·4cos²θ/a is the Fresnel Mueller matrix (a = 1 sr⁻¹, no shadowing, any b)."""
    theta = np.concatenate([np.arange(0.0, 90.0, 0.5), [89.9, math.degrees(math.atan(n))]])
    mat = polbrdf.Material(n=n, k=k, b=1.0, a=1.0, shadowing=False)
    ours = polbrdf.mueller(mat, theta, 0.0, theta, 180.0)
    ours = ours * (4.0 * np.cos(np.radians(theta)) ** 2)[:, None, None]
    stack = FilmStack()  # no films: a bare substrate
    vacuum, substrate = OpticalFunction(1.0), OpticalFunction(dielectric(n, k))
    for t, m in zip(theta, ours, strict=True):
        r = np.array(stack.reflectionCoefficient(math.radians(t), WAVELENGTH_UM, vacuum, substrate))
        assert r[0, 1] == 0 and r[1, 0] == 0
        want = np.asarray(JonesMueller(r), dtype=float)  # psps: index 0 is s, 1 is p
        np.testing.assert_allclose(m, want, rtol=0, atol=TOL, err_msg=f"{label} at θ = {t}°")
    # The conventions this pins down, stated: normal incidence is the mirror R·diag(1, 1, −1, −1)
    # (rp(0) = −rs(0), §2–§3), and M00 = R_F = (|rs|² + |rp|²)/2.
    r0 = ours[0, 0, 0]
    np.testing.assert_allclose(ours[0], r0 * np.diag([1.0, 1.0, -1.0, -1.0]), atol=TOL)
    np.testing.assert_allclose(r0, abs((1 - complex(n, k)) / (1 + complex(n, k))) ** 2, rtol=1e-13)


# ---- the facet model: normalized Mueller matrices at bistatic geometries (§4) ----


@pytest.mark.parametrize(("label", "n", "k", "sigma_deg"), MATERIALS, ids=IDS)
def test_facet_normalized_mueller_bistatic(
    label: str, n: float, k: float, sigma_deg: float
) -> None:
    """M/M00 of the facet reflection: Fresnel at β, the signed rotations η_i, η_r, psps frames.
    polbrdf's own defaults (hemispherical a, shadowing on); SCATMECH without shadowing."""
    mat = polbrdf.Material(n=n, k=k, sigma_deg=sigma_deg)
    model = facet_model(n, k, sigma_deg, shadow=None)
    compare(mat, model, SPECIAL + random_geometries(seed=11), normalized=True, label=label)


# ---- the facet model: absolute pBRDF with matched distributions (§5–§6) ----


@pytest.mark.parametrize(("label", "n", "k", "sigma_deg"), MATERIALS, ids=IDS)
def test_facet_absolute_matched_distribution(
    label: str, n: float, k: float, sigma_deg: float
) -> None:
    """Shadowing off: F = D·R_F(β)/(4cosθi cosθr)·M/M00 with SCATMECH's Gaussian angle
    distribution, entry by entry."""
    mat = matched_material(n, k, sigma_deg, shadow=None)
    model = facet_model(n, k, sigma_deg, shadow=None)
    compare(mat, model, SPECIAL + random_geometries(seed=12), normalized=False, label=label)


@pytest.mark.parametrize("shadow", [(15.0, 40.0), (30.0, 10.0)], ids=["paper", "strong"])
@pytest.mark.parametrize(("label", "n", "k", "sigma_deg"), MATERIALS, ids=IDS)
def test_shadowed_facet_maxwell_beard(
    label: str, n: float, k: float, sigma_deg: float, shadow: tuple[float, float]
) -> None:
    """Shadowing on: eq. 3 (no ΦN factor), τ and Ω in degrees here, radians in SCATMECH — the
    paper's τ = 15°, Ω = 40° and a pair that shadows strongly."""
    mat = matched_material(n, k, sigma_deg, shadow=shadow)
    model = facet_model(n, k, sigma_deg, shadow=shadow)
    compare(mat, model, SPECIAL + random_geometries(seed=13), normalized=False, label=label)


@pytest.mark.parametrize("theta", [0.0, 0.001, 5.0, 30.0, 60.0, 85.0])
def test_exact_backscatter(theta: float) -> None:
    """β = 0 (retro-reflection, §4's degenerate frame): T = −diag(rs, rp) in polbrdf, diag(rs, rp)
    in SCATMECH — the same Mueller matrix, with Fresnel at normal incidence, SO = 1."""
    for label, n, k, sigma_deg in MATERIALS:
        mat = matched_material(n, k, sigma_deg, shadow=(15.0, 40.0))
        model = facet_model(n, k, sigma_deg, shadow=(15.0, 40.0))
        geoms = [(theta, phi, theta, phi) for phi in (0.0, 33.0, 200.0)]
        compare(mat, model, geoms, normalized=False, label=f"{label} backscatter")


@pytest.mark.parametrize("sigma_deg", [2.0, 5.0, 15.0, 30.0])
def test_sigma_convention_and_normalization(sigma_deg: float) -> None:
    """polbrdf's sigma_deg is SCATMECH's sigma (b = 1/σ², §5): with polbrdf's own hemispherical
    normalization the two pBRDFs differ only by the ratio of the constants a, at every geometry
    and in every entry; and that a is the exact normalization ∫D cosθN dΩ = 1, where SCATMECH's
    is its small-slope form (ratio 1 + (2/3)σ² + …)."""
    mat = polbrdf.Material(n=1.65, sigma_deg=sigma_deg, shadowing=False)
    # The exact hemispherical normalization, by Gauss–Legendre on [0, π/2] in numpy.
    x, w = np.polynomial.legendre.leggauss(400)
    th = (x + 1.0) * math.pi / 4.0
    b = 1.0 / math.radians(sigma_deg) ** 2
    integral = (
        2.0 * math.pi * (math.pi / 4.0) * np.sum(w * np.exp(-b * th**2) * np.sin(th) * np.cos(th))
    )
    assert mat.a_effective == pytest.approx(1.0 / integral, rel=1e-12)
    ratio = mat.a_effective / scatmech_a(sigma_deg)
    s = math.radians(sigma_deg)
    assert ratio == pytest.approx(1.0 + 2.0 / 3.0 * s * s, rel=0, abs=s**4)
    # Geometries where D is not negligible (θN ≤ 4σ), so the comparison sees the lobe's shape.
    geoms = [
        g
        for g in SPECIAL + random_geometries(seed=14, count=600)
        if theta_n_deg(g) <= 4 * sigma_deg
    ]
    assert len(geoms) >= 20
    g = np.array(geoms)
    ours = polbrdf.mueller(mat, g[:, 0], g[:, 1], g[:, 2], g[:, 3])
    model = facet_model(1.65, 0.0, sigma_deg, shadow=None)
    for row, f in zip(geoms, ours, strict=True):
        want = ratio * scatmech_mueller(model, row)
        tol = tolerance(row) * f[0, 0]
        np.testing.assert_allclose(f, want, rtol=0, atol=tol, err_msg=f"{row} deg")


# ---- the volume term's ρ_D part: a Lambertian, added after the normalization (§6) ----


@pytest.mark.parametrize(("label", "n", "k", "sigma_deg"), MATERIALS[:3], ids=IDS[:3])
def test_facet_plus_lambertian(label: str, n: float, k: float, sigma_deg: float) -> None:
    """F = f_s·M/M00 + ρ_D·diag(1, 0, 0, 0) (eq. 9 corrected) against SCATMECH's sum of the
    shadowed facet model and a Lambertian of reflectance πρ_D."""
    rho_d, shadow = 0.03, (15.0, 40.0)
    mat = matched_material(n, k, sigma_deg, shadow=shadow, rho_d=rho_d)
    sub = dielectric(n, k)
    model = BRDF_Model(
        "Two_Source_BRDF_Model",
        {"source1": "Shadowed_Facet_BRDF_Model", "source2": "Lambertian_BRDF_Model"},
    )
    model.setParameters(
        {
            "source1.sdf": "Gaussian_Angle_Distribution_Function",
            "source1.shadow": "Maxwell_Beard_Shadow_Function",
        }
    )
    model.setParameters(
        {
            "substrate": sub,
            "source1.substrate": sub,
            "source2.substrate": sub,
            "source1.sdf.sigma": float(sigma_deg),
            "source1.shadow.tau": math.radians(shadow[0]),
            "source1.shadow.Omega": math.radians(shadow[1]),
            "source2.reflectance.table": math.pi * rho_d,
        }
    )
    compare(mat, model, SPECIAL + random_geometries(seed=15), normalized=False, label=label)


# ---- Stokes utilities: DoLP, DoP, AoLP (§2, eq. 13) ----


def test_stokes_utilities() -> None:
    """polbrdf's stokes_dolp, stokes_dop and stokes_aolp against pySCATMECH's StokesVector on
    random physical Stokes vectors (every sign of S1, S2, S3); and SCATMECH's Jones-to-Mueller
    conversion (the one the Mueller comparisons above go through) against §2's Stokes vector of
    a Jones vector, which pins the sign of S3 the agreeing Mueller matrices share."""
    rng = np.random.default_rng(16)
    direction = rng.normal(size=(500, 3))
    direction /= np.linalg.norm(direction, axis=1)[:, None]
    s0 = rng.uniform(0.1, 10.0, 500)
    dop = rng.uniform(0.0, 1.0, 500)
    stokes = np.column_stack([s0, (s0 * dop)[:, None] * direction])
    dolp = polbrdf.stokes_dolp(stokes)
    dopp = polbrdf.stokes_dop(stokes)
    aolp = polbrdf.stokes_aolp(stokes, degrees=False)
    for s, d, p, a in zip(stokes, dolp, dopp, aolp, strict=True):
        v = StokesVector(list(s))
        assert d == pytest.approx(v.DOLP(), rel=1e-14, abs=1e-15)
        assert p == pytest.approx(v.DOP(), rel=1e-14, abs=1e-15)
        assert a == pytest.approx(v.eta(), rel=1e-14, abs=1e-15)
    # A Jones matrix mapping s-polarized light (1, 0) to a random Jones vector e: its Mueller
    # matrix's first column plus second (the image of s-polarized light, psps) is e's Stokes
    # vector, DoP 1.
    for _ in range(50):
        e = rng.normal(size=2) + 1j * rng.normal(size=2)
        m = np.asarray(JonesMueller(np.array([[e[0], 0.0], [e[1], 0.0]])), dtype=float)
        s = m[:, 0] + m[:, 1]
        assert float(polbrdf.stokes_dop(s)) == pytest.approx(1.0, rel=1e-13)
        # S = (|Es|²+|Ep|², |Es|²−|Ep|², 2Re(Es Ep*), −2Im(Es Ep*)) (§2): the sign of S3.
        want = [
            abs(e[0]) ** 2 + abs(e[1]) ** 2,
            abs(e[0]) ** 2 - abs(e[1]) ** 2,
            2 * (e[0] * e[1].conjugate()).real,
            -2 * (e[0] * e[1].conjugate()).imag,
        ]
        np.testing.assert_allclose(s, want, rtol=1e-13, atol=1e-13 * want[0])
