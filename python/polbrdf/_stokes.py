"""Stokes helpers (the core's definitions, docs/model.md §2): the degree of linear
polarization, the degree of polarization and the angle of linear polarization of Stokes
vectors ``(..., 4)``."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._common import public


def _stokes(s: ArrayLike) -> NDArray[np.float64]:
    arr = np.asarray(s, dtype=np.float64)
    if arr.ndim == 0 or arr.shape[-1] != 4:
        raise ValueError(
            f"expected Stokes vectors of shape (..., 4) = (S0, S1, S2, S3), got shape {arr.shape}"
        )
    return arr


def _ratio(num: NDArray[np.float64], den: NDArray[np.float64]) -> NDArray[np.float64]:
    out = np.zeros(np.broadcast(num, den).shape)
    np.divide(num, den, out=out, where=den > 0)
    return out[()] if out.ndim == 0 else out


@public
def stokes_dolp(s: ArrayLike) -> NDArray[np.float64]:
    """Degree of linear polarization ``sqrt(S1² + S2²)/S0`` of Stokes vectors ``(..., 4)``
    (eq. 13); dimensionless, 0 where ``S0 ≤ 0``. Returns shape ``(...)``."""
    a = _stokes(s)
    return _ratio(np.hypot(a[..., 1], a[..., 2]), a[..., 0])


@public
def stokes_dop(s: ArrayLike) -> NDArray[np.float64]:
    """Degree of polarization ``sqrt(S1² + S2² + S3²)/S0`` of Stokes vectors ``(..., 4)``;
    dimensionless, 0 where ``S0 ≤ 0``. Returns shape ``(...)``."""
    a = _stokes(s)
    num = np.sqrt(a[..., 1] ** 2 + a[..., 2] ** 2 + a[..., 3] ** 2)
    return _ratio(num, a[..., 0])


@public
def stokes_aolp(s: ArrayLike, degrees: bool = True) -> NDArray[np.float64]:
    """Angle of linear polarization ``½·atan2(S2, S1)`` of Stokes vectors ``(..., 4)``, from the
    s axis toward the p axis: degrees in (−90, 90] (radians in (−π/2, π/2] with
    ``degrees=False``); 0 for light with no linear polarization. Returns shape ``(...)``."""
    a = _stokes(s)
    out = 0.5 * np.arctan2(a[..., 2], a[..., 1])
    if degrees:
        out = np.degrees(out)
    return out[()] if out.ndim == 0 else out
