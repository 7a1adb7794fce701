"""Bridges to the conventions of the tools users already have (docs/bridges.md).

Every function here calls the Rust core (``polbrdf::geometry::bridges``): the same numbers as
the Rust API. Angles are in **degrees** by default (``degrees=False``: radians), like the rest of
``polbrdf``; the arguments broadcast like NumPy ufuncs.

polbrdf's conventions (docs/model.md §1–2): directions point away from the surface; Stokes
vectors are in each beam's psps frame ``(s, p, k)``, ``s = unit(z × k)``, ``p = k × s``; the
AoLP is in (−90°, 90°], measured from the reflected beam's s axis toward its p axis.

- **Polarization cameras and polanalyser**: :func:`camera_roll`, :func:`stokes_to_camera`,
  :func:`stokes_from_camera`, :func:`stokes_to_polanalyser`, :func:`aolp_to_polanalyser`. A
  level camera (no roll) looking back along the reflected beam has image right = ``s_out`` and
  image up = ``p_out``: polbrdf's AoLP is then the camera's AoLP counterclockwise from image
  right as the image is displayed. polanalyser reports ``½·atan2(S2, S1) mod π`` in radians, in
  [0, π): for the same Stokes vector −73.15° here is 106.85° there (the range alone).
- **NIST SCATMECH** (pySCATMECH): :func:`to_scatmech`, :func:`from_scatmech` —
  ``(θi, θs, φs) = (θi, θr, φr − φi − 180°)``, specular at ``φs = 0`` there, ``φr = φi + 180°``
  here; the Mueller matrices in ``coords="psps"`` are the same.
- **Mitsuba 3**: :func:`mueller_to_mitsuba`, :func:`mueller_from_mitsuba`,
  :func:`stokes_to_mitsuba`, :func:`mitsuba_stokes_basis` — Mitsuba's implicit Stokes bases
  (``mi.mueller.stokes_basis``) and its sign of S3 (minus psps's).

Example
-------
>>> import numpy as np, polbrdf
>>> from polbrdf import bridges
>>> s = np.array([1.0, -0.832, -0.5548, 0.0])      # a Stokes vector, psps frame
>>> round(float(polbrdf.stokes_aolp(s)), 2)         # polbrdf's AoLP, degrees
-73.15
>>> round(float(np.degrees(bridges.aolp_to_polanalyser(polbrdf.stokes_aolp(s)))), 2)
106.85
>>> [float(a) for a in bridges.to_scatmech(30.0, 0.0, 30.0, 180.0)]   # specular: φs = 0
[30.0, 30.0, 0.0]
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _polbrdf

__all__ = [
    "aolp_to_polanalyser",
    "camera_roll",
    "from_scatmech",
    "mitsuba_stokes_basis",
    "mueller_from_mitsuba",
    "mueller_to_mitsuba",
    "stokes_from_camera",
    "stokes_to_camera",
    "stokes_to_mitsuba",
    "stokes_to_polanalyser",
    "to_scatmech",
]

_F64 = NDArray[np.float64]


def _real(name: str, a: ArrayLike) -> _F64:
    arr = np.asarray(a)
    if not (np.issubdtype(arr.dtype, np.floating) or np.issubdtype(arr.dtype, np.integer)):
        raise TypeError(f"`{name}` must be real numbers, got dtype {arr.dtype}")
    return arr.astype(np.float64)


def _call(
    name: str,
    values: tuple[str, ArrayLike, int] | None,
    angles: dict[str, ArrayLike],
    degrees: bool,
    y_down: bool = False,
) -> tuple[_F64, tuple[int, ...]]:
    """Broadcast the angle arguments with the leading axes of ``values`` (whose last axis has
    the stated width), run the core's bridge ``name`` and return ``(rows, shape)``."""
    arrays = {k: _real(k, v) for k, v in angles.items()}
    shapes = [a.shape for a in arrays.values()]
    v = None
    if values is not None:
        vname, raw, width = values
        v = _real(vname, raw)
        if width == 16:
            if v.shape[-2:] != (4, 4):
                raise ValueError(f"`{vname}` must have shape (..., 4, 4), got {v.shape}")
            v = v.reshape(*v.shape[:-2], 16)
        elif v.ndim == 0 or v.shape[-1] != width:
            raise ValueError(f"`{vname}` must have shape (..., {width}), got {v.shape}")
        shapes.append(v.shape[:-1])
    shape = np.broadcast_shapes(*shapes)
    n = int(np.prod(shape))
    cols = [np.broadcast_to(a, shape).reshape(n) for a in arrays.values()]
    a2 = np.ascontiguousarray(np.stack(cols, axis=-1) if cols else np.zeros((n, 0)))
    if v is None:
        v2 = np.zeros((n, 0))
    else:
        v2 = np.ascontiguousarray(np.broadcast_to(v, (*shape, v.shape[-1])).reshape(n, -1))
    return _polbrdf.bridge_flat(name, v2, a2, degrees, y_down), shape


