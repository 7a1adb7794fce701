"""Broadcasting, dtypes, memory layouts and a large batch."""

from __future__ import annotations

import numpy as np
import pytest

import polbrdf


def reference(mat: polbrdf.Material, *angles: object) -> np.ndarray:
    """Element-by-element evaluation, one scalar call per geometry."""
    b = np.broadcast_arrays(*[np.asarray(a, dtype=np.float64) for a in angles])
    out = np.empty(b[0].shape + (4, 4))
    for idx in np.ndindex(b[0].shape):
        out[idx] = polbrdf.mueller(mat, *[float(x[idx]) for x in b])
    return out


def test_scalars_give_numpy_scalars(paint: polbrdf.Material) -> None:
    f = polbrdf.brdf(paint, 60, 0, 60, 180)
    assert isinstance(f, np.float64) and f > 0
    assert np.ndim(polbrdf.dolp(paint, 60, 0, 60, 180)) == 0
    assert polbrdf.mueller(paint, 60, 0, 60, 180).shape == (4, 4)
    e = polbrdf.evaluate(paint, 60, 0, 60, 180, with_mueller=True)
    assert np.ndim(e.brdf) == np.ndim(e.dolp) == np.ndim(e.aolp) == 0
    assert e.mueller is not None and e.mueller.shape == (4, 4)
    assert e.brdf == f == e.mueller[0, 0]


def test_scalar_times_array(paint: polbrdf.Material) -> None:
    theta = np.linspace(0, 89, 7)
    m = polbrdf.mueller(paint, theta, 0, 30, 180)
    assert m.shape == (7, 4, 4)
    np.testing.assert_array_equal(m, reference(paint, theta, 0, 30, 180))
    assert polbrdf.brdf(paint, 30, [0, 90, 180], 30, 180).shape == (3,)
    np.testing.assert_array_equal(polbrdf.brdf(paint, theta, 0, 30, 180), m[:, 0, 0])


def test_outer_product_shapes(paint: polbrdf.Material) -> None:
    ti = np.array([[10.0], [40.0], [70.0]])  # (3, 1)
    pr = np.array([[0.0, 90.0, 180.0, 270.0]])  # (1, 4)
    m = polbrdf.mueller(paint, ti, 0, 45, pr)
    assert m.shape == (3, 4, 4, 4)
    np.testing.assert_array_equal(m, reference(paint, ti, 0, 45, pr))
    f, d = polbrdf.brdf(paint, ti, 0, 45, pr), polbrdf.dolp(paint, ti, 0, 45, pr)
    assert f.shape == d.shape == (3, 4)
    np.testing.assert_array_equal(f, m[..., 0, 0])
    e = polbrdf.evaluate(paint, ti, 0, 45, pr, with_mueller=True)
    assert e.brdf.shape == e.dolp.shape == e.aolp.shape == (3, 4)
    np.testing.assert_array_equal(e.mueller, m)
    np.testing.assert_array_equal(e.dolp, d)
    # Three-way broadcast to (2, 3, 4).
    m3 = polbrdf.mueller(paint, np.zeros((2, 1, 1)) + [[[20]], [[50]]], ti[None], 45, pr)
    assert m3.shape == (2, 3, 4, 4, 4)


def test_lists_and_empty(paint: polbrdf.Material) -> None:
    np.testing.assert_array_equal(
        polbrdf.brdf(paint, [10, 20], [0, 0], [30, 30], [180, 180]),
        polbrdf.brdf(paint, np.array([10.0, 20.0]), 0.0, 30.0, 180.0),
    )
    assert polbrdf.mueller(paint, [], 0, 0, 0).shape == (0, 4, 4)
    assert polbrdf.brdf(paint, np.zeros((0, 3)), 0, 0, 0).shape == (0, 3)


def test_incompatible_shapes_raise(paint: polbrdf.Material) -> None:
    with pytest.raises(ValueError, match="broadcast"):
        polbrdf.brdf(paint, [1, 2, 3], [1, 2], 0, 0)


@pytest.mark.parametrize(
    "dtype", [np.float64, np.float32, np.float16, np.int64, np.int32, np.int16, np.uint8]
)
def test_dtypes(paint: polbrdf.Material, dtype: type) -> None:
    theta: np.ndarray = np.array([0, 10, 33, 60, 85], dtype=dtype)
    phi: np.ndarray = np.array([0, 45, 90, 180, 250], dtype=dtype)
    want = polbrdf.mueller(paint, theta.astype(np.float64), 0, 40, phi.astype(np.float64))
    got = polbrdf.mueller(paint, theta, 0, 40, phi)
    assert got.dtype == np.float64
    np.testing.assert_array_equal(got, want)
    np.testing.assert_array_equal(polbrdf.brdf(paint, theta, 0, 40, phi), want[:, 0, 0])


