"""The sun's position from a date, a time and a place (docs/sun-position.md): NREL's Solar
Position Algorithm (Reda & Andreas 2008, ±0.0003°) through the task layer, the numbers of
``polbrdf sun`` bit for bit."""

from __future__ import annotations

import json
from typing import Any

from . import _polbrdf

__all__ = ["sun_position"]


def sun_position(
    date_time: str,
    latitude_deg: float,
    longitude_deg: float,
    *,
    elevation_m: float | None = None,
    pressure_hpa: float | None = None,
    temperature_c: float | None = None,
    delta_t_s: float | None = None,
    phi0_azimuth_deg: float | None = None,
) -> dict[str, Any]:
    """The sun seen from a place at a time: ``polbrdf sun``.

    Parameters
    ----------
    date_time : str
        RFC 3339 with the UTC offset: ``"2026-06-21T12:00:00Z"`` (UTC) or
        ``"2003-10-17T12:30:30-07:00"`` (local time at UTC−7).
    latitude_deg, longitude_deg : float
        Degrees, north and east positive.
    elevation_m, pressure_hpa, temperature_c : float, optional
        Height above sea level (default 0 m); the air's pressure (default 1013.25 hPa; 0: no
        refraction) and temperature (default 15 °C) for refraction.
    delta_t_s : float, optional
        ΔT = TT − UT1 in seconds (default: estimated from the date).
    phi0_azimuth_deg : float, optional
        The compass azimuth of the surface frame's φ = 0 axis (default 0, north).

    Returns
    -------
    dict
        ``date_time``, ``julian_day``, ``delta_t_s``, the place, ``zenith_deg``,
        ``elevation_deg``, ``azimuth_deg`` (from north toward east), ``phi0_azimuth_deg``,
        ``phi_deg`` (the sun's azimuth in the surface frame, ``phi0 − azimuth``) and
        ``above_horizon``.

    Raises
    ------
    ValueError
        Naming the keyword (also as the exception's ``argument``).
    """
    doc: dict[str, Any] = json.loads(
        _polbrdf.sun_task(
            str(date_time),
            float(latitude_deg),
            float(longitude_deg),
            elevation_m,
            pressure_hpa,
            temperature_c,
            delta_t_s,
            phi0_azimuth_deg,
        )
    )
    return doc