def _column(rows: _F64, shape: tuple[int, ...], j: int) -> _F64:
    out = rows[:, j].reshape(shape)
    return out[()] if out.ndim == 0 else out  # a scalar for scalar arguments, as polbrdf's


# --- Polarization cameras ----------------------------------------------------------------------


def camera_roll(theta_r: ArrayLike, phi_r: ArrayLike, up: ArrayLike, degrees: bool = True) -> _F64:
    """The roll of a camera looking back along the reflected beam ``(theta_r, phi_r)`` whose
    image-up vector is ``up`` (world coordinates, shape ``(..., 3)``; e.g. the ``up`` of a
    look-at): the angle from ``s_out`` to the camera's image right ``unit(up × w_r)``, from s
    toward p. 0 for a level camera (``up = (0, 0, 1)``). Degrees (radians with
    ``degrees=False``)."""
    rows, shape = _call("camera_roll", ("up", up, 3),
                        {"theta_r": theta_r, "phi_r": phi_r}, degrees)
    return _column(rows, shape, 0)


def stokes_to_camera(stokes: ArrayLike, roll: ArrayLike = 0.0, degrees: bool = True) -> _F64:
    """Stokes vectors ``(..., 4)`` of the reflected beam (psps) in the frame of a camera with
    ``roll`` (:func:`camera_roll`): reference axis image right, second axis image up. The AoLP
    becomes ``aolp − roll``; S0 and S3 are unchanged."""
    rows, shape = _call("stokes_to_camera", ("stokes", stokes, 4), {"roll": roll}, degrees)
    return rows.reshape(*shape, 4)


def stokes_from_camera(stokes: ArrayLike, roll: ArrayLike = 0.0, degrees: bool = True) -> _F64:
    """The inverse of :func:`stokes_to_camera`: camera-frame Stokes vectors back to psps."""
    rows, shape = _call("stokes_from_camera", ("stokes", stokes, 4), {"roll": roll}, degrees)
    return rows.reshape(*shape, 4)


def stokes_to_polanalyser(
    stokes: ArrayLike, roll: ArrayLike = 0.0, y_down: bool = False, degrees: bool = True
) -> _F64:
    """Stokes vectors ``(..., 4)`` of the reflected beam as polanalyser's ``calcStokes``
    computes them from polarizer pixels whose angles are measured from image right: toward
    image up (``y_down=False``, counterclockwise as displayed) or toward image down
    (``y_down=True``, the pixel-row direction; S2 and S3 change sign)."""
    rows, shape = _call("stokes_to_polanalyser", ("stokes", stokes, 4), {"roll": roll}, degrees,
                        y_down)
    return rows.reshape(*shape, 4)


def aolp_to_polanalyser(
    aolp: ArrayLike, roll: ArrayLike = 0.0, y_down: bool = False, degrees: bool = True
) -> _F64:
    """polbrdf's AoLP (degrees, or radians with ``degrees=False``; also ``roll``) as
    polanalyser's ``cvtStokesToAoLP`` reports it: **radians in [0, π)**, in the camera frame
    (:func:`stokes_to_polanalyser`)."""
    rows, shape = _call("aolp_to_polanalyser", None, {"aolp": aolp, "roll": roll}, degrees,
                        y_down)
    return _column(rows, shape, 0)


# --- NIST SCATMECH ---------------------------------------------------------------------------


