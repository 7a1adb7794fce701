"""Spectral materials from Python: Material(index=...), polbrdf.index, wavelength_um broadcasting
through the engine, errors, round trips, and a fit of an effective index per wavelength."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

import polbrdf
from polbrdf import Material


@pytest.fixture(scope="module")
def gold() -> Material:
    return Material(index="library:Au/Johnson", sigma_deg=10.0, name="gold film")


def test_spectral_material_properties(gold: Material) -> None:
    assert gold.n is None and gold.k is None
    assert gold.index == "library:Au/Johnson"
    lo, hi = gold.wavelength_range
    assert lo == pytest.approx(0.1879) and hi == pytest.approx(1.937)
    assert "Johnson" in gold.index_references
    d = gold.to_dict()
    assert "n" not in d and "k" not in d and d["index"] == "library:Au/Johnson"
    assert Material(**d) == gold
    assert pickle.loads(pickle.dumps(gold)) == gold
    assert eval(repr(gold), {"Material": Material}) == gold
    assert Material.from_toml_str(gold.to_toml()) == gold
    # A constant material keeps its keys exactly (no `index`).
    assert "index" not in Material(1.5, sigma_deg=5).to_dict()


def test_index_matches_the_preset_and_interpolates(gold: Material) -> None:
    n = polbrdf.index(gold, 0.6328)
    p = Material.preset("gold")
    assert n.real == pytest.approx(p.n, abs=5e-5) and n.imag == pytest.approx(p.k, abs=5e-4)
    # Linear between the table's rows 0.6168 µm (0.21 + 3.272i) and 0.6595 µm (0.14 + 3.697i).
    lam = np.array([0.6168, 0.64, 0.6595])
    got = polbrdf.index(gold, lam)
    t = (0.64 - 0.6168) / (0.6595 - 0.6168)
    want = np.array([0.21 + 3.272j, (0.21 + t * (0.14 - 0.21)) + 1j * (3.272 + t * 0.425), 0.14 + 3.697j])
    np.testing.assert_allclose(got, want, rtol=1e-12)
    assert got.shape == (3,)
    # A constant index does not depend on λ.
    assert polbrdf.index(p, [0.4, 10.0]) == pytest.approx([p.n + 1j * p.k] * 2)


def test_wavelengths_broadcast_like_angles(gold: Material) -> None:
    theta = np.linspace(0, 80, 9)[:, None, None]
    lam = np.array([0.45, 0.55, 0.6328, 1.2])[None, :, None]
    phi_r = np.array([150.0, 180.0])[None, None, :]
    f = polbrdf.mueller(gold, 30.0, 0.0, theta, phi_r, wavelength_um=lam)
    assert f.shape == (9, 4, 2, 4, 4)
    # Each wavelength equals a constant-index material at that wavelength's index.
    for j, l in enumerate(lam.ravel()):
        n = polbrdf.index(gold, l)
        const = Material(n=n.real, k=n.imag, sigma_deg=10.0)
        want = polbrdf.mueller(const, 30.0, 0.0, theta[:, 0, :], phi_r[:, 0, :])
        np.testing.assert_allclose(f[:, j], want, rtol=1e-13, atol=1e-300)
    ev = polbrdf.evaluate(gold, 30.0, 0.0, theta, phi_r, wavelength_um=lam, with_mueller=True)
    np.testing.assert_allclose(ev.mueller, f, rtol=1e-13)
    np.testing.assert_allclose(ev.brdf, f[..., 0, 0], rtol=1e-13)
    np.testing.assert_allclose(polbrdf.brdf(gold, 30, 0, theta, phi_r, wavelength_um=lam), ev.brdf)
    np.testing.assert_allclose(polbrdf.dolp(gold, 30, 0, theta, phi_r, wavelength_um=lam), ev.dolp)


def test_spectral_errors(gold: Material, tmp_path) -> None:
    with pytest.raises(ValueError, match="wavelength_um"):
        polbrdf.brdf(gold, 30, 0, 30, 180)
    with pytest.raises(ValueError, match=r"Au/Johnson.*0\.1879"):
        polbrdf.brdf(gold, 30, 0, 30, 180, wavelength_um=[0.5, 5.0])
    with pytest.raises(ValueError, match="at index 1"):
        polbrdf.index(gold, [0.5, 0.0])
    with pytest.raises(ValueError, match="not both"):
        Material(n=1.5, index="library:Au/Johnson", sigma_deg=10)
    with pytest.raises(ValueError, match="Au/Johnson"):  # the message lists the known ids
        Material(index="library:Au/Nobody", sigma_deg=10)
    with pytest.raises(ValueError, match="give `n`"):
        Material(sigma_deg=10)
    with pytest.raises(FileNotFoundError):
        Material(index=str(tmp_path / "missing.yml"), sigma_deg=10)
    bad = tmp_path / "bad.yml"
    bad.write_text("DATA:\n  - type: tabulated nk\n    data: |\n        0.5 1.0 x\n")
    with pytest.raises(ValueError, match=r"bad\.yml:\d+"):
        Material(index=str(bad), sigma_deg=10)


def test_effective_index_per_wavelength_from_s_and_p_reflectance() -> None:
    # An effective index for a material no database has: synthetic s/p BRDF of a known
    # wavelength-dependent index at three wavelengths, each fitted separately for n and k.
    truth = {0.45: (1.70, 0.05), 0.55: (1.62, 0.03), 0.65: (1.58, 0.01)}
    theta = np.array([20.0, 35.0, 50.0, 60.0, 70.0])
    for lam, (n, k) in truth.items():
        m = Material(n=n, k=k, sigma_deg=8.0, rho_d=0.01)
        f = polbrdf.mueller(m, theta, 0.0, theta, 180.0)
        s, p = f[:, 0, 0] + f[:, 0, 1], f[:, 0, 0] - f[:, 0, 1]
        start = Material(n=1.5, k=0.02, sigma_deg=8.0, rho_d=0.01)
        r = polbrdf.fit(
            start, theta, 0.0, theta, 180.0, {"brdf_s": s, "brdf_p": p}, "n,k",
            sigma={"brdf_s": 1e-3 * s, "brdf_p": 1e-3 * p},
            wavelength_um=lam,
        )  # fmt: skip
        assert r.parameters["n"][0] == pytest.approx(n, rel=1e-6), lam
        assert r.parameters["k"][0] == pytest.approx(k, abs=1e-6), lam


def test_fit_with_a_spectral_index_fixes_n_and_k(gold: Material) -> None:
    lam = np.repeat([0.5, 0.6, 0.7], 6)
    theta = np.tile(np.linspace(10, 70, 6), 3)
    truth = Material(index="library:Au/Johnson", sigma_deg=12.0)
    b = polbrdf.brdf(truth, theta, 0.0, theta, 180.0, wavelength_um=lam)
    r = polbrdf.fit(gold, theta, 0.0, theta, 180.0, {"brdf": b}, "sigma_deg", wavelength_um=lam)
    assert r.parameters["sigma_deg"][0] == pytest.approx(12.0, rel=1e-6)
    with pytest.raises(ValueError, match="spectral index"):
        polbrdf.fit(gold, theta, 0.0, theta, 180.0, {"brdf": b}, "n", wavelength_um=lam)
