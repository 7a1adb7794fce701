"""`polbrdf.bridges` against the peers themselves (docs/bridges.md): polanalyser's Stokes
reconstruction and AoLP from the four polarizer pixels of a rolled camera, and Mitsuba 3's own
Stokes bases and `rotate_mueller_basis`. Each part is skipped, with the reason, when its peer
does not install (pySCATMECH's side is test_scatmech_oracle.py, which uses
`bridges.to_scatmech`; Mitsuba's BSDFs themselves are in test_mitsuba_pbsdf.py)."""

from __future__ import annotations

import importlib
import importlib.util

import numpy as np
import pytest

import polbrdf
from polbrdf import bridges


def direction(theta: np.ndarray, phi: np.ndarray) -> np.ndarray:
    return np.stack(
        [np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], axis=-1
    )


def circular(d: np.ndarray, period: float) -> np.ndarray:
    """The signed distance of angles on a circle of the given period."""
    return (d + period / 2) % period - period / 2


def peer(name: str, hint: str):
    if importlib.util.find_spec(name) is None:
        pytest.skip(f"{name} is not installed: {hint}")
    try:
        return importlib.import_module(name)
    except ImportError as e:  # pragma: no cover - depends on the environment
        pytest.skip(f"{name} does not import ({e}): {hint}")


POLANALYSER = ("pip install polanalyser opencv-python-headless matplotlib (polanalyser imports "
               "OpenCV and matplotlib at import time but declares neither)")


def test_polanalyser_sees_what_the_bridge_says() -> None:
    pa = peer("polanalyser", POLANALYSER)
    paint = polbrdf.Material.preset("paint")
    rng = np.random.default_rng(36)
    n = 200
    ti, tr = rng.uniform(5, 80, n), rng.uniform(5, 80, n)
    pi, pr = rng.uniform(-180, 180, n), rng.uniform(-180, 180, n)
    # The reflected Stokes vectors of unpolarized and of linearly polarized light (psps).
    f = polbrdf.mueller(paint, ti, pi, tr, pr)
    s_in = np.array([1.0, 0.3, -0.6, 0.2])
    stokes = f @ s_in
    for y_down in (False, True):
        for roll_deg in (0.0, 25.0, -140.0):
            k = direction(np.radians(tr), np.radians(pr))
            p_r = np.radians(pr)
            s_axis = np.stack([-np.sin(p_r), np.cos(p_r), np.zeros(n)], axis=-1)
            p_axis = np.cross(k, s_axis)
            c, sn = np.cos(np.radians(roll_deg)), np.sin(np.radians(roll_deg))
            x = c * s_axis + sn * p_axis
            up = -sn * s_axis + c * p_axis
            roll = bridges.camera_roll(tr, pr, up)
            np.testing.assert_allclose(circular(roll - roll_deg, 360.0), 0.0, atol=1e-9)
            yimg = -up if y_down else up
            # Four polarizer pixels at 0°, 45°, 90°, 135° from image right toward `yimg`: the
            # intensity behind an ideal polarizer whose axis is the 3-D vector `a` (its angle
            # from s_out toward p_out in the psps frame).
            intensities = []
            for alpha in np.radians([0.0, 45.0, 90.0, 135.0]):
                a = np.cos(alpha) * x + np.sin(alpha) * yimg
                chi = np.arctan2(np.einsum("ij,ij->i", a, p_axis),
                                 np.einsum("ij,ij->i", a, s_axis))
                intensities.append(0.5 * (stokes[:, 0] + stokes[:, 1] * np.cos(2 * chi)
                                          + stokes[:, 2] * np.sin(2 * chi)))
            measured = pa.calcStokes(intensities, np.radians([0.0, 45.0, 90.0, 135.0]))
            ours = bridges.stokes_to_polanalyser(stokes, roll, y_down=y_down)
            np.testing.assert_allclose(measured, ours[:, :3], atol=1e-12 * stokes[:, :1].max())
            got = pa.cvtStokesToAoLP(measured)
            want = bridges.aolp_to_polanalyser(polbrdf.stokes_aolp(stokes), roll, y_down=y_down)
            assert np.all((want >= 0) & (want < np.pi))
            # The AoLP is ill-conditioned where the light is barely polarized (pinv rounding
            # of 1e-16·S0 turns it by 1e-16/DoLP): compare where the DoLP is at least 1e-4.
            sharp = polbrdf.stokes_dolp(stokes) > 1e-4
            assert sharp.sum() > 150
            np.testing.assert_allclose(circular(got - want, np.pi)[sharp], 0.0, atol=1e-9)


