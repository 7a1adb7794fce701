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

from collections.abc import Mapping, Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

try:
    from . import _polbrdf
    from ._polbrdf import FitResult, Material
except ImportError as _e:  # pragma: no cover - only when the extension was never built
    raise ImportError(
        "polbrdf's compiled extension (polbrdf._polbrdf) is missing. Install the package with "
        "`pip install ./python` from the repository root; if you did, you may be importing the "
        "source folder python/polbrdf instead of the installed package (run from elsewhere)."
    ) from _e

__all__ = [
    "Evaluation",
    "FitResult",
    "Material",
    "__version__",
    "brdf",
    "dolp",
    "evaluate",
    "fit",
    "index",
    "mueller",
    "stokes_aolp",
    "stokes_dolp",
    "stokes_dop",
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


def _flatten(
    material: Material,
    angles: tuple[ArrayLike, ...],
) -> tuple[tuple[int, ...], tuple[_F64, ...]]:
    """Broadcast the four angle arguments (and the wavelength, when given: a fifth); return the
    shape and the flat C-contiguous float64 arrays (views when the input already is one,
    copies otherwise)."""
    if not isinstance(material, Material):
        raise TypeError(
            f"material must be a polbrdf.Material, not {type(material).__name__} "
            "(use polbrdf.Material.preset(name) or polbrdf.Material.from_toml(path))"
        )
    arrays = []
    for name, a in zip(_NAMES, angles):
        arr = np.asarray(a)
        if arr.dtype.kind not in "biuf":
            raise TypeError(f"`{name}` must hold real numbers, got dtype {arr.dtype}")
        arrays.append(arr)
    try:
        b = np.broadcast_arrays(*arrays)
    except ValueError as e:
        shapes = ", ".join(f"{n}: {a.shape}" for n, a in zip(_NAMES, arrays))
        raise ValueError(f"arrays do not broadcast together ({shapes})") from e
    shape = b[0].shape
    flat = tuple(np.ascontiguousarray(x, dtype=np.float64).reshape(-1) for x in b)
    return shape, flat


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
) -> NDArray[np.float64]:
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

    Returns
    -------
    ndarray of float64, shape ``broadcast_shape + (4, 4)``
        ``F[..., i, j]`` in sr⁻¹; ``F[..., 0, 0]`` is the scalar BRDF. Zero where a direction
        is at or below the horizon.

    Raises
    ------
    ValueError
        For NaN/inf angles or zenith angles outside [0°, 180°], naming the argument, value and
        flat index; or when the arguments do not broadcast.
    TypeError
        For a non-Material ``material`` or non-real angles.
    """
    shape, flat = _flatten(material, _args((theta_i, phi_i, theta_r, phi_r), wavelength_um))
    try:
        out = _polbrdf.mueller_flat(material, *flat[:4], degrees, _wl(flat))
    except ValueError as e:
        raise _located(e, shape) from None
    return out.reshape(shape + (4, 4))


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
    shape, flat = _flatten(material, _args(angles, wavelength_um))
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
    shape, flat = _flatten(material, _args((theta_i, phi_i, theta_r, phi_r), wavelength_um))
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
    names = list(data)
    arrays = [np.asarray(data[k], dtype=np.float64) for k in names]
    sig_names = [k for k in names if k in sigma]
    sig_arrays = [np.asarray(sigma[k], dtype=np.float64) for k in sig_names]
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
