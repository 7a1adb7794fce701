"""The pBRDF at geometries: :func:`mueller` (the 4×4 Mueller-matrix BRDF, at angles) and
:func:`mueller_directions` (at direction vectors), their ``out=``, ``precision`` and
``layout`` options; :func:`brdf`, :func:`dolp` and :func:`evaluate` (BRDF, DoLP and AoLP in
one pass); :func:`index`, a material's complex refractive index."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _polbrdf
from ._common import (
    _F64,
    _args,
    _check_material,
    _flatten,
    _located,
    _real,
    _scalar_or_array,
    _wl,
    public,
)
from ._polbrdf import Material
from ._results import Evaluation


@public
def mueller(
    material: Material,
    theta_i: ArrayLike,
    phi_i: ArrayLike,
    theta_r: ArrayLike,
    phi_r: ArrayLike,
    *,
    degrees: bool = True,
    wavelength_um: ArrayLike | None = None,
    out: NDArray[np.floating] | None = None,
    precision: str | type | np.dtype | None = None,
    layout: str = "interleaved",
) -> NDArray[np.floating]:
    """The pBRDF F: the 4×4 Mueller-matrix BRDF (eq. 9 corrected), in sr⁻¹, psps basis.

    Parameters
    ----------
    material : Material
    theta_i, phi_i : array_like
        Zenith and azimuth of the direction toward the source, degrees (radians when
        ``degrees=False``).
    theta_r, phi_r : array_like
        Zenith and azimuth of the direction toward the detector, same unit.
    degrees : bool
        Whether the angles are in degrees (default) or radians.
    wavelength_um : array_like, optional
        Vacuum wavelength in µm, broadcast with the angles: a material with a spectral index
        (``Material(index=...)``) is evaluated with its index at each wavelength — one call
        covers wavelengths × geometries. Required for such a material; a constant index does
        not depend on it.
    out : ndarray, optional
        An array to write the result into (NumPy's ``out=`` convention), returned: shape
        ``broadcast_shape + (4, 4)`` (``(4, 4) + broadcast_shape`` for ``layout="planar"``),
        dtype float64 or float32 (the precision), C-contiguous and writeable. Reusing it saves
        the allocation and the page faults of a new array. When the call raises (an invalid
        element is found as its block is read, after other parts were written), every entry
        of ``out`` is NaN: it never holds a partial result.
    precision : {"float64", "float32"} or dtype, optional
        The result's dtype (default float64, or ``out``'s dtype). float32 computes the model
        in single precision, every entry within 1e-5·F00 + 1e-6·P of float64, P the F00 at the
        specular direction of the same θi (the float32 contract, docs/model.md §12; the few
        elements where single precision would not reach that are computed in float64 and
        rounded) — about twice as fast, half the memory. Fits and the reference use float64.
    layout : {"interleaved", "planar"}
        ``"interleaved"`` (default): the 4×4 matrix last, ``F[..., i, j]``. ``"planar"``: the
        matrix first, ``F[i, j, ...]``, each entry a contiguous array over the geometries —
        Mitsuba's and Dr.Jit's layout of a Mueller matrix, and a table stored entry by entry
        (docs/model.md §12, "Layouts"). The same values bit for bit, with no transpose; not
        faster to compute.

    Returns
    -------
    ndarray of float64 (or float32), shape ``broadcast_shape + (4, 4)``
        ``F[..., i, j]`` in sr⁻¹; ``F[..., 0, 0]`` is the scalar BRDF. Zero where a direction
        is at or below the horizon. ``out`` when given. With ``layout="planar"``, shape
        ``(4, 4) + broadcast_shape`` and ``F[i, j, ...]``.

    Raises
    ------
    ValueError
        For NaN/inf angles or zenith angles outside [0°, 180°], naming the argument, value and
        flat index; when the arguments do not broadcast; for an unknown precision, an ``out``
        of the wrong shape, dtype or layout or not writeable; in float32, for an entry beyond
        float32's range (|F| > 3.4e38 sr⁻¹); for an unknown ``layout``.
    TypeError
        For a non-Material ``material``, non-real angles or an ``out`` that is not an ndarray.
    """
    dtype = _precision(precision, out)
    planar = _planar(layout)
    angles = (theta_i, phi_i, theta_r, phi_r)
    shape, flat = _flatten(material, _args(angles, wavelength_um), singles=True)
    rows = None if out is None else _out_rows(out, shape, dtype, planar)
    try:
        res = _polbrdf.mueller_flat(
            material, *flat[:4], degrees, _wl(flat), rows, dtype.name, planar
        )
    except ValueError as e:
        raise _located(e, shape) from None
    return out if out is not None else res.reshape(_matrix_shape(shape, planar))


@public
def mueller_directions(
    material: Material,
    w_i: ArrayLike,
    w_r: ArrayLike,
    *,
    wavelength_um: ArrayLike | None = None,
    out: NDArray[np.floating] | None = None,
    precision: str | type | np.dtype | None = None,
    layout: str = "interleaved",
) -> NDArray[np.floating]:
    """The pBRDF F at direction vectors: :func:`mueller` for callers that hold directions, as a
    renderer or ray tracer does (docs/model.md §9.11).

    Parameters
    ----------
    material : Material
    w_i : array_like, shape ``(..., 3)``
        Direction toward the source, ``(x, y, z)`` in the surface frame (z along the normal,
        x along azimuth 0): any length from 1e-15 to 1e15 (each vector is normalized).
    w_r : array_like, shape ``(..., 3)``
        Direction toward the detector, same frame; broadcast with ``w_i`` over the leading
        dimensions (a single vector stands for all without being copied).
    wavelength_um, out, precision, layout
        As for :func:`mueller` (``wavelength_um`` broadcast with the leading dimensions).

    Returns
    -------
    ndarray of float64 (or float32), shape ``broadcast_shape + (4, 4)`` (``(4, 4) +
    broadcast_shape`` for ``layout="planar"``)
        The result of :func:`mueller` at ``θ = atan2(√(x² + y²), z)``, ``φ = atan2(y, x)``, and
        ``φ = 0`` for a vector along the normal; computed from the vectors without a sine or
        cosine. Zero where ``z ≤ 0`` (at or below the horizon).

    Raises
    ------
    ValueError
        For a vector that is not finite or whose length is outside 1e-15..1e15 (naming
        ``w_i`` or ``w_r``, the vector and its flat index), a last dimension other than 3,
        arguments that do not broadcast, and as :func:`mueller` for ``out`` and ``precision``.
    TypeError
        As :func:`mueller`.
    """
    _check_material(material)
    dtype = _precision(precision, out)
    planar = _planar(layout)
    wi, wr = _real("w_i", w_i), _real("w_r", w_r)
    for name, w in (("w_i", wi), ("w_r", wr)):
        if w.ndim == 0 or w.shape[-1] != 3:
            raise ValueError(
                f"`{name}` must have shape (..., 3): (x, y, z) in the surface frame, "
                f"got {w.shape}"
            )
    wl = None if wavelength_um is None else _real("wavelength_um", wavelength_um)
    shapes = [wi.shape[:-1], wr.shape[:-1]] + ([] if wl is None else [wl.shape])
    try:
        shape = np.broadcast_shapes(*shapes)
    except ValueError as e:
        given = f"w_i: {wi.shape}, w_r: {wr.shape}"
        if wl is not None:
            given += f", wavelength_um: {wl.shape}"
        raise ValueError(f"arrays do not broadcast together ({given})") from e

    def vectors(w: np.ndarray) -> _F64:
        if w.size == 3:
            return np.ascontiguousarray(w, dtype=np.float64).reshape(1, 3)
        full = np.broadcast_to(w, shape + (3,))
        return np.ascontiguousarray(full, dtype=np.float64).reshape(-1, 3)

    flat_wl = None
    if wl is not None:
        flat_wl = np.ascontiguousarray(np.broadcast_to(wl, shape), dtype=np.float64).reshape(-1)
    rows = None if out is None else _out_rows(out, shape, dtype, planar)
    try:
        res = _polbrdf.mueller_directions_flat(
            material, vectors(wi), vectors(wr), flat_wl, rows, dtype.name, planar
        )
    except ValueError as e:
        raise _located(e, shape) from None
    return out if out is not None else res.reshape(_matrix_shape(shape, planar))


def _precision(precision: str | type | np.dtype | None, out: np.ndarray | None) -> np.dtype:
    """The result dtype of ``precision`` (float64 or float32), ``out``'s when not given."""
    if out is not None and not isinstance(out, np.ndarray):
        raise TypeError(f"`out` must be a numpy.ndarray, not {type(out).__name__}")
    if precision is None:
        dtype = np.dtype(np.float64) if out is None else out.dtype
    else:
        try:
            dtype = np.dtype(precision)
        except TypeError:
            dtype = None
        if dtype not in (np.float64, np.float32):
            names = " or ".join(f'"{p}"' for p in _polbrdf.vocabulary()["precision"])
            raise ValueError(f"unknown precision {precision!r}: expected {names}")
    if dtype not in (np.float64, np.float32):
        raise ValueError(f"`out` must have dtype float64 or float32, got {dtype}")
    if out is not None and out.dtype != dtype:
        raise ValueError(f"`out` has dtype {out.dtype}, the precision is {dtype}")
    return dtype


