"""`mueller`'s `precision` (float32 results) and `out=` (numpy convention) arguments."""

from __future__ import annotations

import numpy as np
import pytest
from support import material_of

import polbrdf


def _geometries(n: int, seed: int = 1) -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(seed)
    ti, tr = rng.uniform(0.0, 89.99, (2, n))
    pi, pr = rng.uniform(-360.0, 720.0, (2, n))
    # near-specular and grazing ones too
    tr[: n // 4] = ti[: n // 4] + rng.normal(0.0, 1e-4, n // 4).clip(-ti[: n // 4], None)
    pr[: n // 4] = pi[: n // 4] + 180.0
    ti[-n // 8 :] = 89.95
    return ti, pi, tr, pr


def _specular_f00(material: polbrdf.Material, ti: np.ndarray, pi: np.ndarray) -> np.ndarray:
    """P of the float32 contract: F00 (float64) at the specular direction of the same θi."""
    return polbrdf.mueller(material, ti, pi, ti, np.asarray(pi) + 180.0)[..., 0, 0]


@pytest.mark.parametrize(
    "material",
    [
        polbrdf.Material.preset("paint"),
        polbrdf.Material.preset("aluminium"),
        polbrdf.Material(n=3.0, k=200.0, sigma_deg=40.0),
        polbrdf.Material(n=1.5, sigma_deg=0.5, rho_d=0.02, rho_v=0.01),
    ],
)
def test_float32_is_within_the_contract(material: polbrdf.Material) -> None:
    # Computed in single precision (docs/model.md §12, the float32 contract): every entry
    # within 1e-5·F00 + 1e-6·P of float64, P the F00 at the specular direction of the same θi
    # (plus half f32's smallest subnormal, for results at the bottom of its range).
    g = _geometries(20_000)
    f64 = polbrdf.mueller(material, *g)
    f32 = polbrdf.mueller(material, *g, precision="float32")
    assert f32.dtype == np.float32 and f32.shape == f64.shape
    f00 = f64[..., 0, 0]
    p = _specular_f00(material, g[0], g[1])
    err = np.abs(f32.astype(np.float64) - f64).max(axis=(-1, -2))
    big = f00 > 1e-35
    assert big.sum() > 1000
    assert np.all(err <= 1e-5 * f00 + 1e-6 * p + 2.0**-150)


def test_float32_is_computed_in_single_precision(paint: polbrdf.Material) -> None:
    # Not float64 rounded: most elements of a rough paint differ from that in the last bits.
    g = _geometries(20_000)
    f64 = polbrdf.mueller(paint, *g)
    f32 = polbrdf.mueller(paint, *g, precision="float32")
    differs = np.any(f32 != f64.astype(np.float32), axis=(-1, -2))
    assert differs.mean() > 0.3


def test_float32_on_the_test_vectors(vectors: list[dict]) -> None:
    for c in vectors:
        inp = c["inputs"]
        m = material_of(inp)
        a = [inp[k] for k in ("theta_i_deg", "phi_i_deg", "theta_r_deg", "phi_r_deg")]
        f64 = polbrdf.mueller(m, *a)
        f32 = polbrdf.mueller(m, *a, precision=np.float32)
        assert f32.dtype == np.float32
        p = _specular_f00(m, a[0], a[1])
        assert np.abs(f32 - f64).max() <= 1e-5 * f64[0, 0] + 1e-6 * p + 1e-44, c["id"]


def test_out_is_filled_and_returned(paint: polbrdf.Material) -> None:
    g = _geometries(5000)
    want = polbrdf.mueller(paint, *g)
    for dtype in (np.float64, np.float32):
        out = np.full(want.shape, np.nan, dtype=dtype)
        got = polbrdf.mueller(paint, *g, out=out)
        assert got is out
        if dtype == np.float64:
            np.testing.assert_array_equal(out, want)
        else:
            # The float32 path (precision from out's dtype), bit for bit.
            np.testing.assert_array_equal(out, polbrdf.mueller(paint, *g, precision="float32"))
            assert np.all(np.abs(out - want).max(axis=(-1, -2)) <= 1e-5 * want[..., 0, 0] + 1e-44)
    # Multi-dimensional broadcast shapes.
    ti = np.linspace(0.0, 80.0, 7)[:, None]
    tr = np.linspace(0.0, 80.0, 5)[None, :]
    out = np.empty((7, 5, 4, 4))
    assert polbrdf.mueller(paint, ti, 0.0, tr, 180.0, out=out) is out
    np.testing.assert_array_equal(out, polbrdf.mueller(paint, ti, 0.0, tr, 180.0))


def test_out_and_precision_are_checked(paint: polbrdf.Material) -> None:
    t = np.array([10.0, 20.0, 30.0])
    with pytest.raises(ValueError, match="shape"):
        polbrdf.mueller(paint, t, 0.0, t, 180.0, out=np.empty((3, 16)))
    with pytest.raises(ValueError, match="dtype"):
        polbrdf.mueller(paint, t, 0.0, t, 180.0, out=np.empty((3, 4, 4), dtype=np.int64))
    with pytest.raises(ValueError, match="precision is float32"):
        polbrdf.mueller(paint, t, 0.0, t, 180.0, out=np.empty((3, 4, 4)), precision="float32")
    with pytest.raises(ValueError, match="C-contiguous"):
        polbrdf.mueller(paint, t, 0.0, t, 180.0, out=np.empty((4, 4, 3)).transpose(2, 0, 1))
    ro = np.empty((3, 4, 4))
    ro.flags.writeable = False
    with pytest.raises(ValueError, match="writeable"):
        polbrdf.mueller(paint, t, 0.0, t, 180.0, out=ro)
    with pytest.raises(TypeError, match="ndarray"):
        polbrdf.mueller(paint, t, 0.0, t, 180.0, out=[[0.0] * 16] * 3)
    for bad in ("float16", "double-ish", np.int32):
        with pytest.raises(ValueError, match="precision"):
            polbrdf.mueller(paint, t, 0.0, t, 180.0, precision=bad)


def test_float32_beyond_its_range_is_refused() -> None:
    m = polbrdf.Material(n=1.5, sigma_deg=5.0, rho_d=1e100, rho_v=1e100)
    with pytest.raises(ValueError, match="float32"):
        polbrdf.mueller(m, 30.0, 0.0, 30.0, 180.0, precision="float32")
    assert np.isfinite(polbrdf.mueller(m, 30.0, 0.0, 30.0, 180.0)).all()


def test_scalar_arguments_broadcast_in_the_engine(paint: polbrdf.Material) -> None:
    # A scalar angle is passed as one value and broadcast by the engine: the same numbers as
    # the materialized array, for every output and in both units.
    ti, pi, tr, pr = _geometries(3000)
    for degrees, s in ((True, 35.0), (False, 0.6)):
        full = np.full_like(ti, s)
        for i in range(4):
            args = [ti, pi, tr, pr]
            if not degrees:
                args = [np.radians(a) for a in args]
            mat = list(args)
            args[i], mat[i] = s, full
            np.testing.assert_array_equal(
                polbrdf.mueller(paint, *args, degrees=degrees),
                polbrdf.mueller(paint, *mat, degrees=degrees),
            )
            np.testing.assert_array_equal(
                polbrdf.brdf(paint, *args, degrees=degrees),
                polbrdf.brdf(paint, *mat, degrees=degrees),
            )
            e1 = polbrdf.evaluate(paint, *args, degrees=degrees, with_mueller=True)
            e2 = polbrdf.evaluate(paint, *mat, degrees=degrees, with_mueller=True)
            np.testing.assert_array_equal(e1.aolp, e2.aolp)
            np.testing.assert_array_equal(e1.mueller, e2.mueller)
    # All scalars, and scalars with an empty array.
    assert polbrdf.mueller(paint, 30.0, 0.0, 30.0, 180.0).shape == (4, 4)
    assert polbrdf.mueller(paint, 30.0, 0.0, np.empty(0), 180.0).shape == (0, 4, 4)
    # A bad scalar is named, at flat index 0.
    with pytest.raises(ValueError, match="theta_r") as e:
        polbrdf.mueller(paint, ti, pi, np.nan, pr)
    assert e.value.index == 0


@pytest.mark.parametrize("precision", ["float64", "float32"])
def test_planar_layout_holds_the_same_bits(paint: polbrdf.Material, precision: str) -> None:
    # layout="planar": F[i, j, ...] — the interleaved result's matrix axes moved first, bit for
    # bit, for angles (broadcast, multi-dimensional) and direction vectors, with and without
    # out=, on both sides of the serial driver's bound (2048 elements).
    for n in (1, 2048, 5001):
        g = _geometries(n, seed=n)
        rows = polbrdf.mueller(paint, *g, precision=precision)
        planes = polbrdf.mueller(paint, *g, precision=precision, layout="planar")
        assert planes.shape == (4, 4, n) and planes.dtype == rows.dtype
        assert planes.flags.c_contiguous
        np.testing.assert_array_equal(planes, np.moveaxis(rows, (-2, -1), (0, 1)))
        out = np.full((4, 4, n), np.nan, dtype=precision)
        assert polbrdf.mueller(paint, *g, out=out, layout="planar") is out
        np.testing.assert_array_equal(out, planes)
    ti = np.linspace(0.0, 80.0, 7)[:, None]
    tr = np.linspace(0.0, 80.0, 5)[None, :]
    rows = polbrdf.mueller(paint, ti, 0.0, tr, 180.0, precision=precision)
    planes = polbrdf.mueller(paint, ti, 0.0, tr, 180.0, precision=precision, layout="planar")
    assert planes.shape == (4, 4, 7, 5)
    np.testing.assert_array_equal(planes, np.moveaxis(rows, (-2, -1), (0, 1)))
    rng = np.random.default_rng(3)
    w_i = rng.normal(size=(3000, 3))
    w_r = rng.normal(size=(3000, 3))
    w_i[:, 2], w_r[:, 2] = np.abs(w_i[:, 2]), np.abs(w_r[:, 2])
    rows = polbrdf.mueller_directions(paint, w_i, w_r, precision=precision)
    planes = polbrdf.mueller_directions(paint, w_i, w_r, precision=precision, layout="planar")
    np.testing.assert_array_equal(planes, np.moveaxis(rows, (-2, -1), (0, 1)))


def test_planar_layout_and_its_out_are_checked(paint: polbrdf.Material) -> None:
    t = np.array([10.0, 20.0, 30.0])
    with pytest.raises(ValueError, match="layout"):
        polbrdf.mueller(paint, t, 0.0, t, 180.0, layout="soa")
    with pytest.raises(ValueError, match="layout"):
        polbrdf.mueller_directions(paint, [0.0, 0.0, 1.0], [0.0, 0.0, 1.0], layout="rows")
    # An interleaved out for a planar result (and the reverse) is refused by its shape.
    with pytest.raises(ValueError, match=r"shape \(4, 4, 3\)"):
        polbrdf.mueller(paint, t, 0.0, t, 180.0, out=np.empty((3, 4, 4)), layout="planar")
    with pytest.raises(ValueError, match=r"shape \(3, 4, 4\)"):
        polbrdf.mueller(paint, t, 0.0, t, 180.0, out=np.empty((4, 4, 3)))
    assert polbrdf.mueller(paint, t[:0], 0.0, t[:0], 180.0, layout="planar").shape == (4, 4, 0)


@pytest.mark.parametrize("layout", ["interleaved", "planar"])
@pytest.mark.parametrize("precision", ["float64", "float32"])
def test_an_invalid_late_element_is_named_and_out_holds_only_nan(
    paint: polbrdf.Material, precision: str, layout: str
) -> None:
    # The kernel validates each block as it reads it, so other chunks (4096 elements, in
    # parallel) are written before the last block's invalid element is met: the error still
    # names the element and its index, and `out` is set to NaN, never left half-written.
    n = 5 * 4096 + 17
    for field, bad, message in [
        (2, np.nan, r"`theta_r` = NaN \(at index 20496\)"),
        (1, np.inf, r"`phi_i` = inf \(at index 20496\)"),
        (0, -1.0, r"`theta_i` = -1 \(at index 20496\)"),
    ]:
        g = list(_geometries(n, seed=7))
        g[field] = g[field].copy()
        g[field][-1] = bad
        shape = (n, 4, 4) if layout == "interleaved" else (4, 4, n)
        out = np.full(shape, 7.0, dtype=precision)
        with pytest.raises(ValueError, match=message) as e:
            polbrdf.mueller(paint, *g, out=out, precision=precision, layout=layout)
        assert e.value.index == n - 1
        assert np.isnan(out).all()
        # Valid input into the same array: the results, bit for bit.
        g[field][-1] = 10.0
        polbrdf.mueller(paint, *g, out=out, precision=precision, layout=layout)
        want = polbrdf.mueller(paint, *g, precision=precision, layout=layout)
        np.testing.assert_array_equal(out, want)
