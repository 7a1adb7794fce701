"""Fitting material parameters to measurements given as arrays: :func:`fit` (the engine of
``polbrdf fit``, docs/model.md §7a)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike

from . import _polbrdf
from ._common import _args, _flatten, _real, _wl, public
from ._polbrdf import FitResult, Material

#: The most extra starts of :func:`fit` (the CLI's ``--starts`` limit).
MAX_STARTS = 10_000


@public
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
