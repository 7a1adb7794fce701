"""Stokes helpers: the core's definitions (docs/model.md §2)."""

from __future__ import annotations

import doctest

import numpy as np
import pytest

import polbrdf


def test_known_states() -> None:
    s = np.array(
        [
            [1, 1, 0, 0],  # s-polarized
            [1, -1, 0, 0],  # p-polarized
            [1, 0, 1, 0],  # +45°
            [1, 0, 0, 1],  # circular
            [2, 1, 0, 0],  # half polarized
            [1, 0, 0, 0],  # unpolarized
            [0, 0, 0, 0],  # no light
            [-1, 1, 0, 0],  # S0 <= 0 -> 0
        ],
        dtype=float,
    )
    np.testing.assert_allclose(polbrdf.stokes_dolp(s), [1, 1, 1, 0, 0.5, 0, 0, 0])
    np.testing.assert_allclose(polbrdf.stokes_dop(s), [1, 1, 1, 1, 0.5, 0, 0, 0])
    np.testing.assert_allclose(polbrdf.stokes_aolp(s), [0, 90, 45, 0, 0, 0, 0, 0])
    np.testing.assert_allclose(
        polbrdf.stokes_aolp(s, degrees=False), np.radians([0, 90, 45, 0, 0, 0, 0, 0])
    )


def test_shapes_and_scalars() -> None:
    assert isinstance(polbrdf.stokes_dolp([2, 1, 1, 0]), np.float64)
    assert polbrdf.stokes_dolp(np.ones((3, 5, 4))).shape == (3, 5)
    with pytest.raises(ValueError, match=r"\(\.\.\., 4\)"):
        polbrdf.stokes_dolp(np.ones((3, 3)))
    with pytest.raises(ValueError):
        polbrdf.stokes_dop(1.0)


def test_match_the_model_for_unpolarized_input(paint: polbrdf.Material) -> None:
    rng = np.random.default_rng(11)
    g = rng.uniform([0, 0, 0, 0], [89, 360, 89, 360], size=(5000, 4)).T
    m = polbrdf.mueller(paint, *g)
    s_out = m @ np.array([1.0, 0, 0, 0])  # S_out = F · S_in (eq. 12)
    e = polbrdf.evaluate(paint, *g)
    np.testing.assert_allclose(polbrdf.stokes_dolp(s_out), e.dolp, rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(polbrdf.stokes_aolp(s_out), e.aolp, rtol=1e-15, atol=1e-12)
    # Surface reflection of unpolarized light has no circular part: DoP = DoLP.
    np.testing.assert_allclose(polbrdf.stokes_dop(s_out), e.dolp, rtol=1e-15, atol=1e-15)


def test_module_docstring_example() -> None:
    failures, tried = doctest.testmod(polbrdf, optionflags=doctest.NORMALIZE_WHITESPACE)[:2]
    assert tried > 0 and failures == 0