def _planar(layout: str) -> bool:
    """Whether ``layout`` is ``"planar"`` (else ``"interleaved"``)."""
    interleaved, planar = _polbrdf.vocabulary()["layout"]
    if layout not in (interleaved, planar):
        raise ValueError(f'unknown layout {layout!r}: expected "{interleaved}" or "{planar}"')
    return layout == planar


def _matrix_shape(shape: tuple[int, ...], planar: bool) -> tuple[int, ...]:
    """The shape of a pBRDF array over ``shape``: the 4×4 matrix last, or first when planar."""
    return (4, 4) + shape if planar else shape + (4, 4)


def _out_rows(
    out: np.ndarray, shape: tuple[int, ...], dtype: np.dtype, planar: bool = False
) -> np.ndarray:
    """The ``(n, 16)`` (planar: ``(16, n)``) view of a caller's output array for a result over
    ``shape``, after checking it (shape, dtype, C-contiguous, writeable): numpy's ``out=``
    convention, without copies."""
    shape = _matrix_shape(shape, planar)
    if out.shape != shape:
        raise ValueError(f"`out` has shape {out.shape}, the result has shape {shape}")
    if not out.flags.c_contiguous:
        raise ValueError("`out` must be C-contiguous")
    if not out.flags.writeable:
        raise ValueError("`out` must be writeable")
    return out.reshape(16, -1) if planar else out.reshape(-1, 16)


