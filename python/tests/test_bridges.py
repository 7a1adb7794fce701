"""`polbrdf.bridges` (docs/bridges.md): each convention against an independent construction in
NumPy (the field as a 3-D vector, Malus's law, the model's isotropy). The peers themselves
(polanalyser, Mitsuba 3, pySCATMECH) are in test_bridges_peers.py, test_mitsuba_pbsdf.py and
test_scatmech_oracle.py."""

from __future__ import annotations

import doctest

import numpy as np
import pytest

import polbrdf
from polbrdf import bridges


def direction(theta_deg: np.ndarray, phi_deg: np.ndarray) -> np.ndarray:
    t, p = np.radians(theta_deg), np.radians(phi_deg)
    return np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1)


def reflected_frame(theta_r: float, phi_r: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """docs/model.md §2: s_out = (−sinφr, cosφr, 0), p_out = k × s_out, k = w_r."""
    k = direction(np.float64(theta_r), np.float64(phi_r))
    p = np.radians(phi_r)
    s = np.array([-np.sin(p), np.cos(p), 0.0])
    return s, np.cross(k, s), k


def test_the_module_docstring_example_runs() -> None:
    failures, tried = doctest.testmod(bridges, optionflags=doctest.NORMALIZE_WHITESPACE)[:2]
    assert tried >= 5 and failures == 0


def test_the_issue_example_is_the_range_alone() -> None:
    # The same Stokes vector: −73.15° in polbrdf, 106.85° (in radians) in polanalyser for a level
    # camera whose angles grow toward image up; 73.15° when they grow toward image down.
    assert np.degrees(bridges.aolp_to_polanalyser(-73.15)) == pytest.approx(106.85, abs=1e-9)
    assert np.degrees(bridges.aolp_to_polanalyser(-73.15, y_down=True)) == pytest.approx(73.15)
    assert np.degrees(bridges.aolp_to_polanalyser(-73.15, roll=30.0)) == pytest.approx(76.85)
    a = bridges.aolp_to_polanalyser(np.linspace(-89.9, 90, 50), roll=[[0.0], [45.0], [-170.0]])
    assert a.shape == (3, 50) and np.all((a >= 0) & (a < np.pi))


def test_camera_stokes_follow_malus_law() -> None:
    rng = np.random.default_rng(4)
    for _ in range(20):
        tr, pr = rng.uniform(1, 85), rng.uniform(-180, 180)
        s, p, k = reflected_frame(tr, pr)
        roll = rng.uniform(-180, 180)
        c, sn = np.cos(np.radians(roll)), np.sin(np.radians(roll))
        x, up = c * s + sn * p, -sn * s + c * p
        # The camera's up vector need not be across the beam: only its part across counts.
        got_roll = bridges.camera_roll(tr, pr, up + 0.4 * k)
        assert np.degrees(np.angle(np.exp(1j * np.radians(got_roll - roll)))) == pytest.approx(
            0.0, abs=1e-9)
        psi = rng.uniform(-90, 90)
        e = np.cos(np.radians(psi)) * s + np.sin(np.radians(psi)) * p
        sto = np.array([1.0, np.cos(np.radians(2 * psi)), np.sin(np.radians(2 * psi)), 0.0])
        for y_down, yaxis in [(False, up), (True, -up)]:
            i = [np.dot(e, np.cos(np.radians(a)) * x + np.sin(np.radians(a)) * yaxis) ** 2
                 for a in (0, 45, 90, 135)]
            want = [i[0] + i[2], i[0] - i[2], i[1] - i[3]]
            got = bridges.stokes_to_polanalyser(sto, got_roll, y_down=y_down)
            np.testing.assert_allclose(got[:3], want, atol=1e-12)
    # A level camera: no roll, and stokes_to_camera is the identity there.
    assert bridges.camera_roll(40.0, 30.0, [0.0, 0.0, 1.0]) == pytest.approx(0.0, abs=1e-12)
    sto = np.array([[1.0, 0.2, -0.3, 0.1]])
    np.testing.assert_allclose(bridges.stokes_to_camera(sto, 0.0), sto)
    back = bridges.stokes_from_camera(bridges.stokes_to_camera(sto, 33.0), 33.0)
    np.testing.assert_allclose(back, sto, atol=1e-15)


def test_bad_camera_up_and_shapes_are_refused() -> None:
    with pytest.raises(ValueError, match=r"element 1: .*`up`.*not parallel to the view"):
        bridges.camera_roll([30.0, 0.0], 0.0, [0.0, 0.0, 1.0])
    with pytest.raises(ValueError, match=r"shape \(\.\.\., 4\)"):
        bridges.stokes_to_camera([1.0, 0.0, 0.0], 10.0)
    with pytest.raises(ValueError, match=r"theta_r_deg"):
        bridges.camera_roll(120.0 + 100.0, 0.0, [0.0, 0.0, 1.0])
    with pytest.raises(TypeError, match="real numbers"):
        bridges.stokes_to_camera(["a", "b", "c", "d"])


def test_scatmech_angles() -> None:
    ti, ts, ps = bridges.to_scatmech(30.0, 15.0, 30.0, 195.0)
    assert (ti, ts, ps) == (30.0, 30.0, pytest.approx(0.0, abs=1e-12))
    assert bridges.to_scatmech(30.0, 15.0, 30.0, 15.0)[2] == pytest.approx(180.0)
    rng = np.random.default_rng(8)
    g = (rng.uniform(0, 85, 200), rng.uniform(-400, 400, 200), rng.uniform(0, 85, 200),
         rng.uniform(-400, 400, 200))
    ti, ts, ps = bridges.to_scatmech(*g)
    assert np.all((ps > -180) & (ps <= 180))
    back = bridges.from_scatmech(ti, ts, ps)
    np.testing.assert_array_equal(back[1], 180.0)
    # Isotropy: SCATMECH's azimuths give the model's own pBRDF.
    paint = polbrdf.Material.preset("paint")
    f = polbrdf.mueller(paint, *g)
    np.testing.assert_allclose(polbrdf.mueller(paint, *back), f, rtol=1e-10, atol=1e-14)
    rad = bridges.to_scatmech(*(np.radians(a) for a in g), degrees=False)
    np.testing.assert_allclose(np.degrees(rad[2]), ps, atol=1e-9)


def test_mitsuba_frames_without_mitsuba() -> None:
    rng = np.random.default_rng(2)
    k = rng.normal(size=(100, 3))
    k /= np.linalg.norm(k, axis=-1, keepdims=True)
    x = bridges.mitsuba_stokes_basis(k)
    np.testing.assert_allclose(np.einsum("ij,ij->i", x, k), 0.0, atol=1e-15)
    np.testing.assert_allclose(np.linalg.norm(x, axis=-1), 1.0, atol=1e-15)
    paint = polbrdf.Material.preset("paint")
    g = (rng.uniform(0, 85, 50), rng.uniform(-180, 180, 50), rng.uniform(0, 85, 50),
         rng.uniform(-180, 180, 50))
    f = polbrdf.mueller(paint, *g)
    m = bridges.mueller_to_mitsuba(f, *g)
    np.testing.assert_allclose(bridges.mueller_from_mitsuba(m, *g), f, rtol=0, atol=1e-13)
    # The field turns as the 3-D vectors say: a linear state along e has Mitsuba's AoLP
    # atan2(e·(k × x), e·x); circular light changes sign.
    for j in range(5):
        s, p, kk = reflected_frame(g[2][j], g[3][j])
        xm = bridges.mitsuba_stokes_basis(kk)
        e = np.cos(0.3) * s + np.sin(0.3) * p
        got = bridges.stokes_to_mitsuba([1.0, np.cos(0.6), np.sin(0.6), 0.5], *(a[j] for a in g))
        want = np.arctan2(np.dot(e, np.cross(kk, xm)), np.dot(e, xm))
        d = np.angle(np.exp(2j * (polbrdf.stokes_aolp(got, degrees=False) - want)))
        assert abs(d) < 1e-12 and got[3] == pytest.approx(-0.5)