def test_polanalyser_reports_the_issue_example_as_106_85_degrees() -> None:
    pa = peer("polanalyser", POLANALYSER)
    psi = np.radians(-73.15)
    s = np.array([1.0, np.cos(2 * psi), np.sin(2 * psi), 0.0])
    assert float(polbrdf.stokes_aolp(s)) == pytest.approx(-73.15)
    # A level camera whose pixel angles grow toward image up: the same Stokes vector.
    cam = bridges.stokes_to_polanalyser(s, 0.0)
    np.testing.assert_allclose(cam, s, atol=1e-15)
    assert np.degrees(pa.cvtStokesToAoLP(cam[:3])) == pytest.approx(106.85)
    assert np.degrees(bridges.aolp_to_polanalyser(-73.15)) == pytest.approx(106.85)
    # Pixel angles growing toward image down (the pixel rows): 73.15°.
    cam = bridges.stokes_to_polanalyser(s, 0.0, y_down=True)
    assert np.degrees(pa.cvtStokesToAoLP(cam[:3])) == pytest.approx(73.15)


def _mitsuba():
    mi = peer("mitsuba", "pip install mitsuba")
    if "scalar_spectral_polarized" not in mi.variants():  # pragma: no cover
        pytest.skip("mitsuba lacks the scalar_spectral_polarized variant")
    mi.set_variant("scalar_spectral_polarized")
    return mi


def test_mitsuba_stokes_basis_and_rotate_mueller_basis() -> None:
    mi = _mitsuba()
    rng = np.random.default_rng(9)
    k = rng.normal(size=(50, 3))
    k[:5] = [[0, 0, 1], [0, 0, -1], [1, 0, 0], [0, -1, 0], [1e-9, 0, -1]]
    k /= np.linalg.norm(k, axis=-1, keepdims=True)
    ours = bridges.mitsuba_stokes_basis(k)
    theirs = np.array([np.array(mi.mueller.stokes_basis(mi.Vector3f(*v))) for v in k])
    np.testing.assert_allclose(ours, theirs, atol=1e-6)  # Mitsuba's float32
    paint = polbrdf.Material.preset("paint")
    done = 0
    for _ in range(60):
        ti, tr = rng.uniform(0.0, 1.4, 2)
        pi, pr = rng.uniform(-np.pi, np.pi, 2)
        wi, wr = direction(ti, pi), direction(tr, pr)
        f = polbrdf.mueller(paint, ti, pi, tr, pr, degrees=False)
        # Mitsuba's own basis change: psps s axes to its implicit bases, then its sign of S3.
        s_in = mi.Vector3f(np.sin(pi), -np.cos(pi), 0.0)
        s_out = mi.Vector3f(-np.sin(pr), np.cos(pr), 0.0)
        k_in, k_out = mi.Vector3f(*(-wi)), mi.Vector3f(*wr)
        m = np.array(mi.mueller.rotate_mueller_basis(
            mi.Matrix4f(f.tolist()), k_in, s_in, mi.mueller.stokes_basis(k_in),
            k_out, s_out, mi.mueller.stokes_basis(k_out)))
        p = np.diag([1.0, 1.0, 1.0, -1.0])
        want = p @ m @ p
        got = bridges.mueller_to_mitsuba(f, ti, pi, tr, pr, degrees=False)
        np.testing.assert_allclose(got, want, atol=2e-6 * abs(f[0, 0]))
        done += 1
    assert done == 60
