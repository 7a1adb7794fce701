"""polbrdf — the simplified Maxwell–Beard polarimetric BRDF, for NumPy.

The model of Zhuansun et al., *Infrared and Laser Engineering* 44(3), 2015, as pinned by the
project's ``docs/model.md``; the computation is the Rust core ``polbrdf`` (parallel, the GIL
released while it runs).

Units
-----
- Angles are in **degrees** by default (``degrees=False``: radians). Directions point away from
  the surface; ``theta`` is the zenith angle, ``phi`` the azimuth; specular reflection is
  ``theta_r = theta_i``, ``phi_r = phi_i + 180``. Zenith angles in [90°, 180°] are valid and
  give a zero pBRDF; NaN, ±inf and zenith angles outside [0°, 180°] raise ``ValueError``.
- BRDF and pBRDF (Mueller-matrix BRDF) values are in **sr⁻¹**; the 4×4 matrices are in the psps
  (SCATMECH) Stokes basis, row-major: ``S_out = F @ S_in`` (eq. 12).
- DoLP and DoP are dimensionless in [0, 1]; AoLP is in (−90°, 90°] (or radians), measured from
  the reflected beam's s axis toward its p axis.
- Thermal emission: wavelengths in **µm**, temperatures in **K**, spectral radiance in
  **W·m⁻²·sr⁻¹·µm⁻¹** (:func:`planck`, :func:`radiance` at one wavelength), band radiance in
  **W·m⁻²·sr⁻¹** (:func:`radiance` over a band); emissivities are dimensionless. Daylight
  (:func:`radiance` with ``sun=`` or ``sky="cie-clear"``): spectral irradiances in
  **W·m⁻²·µm⁻¹**.

Example
-------
>>> import numpy as np, polbrdf
>>> paint = polbrdf.Material.preset("paint")
>>> theta = np.linspace(0, 80, 5)
>>> polbrdf.dolp(paint, theta, 0, theta, 180).round(3)    # specular DoLP vs angle
array([0.   , 0.103, 0.481, 0.915, 0.446])
>>> polbrdf.mueller(paint, theta, 0, theta, 180).shape
(5, 4, 4)

Evaluation functions broadcast their four angle arguments like NumPy ufuncs (scalars, lists,
arrays of any real dtype, any strides); the result has the broadcast shape (``+ (4, 4)`` for
:func:`mueller`). Thread count: rayon's default (all cores); set ``RAYON_NUM_THREADS`` before
the first call to change it.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import NamedTuple, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

try:
    from . import _polbrdf
    from ._polbrdf import DEFAULT_DOP_MAX, FitResult, Material
except ImportError as _e:  # pragma: no cover - only when the extension was never built
    raise ImportError(
        "polbrdf's compiled extension (polbrdf._polbrdf) is missing. Install the package with "
        "`pip install ./python` from the repository root; if you did, you may be importing the "
        "source folder python/polbrdf instead of the installed package (run from elsewhere)."
    ) from _e

from .detection import DetectFrame, DetectStudy, detect, detect_frame
from .jobs import (
    CheckReport,
    Measurements,
    PbsdfTable,
    _band_emission,
    check,
    export_pbsdf,
    fit_measurements,
    fit_pbsdf,
    read_measurements,
    read_pbsdf,
)
from .scene import Atmosphere, Band, PathToSensor, Scene, SceneObject, Sky, Sun, Surface
from .sun import DaytimeStudy, daytime, sun_position
from .tasks import (
    AlbedoTable,
    ContrastStudy,
    HemisphereMap,
    Illumination,
    albedo,
    contrast,
    hemisphere,
)

__all__ = [
    "DEFAULT_DOP_MAX",
    "AlbedoTable",
    "Atmosphere",
    "Band",
    "CheckReport",
    "ContrastStudy",
    "DaytimeStudy",
    "DetectFrame",
    "DetectStudy",
    "Emissivity",
    "Evaluation",
    "FitResult",
    "HemisphereMap",
    "Illumination",
    "Material",
    "Measurements",
    "PathToSensor",
    "PbsdfTable",
    "Radiance",
    "Scene",
    "SceneObject",
    "Sky",
    "Sun",
    "Surface",
    "__version__",
    "albedo",
    "brdf",
    "brightness_temperature",
    "check",
    "contrast",
    "daytime",
    "detect",
    "detect_frame",
    "dolp",
    "emissivity",
    "evaluate",
    "export_pbsdf",
    "fit",
    "fit_measurements",
    "fit_pbsdf",
    "hemisphere",
    "index",
    "mueller",
    "mueller_directions",
    "planck",
    "radiance",
    "read_measurements",
    "read_pbsdf",
    "stokes_aolp",
    "stokes_dolp",
    "stokes_dop",
    "sun_position",
]

try:
    from importlib.metadata import PackageNotFoundError, version

    __version__: str = version("polbrdf")
except PackageNotFoundError:  # pragma: no cover
    __version__ = "unknown"

_NAMES = ("theta_i", "phi_i", "theta_r", "phi_r", "wavelength_um")
_F64 = NDArray[np.float64]
_Flat = tuple[_F64, _F64, _F64, _F64]


class Evaluation(NamedTuple):
    """Result of :func:`evaluate`, every array of the broadcast shape of the angles.

    - ``brdf``: scalar BRDF ``f = F00`` in sr⁻¹ (eqs. 1/6).
    - ``dolp``: degree of linear polarization of the reflected light for unpolarized
      illumination (eq. 13), in [0, 1].
    - ``aolp``: angle of linear polarization of that light, in degrees in (−90, 90] (radians
      with ``degrees=False``), from the reflected s axis toward p; 0 without linear
      polarization.
    - ``mueller``: the pBRDF F (shape ``+ (4, 4)``, sr⁻¹, psps basis) with
      ``with_mueller=True``, else ``None``.
    """

    brdf: NDArray[np.float64]
    dolp: NDArray[np.float64]
    aolp: NDArray[np.float64]
    mueller: NDArray[np.float64] | None


def _check_material(material: Material) -> None:
    if not isinstance(material, Material):
        raise TypeError(
            f"material must be a polbrdf.Material, not {type(material).__name__} "
            "(use polbrdf.Material.preset(name) or polbrdf.Material.from_toml(path))"
        )


#: The most dimensions of a broadcast argument (NumPy's limit for broadcasting).
MAX_DIMS = 32

#: The most extra starts of :func:`fit` (the CLI's ``--starts`` limit).
MAX_STARTS = 10_000


def _real(name: str, a: ArrayLike, masked_as_nan: bool = False) -> np.ndarray:
    """``a`` as an array of real numbers: complex or other dtypes raise ``TypeError``, more than
    :data:`MAX_DIMS` dimensions ``ValueError``. A masked array's masked entries are NaN ("not
    measured") with ``masked_as_nan`` (fit data and sigma), and are refused otherwise (angles
    and wavelengths have no "not given" value)."""
    if isinstance(a, np.ma.MaskedArray):
        mask = np.ma.getmaskarray(a)
        if mask.any() and not masked_as_nan:
            raise ValueError(
                f"`{name}` is a masked array with {int(mask.sum())} masked entr"
                f"{'y' if mask.sum() == 1 else 'ies'}: an angle or wavelength must be given "
                "everywhere (drop the masked entries, or fill them)"
            )
        if a.dtype.kind not in "biuf":
            raise TypeError(f"`{name}` must hold real numbers, got dtype {a.dtype}")
        arr = np.ma.filled(a.astype(np.float64), np.nan)
    else:
        arr = np.asarray(a)
    if arr.dtype.kind not in "biuf":
        raise TypeError(f"`{name}` must hold real numbers, got dtype {arr.dtype}")
    if arr.ndim > MAX_DIMS:
        raise ValueError(f"`{name}` has {arr.ndim} dimensions: at most {MAX_DIMS}")
    return arr


def _broadcast(
    names: Sequence[str], values: tuple[ArrayLike, ...], singles: int = 0
) -> tuple[tuple[int, ...], tuple[_F64, ...]]:
    """Broadcast the arguments ``values`` (named ``names``); return the shape and the flat
    C-contiguous float64 arrays (views when the input already is one, copies otherwise). The
    first ``singles`` arguments are passed as one value when they hold one (a scalar), for the
    Rust side to broadcast without a materialized array."""
    arrays = [_real(name, a) for name, a in zip(names, values)]
    try:
        b = np.broadcast_arrays(*arrays)
    except ValueError as e:
        shapes = ", ".join(f"{n}: {a.shape}" for n, a in zip(names, arrays))
        raise ValueError(f"arrays do not broadcast together ({shapes})") from e
    shape = b[0].shape
    flat = tuple(
        np.ascontiguousarray(a if i < singles and a.size == 1 else x, dtype=np.float64).reshape(-1)
        for i, (a, x) in enumerate(zip(arrays, b))
    )
    return shape, flat


def _flatten(
    material: Material,
    angles: tuple[ArrayLike, ...],
    singles: bool = False,
) -> tuple[tuple[int, ...], tuple[_F64, ...]]:
    """Broadcast the four angle arguments (and the wavelength, when given: a fifth); return the
    shape and the flat C-contiguous float64 arrays (views when the input already is one,
    copies otherwise). With ``singles``, a scalar angle stays one value (the engine calls
    broadcast it)."""
    _check_material(material)
    return _broadcast(_NAMES, angles, 4 if singles else 0)


def _args(
    angles: tuple[ArrayLike, ArrayLike, ArrayLike, ArrayLike], wavelength_um: ArrayLike | None
) -> tuple[ArrayLike, ...]:
    return angles if wavelength_um is None else (*angles, wavelength_um)


def _wl(flat: tuple[_F64, ...]) -> _F64 | None:
    return flat[4] if len(flat) == 5 else None


def _located(e: ValueError, shape: tuple[int, ...]) -> ValueError:
    """Add the position in the broadcast shape to a bad-angle error of a multi-dimensional call."""
    index = getattr(e, "index", None)
    if index is not None and len(shape) >= 2:
        pos = tuple(int(i) for i in np.unravel_index(index, shape))
        e.add_note(f"flat index {index} is position {pos} of the broadcast shape {shape}")
    return e


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


def _scalar_or_array(a: NDArray[np.float64], shape: tuple[int, ...]) -> NDArray[np.float64]:
    out = a.reshape(shape)
    return out[()] if shape == () else out  # a NumPy scalar for all-scalar input, as ufuncs


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


# --- Stokes helpers (the core's definitions, docs/model.md §2) --------------------------------


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


def stokes_dolp(s: ArrayLike) -> NDArray[np.float64]:
    """Degree of linear polarization ``sqrt(S1² + S2²)/S0`` of Stokes vectors ``(..., 4)``
    (eq. 13); dimensionless, 0 where ``S0 ≤ 0``. Returns shape ``(...)``."""
    a = _stokes(s)
    return _ratio(np.hypot(a[..., 1], a[..., 2]), a[..., 0])


def stokes_dop(s: ArrayLike) -> NDArray[np.float64]:
    """Degree of polarization ``sqrt(S1² + S2² + S3²)/S0`` of Stokes vectors ``(..., 4)``;
    dimensionless, 0 where ``S0 ≤ 0``. Returns shape ``(...)``."""
    a = _stokes(s)
    num = np.sqrt(a[..., 1] ** 2 + a[..., 2] ** 2 + a[..., 3] ** 2)
    return _ratio(num, a[..., 0])


def stokes_aolp(s: ArrayLike, degrees: bool = True) -> NDArray[np.float64]:
    """Angle of linear polarization ``½·atan2(S2, S1)`` of Stokes vectors ``(..., 4)``, from the
    s axis toward the p axis: degrees in (−90, 90] (radians in (−π/2, π/2] with
    ``degrees=False``); 0 for light with no linear polarization. Returns shape ``(...)``."""
    a = _stokes(s)
    out = 0.5 * np.arctan2(a[..., 2], a[..., 1])
    if degrees:
        out = np.degrees(out)
    return out[()] if out.ndim == 0 else out


def fit(
    material: Material,
    theta_i: ArrayLike,
    phi_i: ArrayLike,
    theta_r: ArrayLike,
    phi_r: ArrayLike,
    data: Mapping[str, ArrayLike],
    free: str | Sequence[str],
    *,
    sigma: Mapping[str, ArrayLike] | None = None,
    degrees: bool = True,
    starts: int = 2,
    seed: int = 1,
    wavelength_um: ArrayLike | None = None,
) -> FitResult:
    """Fit material parameters to measurements (Levenberg–Marquardt), with uncertainties.

    ``material`` gives the start values and every parameter that stays fixed. ``data`` maps a
    measured quantity — ``"brdf"`` (sr⁻¹), ``"dolp"``, ``"brdf_s"`` / ``"brdf_p"`` (s- or
    p-polarized incidence without analyzer, ``F00 ± F01``), or a pBRDF entry ``"m00"`` …
    ``"m33"`` (sr⁻¹, psps basis) — to its values; the angles, ``wavelength_um`` and every data
    and ``sigma`` array broadcast together. NaN means "not measured here". ``sigma`` maps a quantity to its 1-σ uncertainties
    (> 0 where measured); a quantity without one weighs 1, and the uncertainties are then
    estimated from the scatter of the residuals (covariance × χ²/dof). ``free`` names the
    parameters to fit: any of ``n, k, a, b`` or ``sigma_deg``, ``rho_d, rho_v, tau_deg,
    omega_deg``. ``starts`` extra starts are scattered around the start values; the best χ² wins.
    ``wavelength_um`` (µm) places each value at a wavelength: a material with a spectral index
    is evaluated with its index there (n and k cannot then be free). To fit an effective index
    per wavelength, call ``fit`` once per wavelength with a constant-index material.

    The same engine as ``polbrdf fit`` (docs/model.md §7a). Raises ``ValueError`` when the data
    cannot determine a parameter, when there are no more values than free parameters, or for
    invalid input.
    """
    if isinstance(free, str):
        free = [f for f in free.split(",") if f.strip()]
    sigma = dict(sigma or {})
    unknown = set(sigma) - set(data)
    if unknown:
        raise ValueError(f"sigma given for {sorted(unknown)} but no such data")
    if isinstance(starts, bool) or not isinstance(starts, (int, np.integer)):
        raise TypeError(f"starts must be an integer, not {type(starts).__name__}")
    if not 0 <= starts <= MAX_STARTS:
        raise ValueError(f"starts = {starts}: must lie in [0, {MAX_STARTS}] (each is a full fit)")
    names = list(data)
    # Masked entries of data and sigma are "not measured" (NaN); complex values are refused.
    arrays = [_real(k, data[k], masked_as_nan=True).astype(np.float64) for k in names]
    sig_names = [k for k in names if k in sigma]
    sig_arrays = [
        _real(f"sigma[{k!r}]", sigma[k], masked_as_nan=True).astype(np.float64) for k in sig_names
    ]
    geometry = _args((theta_i, phi_i, theta_r, phi_r), wavelength_um)
    shape, flat = _flatten(material, geometry)
    try:
        b = np.broadcast_arrays(np.empty(shape), *arrays, *sig_arrays)
    except ValueError as e:
        raise ValueError("angle, data and sigma arrays do not broadcast together") from e
    full = b[0].shape
    if full != shape:
        flat = tuple(
            np.ascontiguousarray(np.broadcast_to(np.asarray(a), full), dtype=np.float64).reshape(-1)
            for a in geometry
        )
    vals = [np.ascontiguousarray(a, dtype=np.float64).reshape(-1) for a in b[1 : 1 + len(names)]]
    sigs_by_name = {
        k: np.ascontiguousarray(a, dtype=np.float64).reshape(-1)
        for k, a in zip(sig_names, b[1 + len(names) :])
    }
    sigs = [sigs_by_name.get(k) for k in names]
    return _polbrdf.fit_flat(
        material,
        *flat[:4],
        names,
        vals,
        sigs,
        list(free),
        degrees,
        int(starts),
        int(seed),
        _wl(flat),
    )


# --- Thermal emission (Kirchhoff's law, Planck's law, the observed radiance) -----------------


class Emissivity(NamedTuple):
    """Result of :func:`emissivity` (dimensionless; psps basis of the emitted beam).

    - ``eps``: the emissivity Stokes vector ``ε = e0 − ∫_H F(w_i, w_r)[:, 0] cosθi dω_i``
      (route A, the definition; ``e0 = (1, 0, 0, 0)``), shape ``broadcast_shape + (4,)``. A
      surface at temperature T emits the Stokes radiance ``B_λ(λ, T)·ε``. ``ε1 < 0`` means
      p-polarized emission; ``ε2 = ε3 = 0`` for this isotropic model (computed, not assumed).
    - ``eps_b``: the same by route B (reciprocity): ``e0`` minus the directional–hemispherical
      reflectance of light incident from the view direction, for each input state; shape
      ``broadcast_shape + (4,)``. ``eps_b[..., 0] = 1 − albedo(θr)``.
    - ``eps_s``, ``eps_p``: ``ε0 + ε1`` and ``ε0 − ε1``, the emissivities of the s and p
      components; shape ``broadcast_shape``.
    - ``dolp``: degree of linear polarization of the emitted light ``sqrt(ε1² + ε2²)/ε0``.
    - ``reciprocity_residual``: ``max_j |ε_j − ε_B,j|`` — rounding and quadrature error
      (< 1e-12) for the reciprocal ``standard`` form, the model's non-reciprocity for
      ``azimuth_term="eq3"``.
    - ``valid``: (bool) whether the emissivity of every polarization state lies in [0, 1] to
      1e-6 (``ε0 ∓ |(ε1, ε2, ε3)|``). The model is not energy-conserving: a parameter set that
      reflects more than it receives gives values outside — flagged here, never clipped.
    """

    eps: NDArray[np.float64]
    eps_b: NDArray[np.float64]
    eps_s: NDArray[np.float64]
    eps_p: NDArray[np.float64]
    dolp: NDArray[np.float64]
    reciprocity_residual: NDArray[np.float64]
    valid: NDArray[np.bool_]


class Radiance(NamedTuple):
    """Result of :func:`radiance`; radiances in W·m⁻²·sr⁻¹·µm⁻¹ at one wavelength, W·m⁻²·sr⁻¹
    integrated over a band (psps basis of the beam toward the sensor).

    - ``stokes``: the Stokes radiance at the sensor, ``τ·(emitted + reflected) + L_path·e0``,
      shape ``views_shape + (4,)``.
    - ``emitted``: the thermal emission ``B_λ(λ, T)·ε`` at the surface (zero without
      ``temperature_k``), shape ``views_shape + (4,)``.
    - ``reflected``: the sun and the sky reflected by the surface,
      ``E·cosθs·F(w_s, w_r)·s + ∫_H F(w, w_r)·L_sky(w) cosθ dω``, shape ``views_shape + (4,)``.
    - ``dolp``: degree of linear polarization of ``stokes``, shape ``views_shape``.
    - ``aolp``: angle of linear polarization of ``stokes``, in degrees in (−90, 90] (radians
      with ``degrees=False``), from the s axis toward p; shape ``views_shape``.
    """

    stokes: NDArray[np.float64]
    emitted: NDArray[np.float64]
    reflected: NDArray[np.float64]
    dolp: NDArray[np.float64]
    aolp: NDArray[np.float64]


def planck(wavelength_um: ArrayLike, temperature_k: ArrayLike) -> NDArray[np.float64]:
    """Planck's law: the spectral radiance of a blackbody, in W·m⁻²·sr⁻¹·µm⁻¹.

    ``B_λ(λ, T) = c1L / (λ⁵·(exp(c2/(λT)) − 1))`` with ``c1L = 2hc² = 1.191042972e8
    W·µm⁴·m⁻²·sr⁻¹`` and ``c2 = hc/k = 14387.76877 µm·K`` (CODATA 2018).

    Parameters
    ----------
    wavelength_um : array_like
        Vacuum wavelength in µm (finite, > 0).
    temperature_k : array_like
        Temperature in K (finite, > 0). Broadcast with ``wavelength_um``.

    Returns
    -------
    ndarray of float64, shape ``broadcast_shape``
        (a NumPy scalar for scalar input). 0 where ``c2/(λT) > 700`` (the exponential would
        overflow: a cold body at a short wavelength).

    Raises
    ------
    ValueError
        For an element that is not finite and > 0, naming the argument, the value and the
        flat index (and its position in a multi-dimensional broadcast shape).
    """
    shape, flat = _broadcast(("wavelength_um", "temperature_k"), (wavelength_um, temperature_k))
    try:
        out = _polbrdf.planck_flat(*flat)
    except ValueError as e:
        raise _located(e, shape) from None
    return _scalar_or_array(out, shape)


def brightness_temperature(wavelength_um: ArrayLike, radiance: ArrayLike) -> NDArray[np.float64]:
    """The brightness temperature in K: the temperature T of the blackbody whose spectral
    radiance :func:`planck` at ``wavelength_um`` (µm) is ``radiance`` (W·m⁻²·sr⁻¹·µm⁻¹),
    ``T = c2/(λ·ln(1 + c1L/(λ⁵·L)))``. The arguments broadcast; the result has their shape.

    Raises ``ValueError`` for an element that is not finite and > 0, naming the argument, the
    value and the flat index.
    """
    shape, flat = _broadcast(("wavelength_um", "radiance"), (wavelength_um, radiance))
    try:
        out = _polbrdf.brightness_temperature_flat(*flat)
    except ValueError as e:
        raise _located(e, shape) from None
    return _scalar_or_array(out, shape)


def emissivity(
    material: Material,
    theta_r: ArrayLike,
    *,
    degrees: bool = True,
    wavelength_um: ArrayLike | None = None,
    band: str | os.PathLike[str] | None = None,
    band_step_um: float | None = None,
    temperature_k: float | None = None,
) -> Emissivity:
    """The emissivity Stokes vector of an opaque surface seen from view zenith ``theta_r``, by
    Kirchhoff's law (the core's ``analysis::emission``; dimensionless).

    Inside an isothermal enclosure a surface sends ``B·(1, 0, 0, 0)`` into every direction:
    what it reflects of the enclosure plus what it emits, so the emitted Stokes radiance at
    temperature T is ``B_λ(λ, T)·ε`` with ``ε = e0 − ∫_H F(w_i, w_r)[:, 0] cosθi dω_i``. The
    hemispherical integrals are a facet-normal quadrature accurate to 1e-6 on every component
    for σ from 0.05° to 80°; the volume term is integrated in closed form. The model is
    isotropic: ε does not depend on the view azimuth.

    Parameters
    ----------
    material : Material
        The ``standard`` form (the ``paper`` form's hemispherical integrals diverge).
    theta_r : array_like
        View zenith angle, in [0°, 90°) — degrees, or radians with ``degrees=False``.
    degrees : bool
        Whether ``theta_r`` is in degrees (default) or radians.
    wavelength_um : array_like, optional
        Vacuum wavelength in µm, broadcast with ``theta_r``: required for a spectral index
        (``Material(index=...)``), evaluated with its index at each wavelength; a constant
        index does not depend on it. Each distinct wavelength is one batch of all its distinct
        angles.
    band, band_step_um : str or path, float, optional
        A band instead of ``wavelength_um``: a response file (CSV ``wavelength_um,response``)
        and its largest quadrature step (µm): the response-weighted mean of ε over the band's
        nodes, as ``polbrdf emission --band`` computes it (the same numbers bit for bit; the
        view angles are taken in degrees, radians converted).
    temperature_k : float, optional
        With ``band``: weight the wavelengths by Planck's law at this temperature as well as by
        the response (``polbrdf emission --temperature-k``): the emissivity of a surface at that
        temperature, seen in the band.

    Returns
    -------
    Emissivity
        ``eps``, ``eps_b`` of shape ``broadcast_shape + (4,)``; ``eps_s``, ``eps_p``, ``dolp``,
        ``reciprocity_residual`` and ``valid`` (bool) of ``broadcast_shape`` (NumPy scalars
        for scalar input). See :class:`Emissivity`.

    Raises
    ------
    ValueError
        For ``theta_r`` NaN/inf or outside [0°, 90°) (naming ``theta_r``, the value and the flat
        index); a wavelength not finite and > 0 or outside a spectral index's data (naming
        ``wavelength_um`` and the index); a spectral material without ``wavelength_um``; the
        ``paper`` form (the core's message).
    TypeError
        For a non-Material ``material`` or non-real arguments.
    """
    _check_material(material)
    if band is not None or temperature_k is not None or band_step_um is not None:
        return _emissivity_over_band(
            material, theta_r, degrees, wavelength_um, band, band_step_um, temperature_k
        )
    names = ("theta_r", "wavelength_um")
    args = (theta_r,) if wavelength_um is None else (theta_r, wavelength_um)
    shape, flat = _broadcast(names, args)
    try:
        e, eb, es, ep, d, r, v = _polbrdf.emissivity_flat(
            material, flat[0], degrees, flat[1] if len(flat) == 2 else None
        )
    except ValueError as err:
        raise _located(err, shape) from None
    return Emissivity(
        e.reshape(shape + (4,)),
        eb.reshape(shape + (4,)),
        _scalar_or_array(es, shape),
        _scalar_or_array(ep, shape),
        _scalar_or_array(d, shape),
        _scalar_or_array(r, shape),
        _scalar_or_array(v, shape),
    )


def _emissivity_over_band(
    material: Material,
    theta_r: ArrayLike,
    degrees: bool,
    wavelength_um: ArrayLike | None,
    band: str | os.PathLike[str] | None,
    band_step_um: float | None,
    temperature_k: float | None,
) -> Emissivity:
    """:func:`emissivity` over a band, through the task layer (``polbrdf emission``)."""
    if wavelength_um is not None:
        e = ValueError("invalid `wavelength_um`: give one wavelength or a band, not both")
        e.argument = "wavelength_um"  # type: ignore[attr-defined]
        raise e
    t = _real("theta_r", theta_r).astype(np.float64)
    shape = t.shape
    flat = t.reshape(-1) if degrees else np.degrees(t.reshape(-1))
    if flat.size == 0:
        e = ValueError("invalid `theta_r`: no angle given")
        e.argument = "theta_r"  # type: ignore[attr-defined]
        raise e
    e0, eb, es, ep, d, r, v = _band_emission(material, flat, temperature_k, band, band_step_um)
    return Emissivity(
        e0.reshape(shape + (4,)),
        eb.reshape(shape + (4,)),
        _scalar_or_array(es, shape),
        _scalar_or_array(ep, shape),
        _scalar_or_array(d, shape),
        _scalar_or_array(r, shape),
        _scalar_or_array(v, shape),
    )


def _scalar(name: str, x: ArrayLike | None, hint: str = "") -> float | None:
    """A scalar keyword argument as a float (``None`` stays ``None``)."""
    if x is None:
        return None
    arr = np.asarray(x)
    if arr.dtype.kind not in "biuf":
        raise TypeError(f"`{name}` must be a real number, got dtype {arr.dtype}")
    if arr.ndim != 0:
        raise ValueError(f"`{name}` must be a scalar, got an array of shape {arr.shape}{hint}")
    return float(arr)


def _table(
    name: str, t: tuple[ArrayLike, ArrayLike] | None, columns: tuple[str, str]
) -> tuple[_F64, _F64] | None:
    """A pair of 1-D arrays (a band, a sky profile) as contiguous float64 arrays."""
    if t is None:
        return None
    if isinstance(t, (str, bytes)) or not isinstance(t, Sequence) or len(t) != 2:
        raise TypeError(f"`{name}` must be a pair ({columns[0]}, {columns[1]}) of 1-D arrays")
    out = []
    for col, a in zip(columns, t):
        arr = np.asarray(a)
        if arr.dtype.kind not in "biuf":
            raise TypeError(f"`{name}`: `{col}` must hold real numbers, got dtype {arr.dtype}")
        if arr.ndim != 1:
            raise ValueError(f"`{name}`: `{col}` must be a 1-D array, got shape {arr.shape}")
        out.append(np.ascontiguousarray(arr, dtype=np.float64))
    return out[0], out[1]


def _sun(
    sun: tuple[float, float, float] | tuple[float, float, float, ArrayLike] | None,
) -> tuple[float, float, float, tuple[float, float, float, float]] | None:
    """The ``sun`` argument as ``(zenith, azimuth, irradiance, stokes)`` floats (unpolarized
    when no Stokes vector is given; normalized and checked by the compiled half)."""
    if sun is None:
        return None
    if isinstance(sun, (str, bytes)) or not isinstance(sun, Sequence) or len(sun) not in (3, 4):
        raise TypeError(
            "`sun` must be a tuple (zenith, azimuth, irradiance) or (zenith, azimuth, "
            "irradiance, stokes)"
        )
    names = ("sun[0] (zenith)", "sun[1] (azimuth)", "sun[2] (irradiance)")
    zenith, azimuth, irradiance = (_scalar(n, x) for n, x in zip(names, sun[:3]))
    stokes = (1.0, 0.0, 0.0, 0.0)
    if len(sun) == 4:
        arr = np.asarray(sun[3])
        if arr.dtype.kind not in "biuf":
            raise TypeError(f"`sun[3] (stokes)` must hold real numbers, got dtype {arr.dtype}")
        if arr.shape != (4,):
            raise ValueError(
                "`sun[3] (stokes)` must be a Stokes vector (s0, s1, s2, s3) of shape (4,), got "
                f"shape {arr.shape}"
            )
        stokes = tuple(float(v) for v in arr)
    return zenith, azimuth, irradiance, stokes  # type: ignore[return-value]


def _sky_table(
    t: tuple[ArrayLike, ArrayLike, ArrayLike] | None,
) -> tuple[_F64, _F64, _F64] | None:
    """The ``sky_table`` argument as contiguous float64 arrays: zenith angles, azimuths and the
    Stokes radiances as ``(len(theta_deg)·len(phi_deg), 4)``, θ-major."""
    if t is None:
        return None
    if isinstance(t, (str, bytes)) or not isinstance(t, Sequence) or len(t) != 3:
        raise TypeError("`sky_table` must be a triple (theta_deg, phi_deg, stokes) of arrays")
    out = []
    for col, a in zip(("theta_deg", "phi_deg", "stokes"), t):
        arr = np.asarray(a)
        if arr.dtype.kind not in "biuf":
            raise TypeError(f"`sky_table`: `{col}` must hold real numbers, got dtype {arr.dtype}")
        out.append(arr)
    theta, phi, stokes = out
    for col, arr in (("theta_deg", theta), ("phi_deg", phi)):
        if arr.ndim != 1:
            raise ValueError(f"`sky_table`: `{col}` must be a 1-D array, got shape {arr.shape}")
    expected = (theta.shape[0], phi.shape[0], 4)
    if stokes.shape != expected:
        raise ValueError(
            "`sky_table`: `stokes` must have shape (len(theta_deg), len(phi_deg), 4) = "
            f"{expected}, got {stokes.shape}"
        )
    return (
        np.ascontiguousarray(theta, dtype=np.float64),
        np.ascontiguousarray(phi, dtype=np.float64),
        np.ascontiguousarray(stokes, dtype=np.float64).reshape(-1, 4),
    )


@overload
def radiance(
    material: Material,
    theta_r: Scene,
    phi_r: tuple[ArrayLike, ArrayLike],
    *,
    degrees: bool = True,
) -> Radiance: ...
@overload
def radiance(
    material: Material,
    theta_r: ArrayLike,
    phi_r: ArrayLike,
    *,
    degrees: bool = True,
    wavelength_um: float | None = None,
    band: tuple[ArrayLike, ArrayLike] | None = None,
    band_step_um: float | None = None,
    temperature_k: float | None = None,
    sky: str | None = None,
    sky_radiance: float | None = None,
    sky_temperature_k: float | None = None,
    sky_profile: tuple[ArrayLike, ArrayLike] | None = None,
    transmittance: float | None = None,
    path_radiance: float | None = None,
    sun: tuple[float, float, float] | tuple[float, float, float, ArrayLike] | None = None,
    sky_irradiance: float | None = None,
    dop_max: float | None = None,
    sky_table: tuple[ArrayLike, ArrayLike, ArrayLike] | None = None,
) -> Radiance: ...
def radiance(
    material: Material,
    theta_r: ArrayLike | Scene,
    phi_r: ArrayLike | tuple[ArrayLike, ArrayLike],
    *,
    degrees: bool = True,
    wavelength_um: float | None = None,
    band: tuple[ArrayLike, ArrayLike] | None = None,
    band_step_um: float | None = None,
    temperature_k: float | None = None,
    sky: str | None = None,
    sky_radiance: float | None = None,
    sky_temperature_k: float | None = None,
    sky_profile: tuple[ArrayLike, ArrayLike] | None = None,
    transmittance: float | None = None,
    path_radiance: float | None = None,
    sun: tuple[float, float, float] | tuple[float, float, float, ArrayLike] | None = None,
    sky_irradiance: float | None = None,
    dop_max: float | None = None,
    sky_table: tuple[ArrayLike, ArrayLike, ArrayLike] | None = None,
) -> Radiance:
    """The observed Stokes radiance of a surface in a scene: its own polarized emission, the
    sun and the sky it reflects, and the atmosphere between it and the sensor (the core's
    ``analysis::scene::observed_radiance``), vectorized over the views.

    Two forms. ``radiance(material, scene, (theta_r, phi_r))`` takes a :class:`Scene` (a scene
    file's keys, e.g. ``Scene.from_toml("scene.toml")``), read by the CLI's reader: the same
    numbers as ``polbrdf radiance --scene`` bit for bit, at the ``[surface]`` temperature (a
    scene with a ``[target]`` or ``[background]`` is refused: those are for ``contrast``).
    ``radiance(material, theta_r, phi_r, **keywords)`` takes the scene as the keywords below,
    which also take a band, a sky profile or a sky table as arrays rather than files; a keyword
    left at ``None`` takes the scene files' default. Both forms give identical numbers for the
    same scene.

    ``S(w_r) = B_λ(λ, T)·ε(w_r) + E·cosθs·F(w_s, w_r)·s + ∫_H F(w, w_r)·L_sky(w) cosθ dω`` and
    at the sensor ``S_sensor = τ·S + L_path·(1, 0, 0, 0)``, with ``F`` the pBRDF
    (:func:`mueller`), ``w_s`` the direction toward the sun, ``E`` its irradiance and ``s`` its
    Stokes vector. For a uniform sky of radiance ``L_d`` (``"uniform"``, or ``"thermal"`` with
    ``L_d = B_λ(λ, T_sky)``) the sky term is exactly ``L_d·(e0 − ε)`` by Kirchhoff's law, so
    without a sun ``S = L_d·e0 + (B_λ(T) − L_d)·ε``: unpolarized when ``B_λ(T) = L_d`` (an
    isothermal enclosure), and S1 changes sign (AoLP turns by 90°) when the sky is the
    brighter. The other skies (``"profile"``, ``"cie-clear"``, ``"table"``) take the general
    sky integral; ``"cie-clear"`` and ``"table"`` (and a sun) depend on the view azimuth.

    **Units**: radiances (``stokes``, ``emitted``, ``reflected``) are spectral radiances in
    **W·m⁻²·sr⁻¹·µm⁻¹** at one wavelength (``wavelength_um``), and band radiances
    ``∫ R(λ)·S(λ) dλ`` in **W·m⁻²·sr⁻¹** over a ``band`` (the Stokes vector is integrated, then
    DoLP and AoLP taken of it). ``sky_radiance``, ``sky_profile``'s and ``sky_table``'s
    radiances and ``path_radiance`` are spectral radiances (W·m⁻²·sr⁻¹·µm⁻¹), the sun's and
    ``sky_irradiance`` spectral irradiances (W·m⁻²·µm⁻¹), all constant across a band.

    Parameters
    ----------
    material : Material
        The ``standard`` form (the ``paper`` form has no emissivity).
    theta_r, phi_r : array_like
        View zenith (in [0°, 90°)) and azimuth, degrees (radians with ``degrees=False``);
        broadcast together to ``views_shape``. Directions point from the surface to the sensor.
    degrees : bool
        Unit of the angles and of the returned AoLP.
    wavelength_um : float, optional
        One vacuum wavelength in µm (a scalar). Exactly one of ``wavelength_um`` and ``band``.
    band : (wavelengths_um, response), optional
        A band: its relative spectral response ``response[i]`` (≥ 0) at strictly increasing
        ``wavelengths_um[i]`` (µm), 1-D arrays, linear between them and zero outside; results
        are integrated over it with 3-point Gauss–Legendre pieces.
    band_step_um : float, optional
        Largest quadrature piece over the band in µm (default: 1/16 of its width; the
        tabulated wavelengths of a spectral index are panel edges as well). Only with ``band``.
    temperature_k : float, optional
        Surface temperature in K (> 0); ``None``: no thermal emission.
    sky : str, optional
        ``"none"`` (the default: nothing to reflect), ``"uniform"`` (an unpolarized sky of radiance
        ``sky_radiance`` everywhere), ``"thermal"`` (a uniform sky radiating as a blackbody at
        ``sky_temperature_k``), ``"profile"`` (``sky_profile``, depending on the zenith angle),
        ``"cie-clear"`` (the CIE standard clear sky, type 12, with Rayleigh polarization, for
        the ``sun``'s position, scaled to ``sky_irradiance``) or ``"table"`` (a tabulated
        Stokes sky, ``sky_table``).
    sky_radiance : float, optional
        For ``sky="uniform"`` only: W·m⁻²·sr⁻¹·µm⁻¹ (≥ 0).
    sky_temperature_k : float, optional
        For ``sky="thermal"`` only: the sky's brightness temperature in K (> 0).
    sky_profile : (zenith_deg, radiance), optional
        For ``sky="profile"`` only: 1-D arrays, zenith angles in degrees strictly increasing
        from 0 to 90, spectral radiance (≥ 0, W·m⁻²·sr⁻¹·µm⁻¹) at each, linear between them;
        an unpolarized sky independent of azimuth.
    transmittance : float, optional
        Atmospheric transmittance τ in [0, 1] between surface and sensor (default 1, the
        scene files' default).
    path_radiance : float, optional
        Unpolarized path radiance added at the sensor, W·m⁻²·sr⁻¹·µm⁻¹ (≥ 0, default 0).
    sun : (zenith, azimuth, irradiance) or (zenith, azimuth, irradiance, stokes), optional
        A collimated source in the direction ``(zenith, azimuth)`` (toward the sun; in the
        unit of the views: degrees, radians with ``degrees=False``; zenith in [0°, 90°)), of
        spectral irradiance ``irradiance`` on a plane normal to its beam (W·m⁻²·µm⁻¹, ≥ 0) and
        Stokes vector ``stokes`` (a length-4 sequence, normalized here to ``s0 = 1``, so only
        its polarization matters; degree of polarization ≤ 1, up to 1e-9 above it taken as 1;
        in the psps basis of the beam arriving at the surface, as a ``mueller`` input; default
        unpolarized ``(1, 0, 0, 0)``). It adds ``E·cosθs·F(w_s, w_r)·s`` to ``reflected``.
        ``None`` (default): no sun.
    sky_irradiance : float, optional
        For ``sky="cie-clear"`` only (and required there): the sky's horizontal spectral
        irradiance ``∫_H L_sky cosθ dω`` in W·m⁻²·µm⁻¹ (≥ 0), the sun's beam excluded.
    dop_max : float, optional
        For ``sky="cie-clear"`` only: the Rayleigh maximum degree of polarization δ_max in
        [0, 1], reached 90° from the sun (default :data:`DEFAULT_DOP_MAX`); the sky's DoLP is
        ``δ_max·sin²γ/(1 + cos²γ)`` at angle γ from the sun, its E-vector normal to the plane
        of sun, sky point and surface.
    sky_table : (theta_deg, phi_deg, stokes), optional
        For ``sky="table"`` only: zenith angles in **degrees** (whatever ``degrees`` says, as
        in a scene file), strictly increasing from 0 to 90; azimuths in degrees, strictly
        increasing in [0, 360); ``stokes`` of shape ``(len(theta_deg), len(phi_deg), 4)``: the
        Stokes radiance (W·m⁻²·sr⁻¹·µm⁻¹; ``s0 ≥ 0``, degree of polarization ≤ 1) arriving
        from ``(theta_deg[j], phi_deg[k])`` in that arriving beam's psps basis (propagation
        ``k = −w``, ``s = unit(z × k)``), bilinear between the nodes and periodic in azimuth.

    Returns
    -------
    Radiance
        ``stokes``, ``emitted``, ``reflected`` of shape ``views_shape + (4,)``, ``dolp`` and
        ``aolp`` of ``views_shape``. See :class:`Radiance`.

    Raises
    ------
    ValueError
        For a view angle NaN/inf or a zenith outside [0°, 90°) (naming the argument, the value
        and the flat index); both or neither of ``wavelength_um`` and ``band``; a sky argument
        missing for its model or given to another model; an unknown sky model;
        ``sky="cie-clear"`` without a ``sun``; a sun at or below the horizon, a negative
        irradiance, a Stokes vector with ``s0 ≤ 0``, of a degree of polarization above 1 or not
        of length 4; an invalid temperature, radiance,
        transmittance, band, profile, ``dop_max`` or sky table (naming the argument, and for a
        table the offending entry); a wavelength outside a spectral index's data; the
        ``paper`` form (the core's message).
    TypeError
        For a non-Material ``material``, non-real arguments, or a ``sun`` / ``sky_table`` that
        is not a tuple of 3–4 / 3 entries; a scene with a flat keyword, or ``views`` that are
        not a pair ``(theta_r, phi_r)``.
    """
    _check_material(material)
    flat_keywords = {
        "wavelength_um": wavelength_um, "band": band, "band_step_um": band_step_um,
        "temperature_k": temperature_k, "sky": sky, "sky_radiance": sky_radiance,
        "sky_temperature_k": sky_temperature_k, "sky_profile": sky_profile,
        "transmittance": transmittance, "path_radiance": path_radiance, "sun": sun,
        "sky_irradiance": sky_irradiance, "dop_max": dop_max, "sky_table": sky_table,
    }  # fmt: skip
    if isinstance(theta_r, Scene):
        given = [k for k, v in flat_keywords.items() if v is not None]
        if given:
            raise TypeError(
                f"radiance(material, scene, views) takes the scene's own keys, not `{given[0]}`"
            )
        return _radiance_of_scene(material, theta_r, phi_r, degrees)
    shape, flat = _broadcast(("theta_r", "phi_r"), (theta_r, phi_r))
    if sky is not None and not isinstance(sky, str):
        raise TypeError(f"`sky` must be a string, not {type(sky).__name__}")
    kwargs = {
        "wavelength_um": _scalar(
            "wavelength_um",
            wavelength_um,
            " (one wavelength in µm: call radiance once per wavelength, or give band=)",
        ),
        "band": _table("band", band, ("wavelengths_um", "response")),
        "band_step_um": _scalar("band_step_um", band_step_um),
        "temperature_k": _scalar("temperature_k", temperature_k),
        "sky": sky,
        "sky_radiance": _scalar("sky_radiance", sky_radiance),
        "sky_temperature_k": _scalar("sky_temperature_k", sky_temperature_k),
        "sky_profile": _table("sky_profile", sky_profile, ("zenith_deg", "radiance")),
        "transmittance": _scalar("transmittance", transmittance),
        "path_radiance": _scalar("path_radiance", path_radiance),
        "sun": _sun(sun),
        "sky_irradiance": _scalar("sky_irradiance", sky_irradiance),
        "dop_max": _scalar("dop_max", dop_max),
        "sky_table": _sky_table(sky_table),
    }
    try:
        arrays = _polbrdf.radiance_flat(material, flat[0], flat[1], degrees, **kwargs)
    except ValueError as e:
        raise _located(e, shape) from None
    return _radiance_result(arrays, shape)


def _radiance_of_scene(
    material: Material, scene: Scene, views: object, degrees: bool
) -> Radiance:
    """:func:`radiance` of a :class:`Scene` at ``views = (theta_r, phi_r)``."""
    if isinstance(views, (str, bytes)) or not isinstance(views, Sequence) or len(views) != 2:
        raise TypeError("`views` must be a pair (theta_r, phi_r) of array_likes")
    shape, flat = _broadcast(("theta_r", "phi_r"), (views[0], views[1]))
    try:
        arrays = _polbrdf.radiance_scene(
            material, scene.to_toml(), "<polbrdf.Scene>", flat[0], flat[1], degrees
        )
    except ValueError as e:
        raise _located(e, shape) from None
    return _radiance_result(arrays, shape)


def _radiance_result(
    arrays: tuple[_F64, _F64, _F64, _F64, _F64], shape: tuple[int, ...]
) -> Radiance:
    """The arrays of ``radiance_flat`` / ``radiance_scene`` in the views' shape."""
    s, em, re, d, a = arrays
    return Radiance(
        s.reshape(shape + (4,)),
        em.reshape(shape + (4,)),
        re.reshape(shape + (4,)),
        _scalar_or_array(d, shape),
        _scalar_or_array(a, shape),
    )


# --- Lookup tables (optional extra `polbrdf[xarray]`; imported on first use) ----------------


def __getattr__(name: str) -> object:
    """``polbrdf.lut``, ``polbrdf.open_lut``: :mod:`polbrdf.xarray`'s, imported on first use so that
    ``import polbrdf`` does not import xarray."""
    if name in ("lut", "open_lut", "xarray"):
        import importlib

        try:
            _lut_module = importlib.import_module(".xarray", __name__)
        except ImportError as e:
            raise ImportError(
                f"polbrdf.{name} needs the optional extra: pip install 'polbrdf[xarray]' ({e})"
            ) from e
        return _lut_module if name == "xarray" else getattr(_lut_module, name)
    raise AttributeError(f"module 'polbrdf' has no attribute {name!r}")