def to_scatmech(
    theta_i: ArrayLike, phi_i: ArrayLike, theta_r: ArrayLike, phi_r: ArrayLike,
    degrees: bool = True,
) -> tuple[_F64, _F64, _F64]:
    """polbrdf's angles as SCATMECH's ``(thetai, thetas, phis)`` =
    ``(θi, θr, φr − φi − 180°)``, ``phis`` in (−180°, 180°] (same unit as given: pass
    ``degrees=False`` and radians for pySCATMECH, which takes radians)."""
    rows, shape = _call("to_scatmech", None, {"theta_i": theta_i, "phi_i": phi_i,
                                              "theta_r": theta_r, "phi_r": phi_r}, degrees)
    return _column(rows, shape, 0), _column(rows, shape, 1), _column(rows, shape, 2)


def from_scatmech(
    theta_i: ArrayLike, theta_s: ArrayLike, phi_s: ArrayLike, degrees: bool = True
) -> tuple[_F64, _F64, _F64, _F64]:
    """SCATMECH's ``(thetai, thetas, phis)`` as polbrdf's ``(θi, φi, θr, φr)`` with SCATMECH's
    source azimuth: ``(θi, 180°, θs, φs)``."""
    rows, shape = _call("from_scatmech", None,
                        {"theta_i": theta_i, "theta_s": theta_s, "phi_s": phi_s}, degrees)
    return tuple(_column(rows, shape, j) for j in range(4))  # type: ignore[return-value]


# --- Mitsuba 3 -------------------------------------------------------------------------------


def _geometry(theta_i: ArrayLike, phi_i: ArrayLike, theta_r: ArrayLike,
              phi_r: ArrayLike) -> dict[str, ArrayLike]:
    return {"theta_i": theta_i, "phi_i": phi_i, "theta_r": theta_r, "phi_r": phi_r}


def mueller_to_mitsuba(
    f: ArrayLike, theta_i: ArrayLike, phi_i: ArrayLike, theta_r: ArrayLike, phi_r: ArrayLike,
    degrees: bool = True,
) -> _F64:
    """pBRDFs ``(..., 4, 4)`` (psps) as Mitsuba 3's polarized ``bsdf.eval(...)/cosθi`` returns
    them in the local frame, radiance mode (polbrdf's ``w_i`` is Mitsuba's ``wo``, ``w_r`` is
    ``si.wi``): incident basis ``stokes_basis(−w_i)``, outgoing ``stokes_basis(w_r)``,
    Mitsuba's S3 (minus psps's)."""
    rows, shape = _call("mueller_to_mitsuba", ("f", f, 16),
                        _geometry(theta_i, phi_i, theta_r, phi_r), degrees)
    return rows.reshape(*shape, 4, 4)


def mueller_from_mitsuba(
    m: ArrayLike, theta_i: ArrayLike, phi_i: ArrayLike, theta_r: ArrayLike, phi_r: ArrayLike,
    degrees: bool = True,
) -> _F64:
    """The inverse of :func:`mueller_to_mitsuba`: Mitsuba's Mueller matrices back to psps."""
    rows, shape = _call("mueller_from_mitsuba", ("m", m, 16),
                        _geometry(theta_i, phi_i, theta_r, phi_r), degrees)
    return rows.reshape(*shape, 4, 4)


def stokes_to_mitsuba(
    stokes: ArrayLike, theta_i: ArrayLike, phi_i: ArrayLike, theta_r: ArrayLike,
    phi_r: ArrayLike, degrees: bool = True,
) -> _F64:
    """Stokes vectors ``(..., 4)`` of the reflected beam (psps) in Mitsuba's basis of that beam
    (``stokes_basis(w_r)``, Mitsuba's sign of S3)."""
    rows, shape = _call("stokes_to_mitsuba", ("stokes", stokes, 4),
                        _geometry(theta_i, phi_i, theta_r, phi_r), degrees)
    return rows.reshape(*shape, 4)


def mitsuba_stokes_basis(k: ArrayLike) -> _F64:
    """Mitsuba's implicit Stokes reference axis ``mi.mueller.stokes_basis(k)`` of beams
    travelling along the unit vectors ``k`` ``(..., 3)``."""
    rows, shape = _call("mitsuba_stokes_basis", ("k", k, 3), {}, True)
    return rows.reshape(*shape, 3)
