"""The observed Stokes radiance of a surface in a scene, :func:`radiance`: from a
:class:`~polbrdf.Scene` (the scene file's reader) or from flat keywords (a band, a sky
profile or a sky table as arrays), both through the core's ``analysis::scene``."""

from __future__ import annotations

from collections.abc import Sequence
from typing import overload

import numpy as np
from numpy.typing import ArrayLike

from . import _polbrdf
from ._common import _F64, _broadcast, _check_material, _located, _scalar_or_array, public
from ._polbrdf import Material
from ._results import Radiance
from .scene import Scene


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
@public
def radiance(
    material: Material,
    theta_r: Scene,
    phi_r: tuple[ArrayLike, ArrayLike],
    *,
    degrees: bool = True,
) -> Radiance: ...
@overload
@public
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


@public
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
    keywords = {
        "wavelength_um": wavelength_um, "band": band, "band_step_um": band_step_um,
        "temperature_k": temperature_k, "sky": sky, "sky_radiance": sky_radiance,
        "sky_temperature_k": sky_temperature_k, "sky_profile": sky_profile,
        "transmittance": transmittance, "path_radiance": path_radiance, "sun": sun,
        "sky_irradiance": sky_irradiance, "dop_max": dop_max, "sky_table": sky_table,
    }  # fmt: skip
    if isinstance(theta_r, Scene):
        return _radiance_of_scene(material, theta_r, phi_r, degrees, keywords)
    return _radiance_of_keywords(material, theta_r, phi_r, degrees, keywords)


def _radiance_of_scene(
    material: Material, scene: Scene, views: object, degrees: bool, keywords: dict[str, object]
) -> Radiance:
    """:func:`radiance` of a :class:`Scene` at ``views = (theta_r, phi_r)``: the scene's keys
    read by the scene files' reader (``radiance_scene``). Every flat keyword (``keywords``)
    must be ``None``: a scene is given whole, by its own keys."""
    given = [k for k, v in keywords.items() if v is not None]
    if given:
        raise TypeError(
            f"radiance(material, scene, views) takes the scene's own keys, not `{given[0]}`"
        )
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


def _radiance_of_keywords(
    material: Material,
    theta_r: ArrayLike,
    phi_r: ArrayLike,
    degrees: bool,
    keywords: dict[str, object],
) -> Radiance:
    """:func:`radiance` of the scene given by the flat keywords, at the views ``theta_r``,
    ``phi_r`` broadcast together: the keywords checked and converted
    (:func:`_scene_arguments`), then the compiled half's ``radiance_flat``, which assembles
    the scene (the scene files' default for every ``None``) and observes it."""
    shape, flat = _broadcast(("theta_r", "phi_r"), (theta_r, phi_r))
    arguments = _scene_arguments(**keywords)  # type: ignore[arg-type]
    try:
        arrays = _polbrdf.radiance_flat(material, flat[0], flat[1], degrees, **arguments)
    except ValueError as e:
        raise _located(e, shape) from None
    return _radiance_result(arrays, shape)


def _scene_arguments(
    *,
    wavelength_um: float | None,
    band: tuple[ArrayLike, ArrayLike] | None,
    band_step_um: float | None,
    temperature_k: float | None,
    sky: str | None,
    sky_radiance: float | None,
    sky_temperature_k: float | None,
    sky_profile: tuple[ArrayLike, ArrayLike] | None,
    transmittance: float | None,
    path_radiance: float | None,
    sun: tuple[float, float, float] | tuple[float, float, float, ArrayLike] | None,
    sky_irradiance: float | None,
    dop_max: float | None,
    sky_table: tuple[ArrayLike, ArrayLike, ArrayLike] | None,
) -> dict[str, object]:
    """The flat keywords of :func:`radiance` as ``radiance_flat`` takes them, in order, each
    checked for its type and shape (``TypeError`` / ``ValueError`` naming it): numbers as
    floats, a band and a sky profile as pairs of 1-D float64 arrays, the sun as floats, a sky
    table as float64 arrays, ``None`` kept. Their values are checked by the compiled half."""
    if sky is not None and not isinstance(sky, str):
        raise TypeError(f"`sky` must be a string, not {type(sky).__name__}")
    return {
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
