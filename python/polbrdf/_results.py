"""The named tuples that ``polbrdf``'s functions return: :class:`Evaluation`
(:func:`~polbrdf.evaluate`), :class:`Emissivity` (:func:`~polbrdf.emissivity`) and
:class:`Radiance` (:func:`~polbrdf.radiance`).

Their field annotations are evaluated here (no ``from __future__ import annotations``): the
classes' module is ``polbrdf`` (:func:`~polbrdf._common.public`), where
:func:`typing.get_type_hints` could not resolve them as strings."""

from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from ._common import public


@public
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


@public
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


@public
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