@public
def index(material: Material, wavelength_um: ArrayLike) -> NDArray[np.complex128]:
    """The complex refractive index ``n + ik`` of ``material`` at each vacuum wavelength (µm):
    its spectral index there (linear interpolation of tabulated n and k, or its dispersion
    formula), or its constant index. Same shape as ``wavelength_um``.

    Raises
    ------
    ValueError
        For a wavelength outside a spectral index's data (naming the material and its range) or
        not finite and > 0.
    """
    if not isinstance(material, Material):
        raise TypeError(f"material must be a polbrdf.Material, not {type(material).__name__}")
    wl = np.asarray(wavelength_um)
    if wl.dtype.kind not in "biuf":
        raise TypeError(f"`wavelength_um` must hold real numbers, got dtype {wl.dtype}")
    flat = np.ascontiguousarray(wl, dtype=np.float64).reshape(-1)
    n, k = _polbrdf.index_flat(material, flat)
    out = (n + 1j * k).reshape(wl.shape)
    return out[()] if wl.shape == () else out


def _brdf_dolp(
    material: Material,
    angles: tuple[ArrayLike, ArrayLike, ArrayLike, ArrayLike],
    degrees: bool,
    wavelength_um: ArrayLike | None,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    shape, flat = _flatten(material, _args(angles, wavelength_um), singles=True)
    try:
        f, d = _polbrdf.brdf_dolp_flat(material, *flat[:4], degrees, _wl(flat))
    except ValueError as e:
        raise _located(e, shape) from None
    return _scalar_or_array(f, shape), _scalar_or_array(d, shape)


@public
def brdf(
    material: Material,
    theta_i: ArrayLike,
    phi_i: ArrayLike,
    theta_r: ArrayLike,
    phi_r: ArrayLike,
    *,
    degrees: bool = True,
    wavelength_um: ArrayLike | None = None,
) -> NDArray[np.float64]:
    """The scalar BRDF ``f = f_s + f_v = F00`` (eqs. 1/6), in sr⁻¹.

    Arguments, broadcasting and errors as :func:`mueller`; the result has the broadcast shape
    (a NumPy scalar when every angle is a scalar). Zero where a direction is at or below the
    horizon.
    """
    return _brdf_dolp(material, (theta_i, phi_i, theta_r, phi_r), degrees, wavelength_um)[0]


@public
def dolp(
    material: Material,
    theta_i: ArrayLike,
    phi_i: ArrayLike,
    theta_r: ArrayLike,
    phi_r: ArrayLike,
    *,
    degrees: bool = True,
    wavelength_um: ArrayLike | None = None,
) -> NDArray[np.float64]:
    """Degree of linear polarization of the reflected light for unpolarized illumination,
    ``sqrt(F10² + F20²)/F00`` (eq. 13), dimensionless in [0, 1]; 0 where ``F00 = 0``.

    Arguments, broadcasting and errors as :func:`mueller`; the result has the broadcast shape.
    """
    return _brdf_dolp(material, (theta_i, phi_i, theta_r, phi_r), degrees, wavelength_um)[1]


@public
def evaluate(
    material: Material,
    theta_i: ArrayLike,
    phi_i: ArrayLike,
    theta_r: ArrayLike,
    phi_r: ArrayLike,
    *,
    degrees: bool = True,
    with_mueller: bool = False,
    wavelength_um: ArrayLike | None = None,
) -> Evaluation:
    """BRDF (sr⁻¹), DoLP and AoLP for unpolarized illumination — and the pBRDF with
    ``with_mueller=True`` — in one pass over the geometries.

    AoLP is that of ``F @ (1, 0, 0, 0)``: degrees in (−90, 90] (radians when
    ``degrees=False``, the unit of the inputs), measured from the reflected beam's s axis
    toward its p axis; 0 without linear polarization. Arguments, broadcasting and errors as
    :func:`mueller`. Returns an :class:`Evaluation` named tuple.
    """
    angles = (theta_i, phi_i, theta_r, phi_r)
    shape, flat = _flatten(material, _args(angles, wavelength_um), singles=True)
    try:
        f, d, a, m = _polbrdf.evaluate_flat(material, *flat[:4], degrees, with_mueller, _wl(flat))
    except ValueError as e:
        raise _located(e, shape) from None
    return Evaluation(
        _scalar_or_array(f, shape),
        _scalar_or_array(d, shape),
        _scalar_or_array(a, shape),
        None if m is None else m.reshape(shape + (4, 4)),
    )
