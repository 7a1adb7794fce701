"""`mueller_directions`: the pBRDF at direction vectors (docs/model.md §9.11) — the results of
`mueller` at the vectors' angles, any vector length, broadcasting, `out=` and `precision`, the
horizon, and bad input named by argument and index. Mitsuba 3, which takes direction vectors
itself, is the oracle on the same float32 vectors in test_peer_mitsuba.py."""

from __future__ import annotations

import numpy as np
import pytest

import polbrdf

PAINT = polbrdf.Material.preset("paint")
METAL = polbrdf.Material(n=1.2, k=7.0, sigma_deg=11.3, shadowing=False)


def _vectors(theta_deg: np.ndarray, phi_deg: np.ndarray) -> np.ndarray:
    t, p = np.radians(theta_deg), np.radians(phi_deg)
    return np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1)


def _angles(w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """θ, φ (degrees) of vectors, as the direction entry point defines them."""
    r = np.hypot(w[..., 0], w[..., 1])
    phi = np.where(r > 0, np.arctan2(w[..., 1], w[..., 0]), 0.0)
    return np.degrees(np.arctan2(r, w[..., 2])), np.degrees(phi)


def _random(n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    ti, tr = rng.uniform(0.0, 89.0, (2, n))
    pi, pr = rng.uniform(0.0, 360.0, (2, n))
    # lengths over many decades: each vector is normalized
    scale = 10.0 ** rng.uniform(-10.0, 10.0, (2, n, 1))
    return _vectors(ti, pi) * scale[0], _vectors(tr, pr) * scale[1]


@pytest.mark.parametrize("material", [PAINT, METAL], ids=["paint", "metal"])
def test_directions_give_mueller_at_their_angles(material: polbrdf.Material) -> None:
    w_i, w_r = _random(20_000, seed=3)
    got = polbrdf.mueller_directions(material, w_i, w_r)
    ti, pi = _angles(w_i)
    tr, pr = _angles(w_r)
    want = polbrdf.mueller(material, ti, pi, tr, pr)
    assert got.shape == (20_000, 4, 4) and got.dtype == np.float64
    f00 = want[..., 0, 0]
    assert np.all(f00 > 0)
    dev = np.abs(got - want).max(axis=(-1, -2)) / f00
    # The degrees round trip of the angles costs a few ulps; the physics is the same.
    assert dev.max() < 1e-11, dev.max()


def test_float32_and_out() -> None:
    w_i, w_r = _random(5_000, seed=4)
    f64 = polbrdf.mueller_directions(PAINT, w_i, w_r)
    f32 = polbrdf.mueller_directions(PAINT, w_i, w_r, precision="float32")
    assert f32.dtype == np.float32
    err = np.abs(f32.astype(np.float64) - f64).max(axis=(-1, -2)) / f64[..., 0, 0]
    assert err.max() <= 1e-5, err.max()
    out = np.full((5_000, 4, 4), np.nan)
    res = polbrdf.mueller_directions(PAINT, w_i, w_r, out=out)
    assert res is out and np.array_equal(out, f64)
    with pytest.raises(ValueError, match="shape"):
        polbrdf.mueller_directions(PAINT, w_i, w_r, out=np.empty((4_999, 4, 4)))


def test_broadcasting_a_single_source_over_a_grid_of_views() -> None:
    theta, phi = np.meshgrid(np.linspace(0.0, 85.0, 18), np.linspace(0.0, 350.0, 36))
    views = _vectors(theta, phi)  # (36, 18, 3)
    sun = np.array([0.3, -0.2, 0.8])
    got = polbrdf.mueller_directions(PAINT, sun, views)
    assert got.shape == (36, 18, 4, 4)
    each = polbrdf.mueller_directions(PAINT, np.broadcast_to(sun, views.shape).copy(), views)
    assert np.array_equal(got, each)
    # With wavelengths broadcast too (a constant index does not depend on them).
    wl = np.array([0.5, 0.6])[:, None, None]
    spectral = polbrdf.mueller_directions(PAINT, sun, views, wavelength_um=wl)
    assert spectral.shape == (2, 36, 18, 4, 4)
    assert np.array_equal(spectral[1], got)


def test_the_normal_stands_for_azimuth_zero_and_the_horizon_for_zero() -> None:
    w_r = _vectors(np.array(35.0), np.array(70.0))
    got = polbrdf.mueller_directions(PAINT, [0.0, 0.0, 1.0], w_r)
    assert np.allclose(got, polbrdf.mueller(PAINT, 0.0, 0.0, 35.0, 70.0), rtol=1e-12, atol=0)
    assert not np.allclose(got, polbrdf.mueller(PAINT, 0.0, 90.0, 35.0, 70.0), rtol=1e-3)
    for w in ([1.0, 0.0, 0.0], [0.2, 0.1, -0.5], [0.0, 0.0, -1.0]):
        assert np.all(polbrdf.mueller_directions(PAINT, w, w_r) == 0.0)
        assert np.all(polbrdf.mueller_directions(PAINT, w_r, w) == 0.0)


@pytest.mark.parametrize(
    "bad",
    [[np.nan, 0.0, 1.0], [0.0, np.inf, 1.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1e-16], [2e15, 0.0, 1.0]],
)
def test_a_bad_vector_is_named_with_its_index(bad: list[float]) -> None:
    w_i, w_r = _random(3_000, seed=5)
    w_r = w_r.reshape(30, 100, 3)
    w_r[12, 34] = bad
    with pytest.raises(ValueError, match=r"w_r.*index 1234") as e:
        polbrdf.mueller_directions(PAINT, w_i.reshape(30, 100, 3), w_r)
    assert e.value.argument == "w_r" and e.value.index == 1234
    assert "(12, 34)" in "".join(getattr(e.value, "__notes__", []))


def test_shapes_and_types_are_checked() -> None:
    w = np.array([0.1, 0.2, 0.9])
    with pytest.raises(ValueError, match=r"w_i.*\(\.\.\., 3\)"):
        polbrdf.mueller_directions(PAINT, [0.1, 0.9], w)
    with pytest.raises(ValueError, match=r"w_r.*\(\.\.\., 3\)"):
        polbrdf.mueller_directions(PAINT, w, 1.0)
    with pytest.raises(ValueError, match="broadcast"):
        polbrdf.mueller_directions(PAINT, np.tile(w, (3, 1)), np.tile(w, (4, 1)))
    with pytest.raises(TypeError, match="real"):
        polbrdf.mueller_directions(PAINT, w.astype(complex), w)
    with pytest.raises(TypeError, match="Material"):
        polbrdf.mueller_directions("paint", w, w)  # type: ignore[arg-type]
    # Non-contiguous and integer input is accepted (copied).
    grid = np.zeros((5, 6))
    grid[:, 0] = 1
    grid[:, 4] = 1  # (x, y, z) = (1, 0, 1) in columns 0, 2, 4
    got = polbrdf.mueller_directions(PAINT, grid[:, ::2], np.array([0, 0, 1]))
    assert np.allclose(got, polbrdf.mueller(PAINT, 45.0, 0.0, 0.0, 0.0), rtol=1e-12, atol=0)
    assert polbrdf.mueller_directions(PAINT, np.empty((0, 3)), w).shape == (0, 4, 4)


@pytest.mark.parametrize("precision", ["float64", "float32"])
def test_a_bad_vector_in_the_last_block_leaves_out_all_nan(precision: str) -> None:
    # Validated as the kernel reads each block: the other chunks are written first, then the
    # whole of `out` is set to NaN (never a partial result), and the vector is named as before.
    n = 3 * 4096 + 5
    w_i, w_r = _random(n, seed=9)
    w_r[-1] = [0.0, np.nan, 1.0]
    out = np.full((n, 4, 4), 7.0, dtype=precision)
    with pytest.raises(ValueError, match=rf"w_r.*index {n - 1}") as e:
        polbrdf.mueller_directions(PAINT, w_i, w_r, out=out, precision=precision)
    assert e.value.argument == "w_r" and e.value.index == n - 1
    assert np.isnan(out).all()
