"""Thermal emission: Planck's law (:func:`planck`), its inverse
(:func:`brightness_temperature`) and the emissivity Stokes vector of a surface by Kirchhoff's
law (:func:`emissivity`), at wavelengths or over a band."""

from __future__ import annotations

import os

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _polbrdf
from ._common import _broadcast, _check_material, _located, _real, _scalar_or_array, public
from ._polbrdf import Material
from ._results import Emissivity
from .jobs import _band_emission


@public
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


@public
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


@public
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
