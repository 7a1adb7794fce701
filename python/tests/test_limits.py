"""Issue 18's Python items: MemoryError for outputs that cannot be allocated, complex and masked
inputs, more than 32 dimensions, the number of fit starts, degenerate fit data, the azimuth
bound."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import numpy as np
import pytest

import polbrdf


def test_an_output_too_large_for_memory_is_a_memory_error() -> None:
    # Under RLIMIT_AS = 3 GB, a (5000, 10000, 4, 4) pBRDF (6.4 GB) cannot be allocated: a
    # MemoryError that `except MemoryError` catches (was: PanicException, a BaseException).
    code = textwrap.dedent(
        """
        import resource
        import numpy as np
        import polbrdf
        resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))
        m = polbrdf.Material.preset("paint")
        for call in (
            lambda: polbrdf.mueller(m, np.zeros((5000, 1)), 0, np.zeros((1, 10000)), 0),
            lambda: polbrdf.evaluate(m, np.zeros((8000, 1)), 0, np.zeros((1, 10000)), 0),
            lambda: polbrdf.brdf(m, np.zeros((20000, 1)), 0, np.zeros((1, 20000)), 0),
        ):
            try:
                call()
            except MemoryError:
                print("MemoryError")
        """
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=False
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["MemoryError"] * 3, out.stdout + out.stderr


def test_more_than_32_dimensions_is_a_value_error(paint: polbrdf.Material) -> None:
    a = np.zeros((1,) * 33)
    with pytest.raises(ValueError, match="33 dimensions: at most 32"):
        polbrdf.mueller(paint, a, 0, 30, 180)


def test_masked_angles_are_refused_and_unmasked_ones_work(paint: polbrdf.Material) -> None:
    theta = np.ma.masked_array([10.0, 20.0, 30.0], mask=[False, True, False])
    with pytest.raises(ValueError, match="`theta_i` is a masked array with 1 masked entry"):
        polbrdf.brdf(paint, theta, 0, 30, 180)
    clean = np.ma.masked_array([10.0, 20.0], mask=[False, False])
    assert np.array_equal(
        polbrdf.brdf(paint, clean, 0, 30, 180), polbrdf.brdf(paint, [10.0, 20.0], 0, 30, 180)
    )


def _data(paint: polbrdf.Material) -> tuple[np.ndarray, np.ndarray]:
    theta = np.linspace(5, 70, 14)
    return theta, polbrdf.brdf(paint, theta, 0, theta, 180)


def test_masked_fit_data_are_not_measured(paint: polbrdf.Material) -> None:
    theta, f = _data(paint)
    bad = f.copy()
    bad[3] = 1e6  # masked: must not count
    masked = np.ma.masked_array(bad, mask=np.arange(14) == 3)
    nan = f.copy()
    nan[3] = np.nan
    a = polbrdf.fit(paint, theta, 0, theta, 180, {"brdf": masked}, "n")
    b = polbrdf.fit(paint, theta, 0, theta, 180, {"brdf": nan}, "n")
    assert np.array_equal(a.values, b.values)
    assert len(a.residuals) == 13


def test_complex_fit_data_are_a_type_error(paint: polbrdf.Material) -> None:
    theta, f = _data(paint)
    with pytest.raises(TypeError, match="`brdf` must hold real numbers"):
        polbrdf.fit(paint, theta, 0, theta, 180, {"brdf": f + 0j}, "n")
    with pytest.raises(TypeError, match="sigma"):
        polbrdf.fit(
            paint, theta, 0, theta, 180, {"brdf": f}, "n", sigma={"brdf": f * 0.01 + 0j}
        )


@pytest.mark.parametrize("starts", [10**9, -1, 10**30])
def test_starts_are_bounded(paint: polbrdf.Material, starts: int) -> None:
    theta, f = _data(paint)
    with pytest.raises(ValueError, match="starts"):
        polbrdf.fit(paint, theta, 0, theta, 180, {"brdf": f}, "n", starts=starts)


def test_repeated_rows_warn(paint: polbrdf.Material) -> None:
    f = float(polbrdf.brdf(paint, 30, 0, 30, 180))
    r = polbrdf.fit(paint, np.full(50, 30.0), 0, 30, 180, {"brdf": np.full(50, f)}, "n")
    assert len(r.warnings) == 1 and "not meaningful" in r.warnings[0]
    theta, g = _data(paint)
    assert polbrdf.fit(paint, theta, 0, theta, 180, {"brdf": g}, "n").warnings == []


@pytest.mark.parametrize("phi", [1e17, -1e300])
def test_azimuths_beyond_the_bound_are_refused(paint: polbrdf.Material, phi: float) -> None:
    with pytest.raises(ValueError, match="1e8"):
        polbrdf.mueller(paint, 30, phi, 30, 180)