def test_python_int_and_bool_scalars(paint: polbrdf.Material) -> None:
    assert polbrdf.brdf(paint, 60, 0, 60, 180) == polbrdf.brdf(paint, 60.0, 0.0, 60.0, 180.0)


def test_non_real_dtypes_raise(paint: polbrdf.Material) -> None:
    with pytest.raises(TypeError, match="theta_r"):
        polbrdf.brdf(paint, 10, 0, np.array([1 + 1j]), 0)
    with pytest.raises(TypeError, match="phi_i"):
        polbrdf.brdf(paint, 10, ["a"], 10, 0)


def test_non_contiguous_inputs(paint: polbrdf.Material) -> None:
    rng = np.random.default_rng(1)
    base = rng.uniform(0, 85, size=(40, 30))
    phi = rng.uniform(0, 360, size=(40, 30))
    views = {
        "step": (base[::2, ::3], phi[::2, ::3]),
        "transposed": (base.T, phi.T),
        "reversed": (base[::-1, ::-2], phi[::-1, ::-2]),
        "fortran": (np.asfortranarray(base), np.asfortranarray(phi)),
        "column": (base[:, 5], phi[:, 7]),
    }
    for name, (t, p) in views.items():
        assert not t.flags.c_contiguous, name
        want = polbrdf.mueller(paint, t.copy(), 10, 50, p.copy())
        got = polbrdf.mueller(paint, t, 10, 50, p)
        np.testing.assert_array_equal(got, want, err_msg=name)
        assert got.shape == t.shape + (4, 4)
        np.testing.assert_array_equal(
            polbrdf.dolp(paint, t, 10, 50, p), polbrdf.dolp(paint, t.copy(), 10, 50, p.copy())
        )
    # Strided float32 view of a bigger array (conversion + gather).
    f32 = base.astype(np.float32)[::3, 1::2]
    np.testing.assert_array_equal(
        polbrdf.brdf(paint, f32, 0, 30, 180),
        polbrdf.brdf(paint, f32.astype(np.float64), 0, 30, 180),
    )


def test_inputs_are_not_modified(paint: polbrdf.Material) -> None:
    t = np.array([10.0, 20.0, 30.0])
    t0 = t.copy()
    polbrdf.mueller(paint, t, t, t, t)
    np.testing.assert_array_equal(t, t0)


def test_degrees_and_radians_agree(paint: polbrdf.Material) -> None:
    rng = np.random.default_rng(3)
    g = rng.uniform([0, 0, 0, 0], [89, 360, 89, 360], size=(1000, 4))
    deg = polbrdf.mueller(paint, *g.T)
    rad = polbrdf.mueller(paint, *np.radians(g).T, degrees=False)
    np.testing.assert_array_equal(deg, rad)
    e = polbrdf.evaluate(paint, *g.T)
    er = polbrdf.evaluate(paint, *np.radians(g).T, degrees=False)
    np.testing.assert_allclose(np.radians(e.aolp), er.aolp, rtol=1e-15, atol=1e-15)


def test_one_million_geometries(paint: polbrdf.Material) -> None:
    n = 1_000_000
    rng = np.random.default_rng(2024)
    ti = rng.uniform(0, 89.9, n)
    pi = rng.uniform(0, 360, n)
    tr = rng.uniform(0, 89.9, n)
    pr = rng.uniform(0, 360, n)
    m = polbrdf.mueller(paint, ti, pi, tr, pr)
    assert m.shape == (n, 4, 4) and m.dtype == np.float64
    assert np.isfinite(m).all()
    assert (m[:, 0, 0] > 0).all()
    f, d = polbrdf.brdf(paint, ti, pi, tr, pr), polbrdf.dolp(paint, ti, pi, tr, pr)
    assert f.shape == d.shape == (n,)
    assert np.isfinite(f).all() and np.isfinite(d).all()
    assert ((d >= 0) & (d <= 1)).all()
    np.testing.assert_array_equal(f, m[:, 0, 0])
    e = polbrdf.evaluate(paint, ti, pi, tr, pr)
    np.testing.assert_array_equal(e.brdf, f)
    np.testing.assert_array_equal(e.dolp, d)
    assert ((e.aolp > -90) & (e.aolp <= 90)).all()


def test_threads_agree(paint: polbrdf.Material) -> None:
    """Calls from several Python threads (the GIL is released during evaluation)."""
    from concurrent.futures import ThreadPoolExecutor

    rng = np.random.default_rng(5)
    batches = [rng.uniform(0, 80, size=(4, 20_000)) for _ in range(6)]
    want = [polbrdf.mueller(paint, *b) for b in batches]
    with ThreadPoolExecutor(max_workers=3) as pool:
        got = list(pool.map(lambda b: polbrdf.mueller(paint, *b), batches))
    for w, g in zip(want, got):
        np.testing.assert_array_equal(w, g)
