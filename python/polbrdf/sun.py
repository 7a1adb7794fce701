"""The sun's position from a date, a time and a place (docs/sun-position.md): NREL's Solar
Position Algorithm (Reda & Andreas 2008, ±0.0003°) through the task layer, the numbers of
``polbrdf sun`` bit for bit; and the time-of-day sweep of a scene (:func:`daytime`), the
numbers of ``polbrdf daytime``'s ``daytime.csv`` bit for bit."""

from __future__ import annotations

import json
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from . import _polbrdf
from .scene import Scene

if TYPE_CHECKING:  # pragma: no cover
    import xarray

__all__ = ["DaytimeStudy", "daytime", "sun_position"]


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


@dataclass(frozen=True)
class DaytimeStudy:
    """The result of :func:`daytime`: ``daytime.csv``, one row per local time.

    - ``date_time``: each row's local date-time (RFC 3339 with the scene's UTC offset);
    - ``columns`` and ``table`` (``(times, len(columns))``): the CSV's columns after
      ``date_time``, every one a number (NaN where the sun is down), also reachable as
      ``study["best_delta_dolp"]``; with a sensor the detection ranges ``best_max_range_m``
      and ``fixed_max_range_m`` (m; ``inf`` beyond the search's limit, 0 when not
      detectable) and the view of the longest range;
    - ``warnings``: the setup's notes (the CLI prints them), each once over the sweep.
    """

    date_time: NDArray[np.str_]
    columns: tuple[str, ...]
    table: NDArray[np.float64] = field(repr=False)
    warnings: tuple[str, ...] = ()

    def __getitem__(self, name: str) -> NDArray[np.float64]:
        return self.table[:, self.columns.index(name)]

    def __len__(self) -> int:
        return len(self.date_time)

    def to_xarray(self) -> xarray.Dataset:
        """The columns as an :class:`xarray.Dataset` over ``local_time_h`` (with ``date_time``
        as a coordinate). Needs ``xarray``: ``pip install "polbrdf[xarray]"``."""
        try:
            import xarray as xr
        except ImportError as e:
            raise ImportError('to_xarray() needs xarray: pip install "polbrdf[xarray]"') from e
        dim = "local_time_h"
        return xr.Dataset(
            {c: (dim, self[c]) for c in self.columns if c != dim},
            coords={dim: self[dim], "date_time": (dim, self.date_time)},
        )


def _invalid(name: str, message: str) -> ValueError:
    e = ValueError(f"invalid `{name}`: {message}")
    e.argument = name  # type: ignore[attr-defined]
    return e


def daytime(
    scene: Scene | str | os.PathLike[str],
    *,
    sensor: str | os.PathLike[str] | None = None,
    target: str | os.PathLike[str] | None = None,
    background: str | os.PathLike[str] | None = None,
    date: str | None = None,
    from_: str | None = None,
    to: str | None = None,
    step_min: float | None = None,
    times: Sequence[str] | None = None,
    grid_deg: float | Sequence[float] | None = None,
    fixed_view_deg: Sequence[float] | None = None,
    area_m2: float | None = None,
    pfa: float | None = None,
    pd: float | None = None,
    range_limit_m: float | None = None,
) -> DaytimeStudy:
    """A scene whose sun is placed by date, time and place, swept through the day:
    ``polbrdf daytime`` (docs/sun-position.md).

    Parameters
    ----------
    scene : Scene, or str or path
        The scene (``--scene``), its ``[sun]`` placed by ``date_time``, ``latitude_deg`` and
        ``longitude_deg``.
    sensor : str or path, optional
        A sensor file (``--sensor``): adds the detection range of the best view and of the
        fixed view.
    target, background : str or path, optional
        A material file or preset replacing the scene's.
    date : str, optional
        ``YYYY-MM-DD`` (default: the date of the scene's ``date_time``).
    from_, to, step_min
        Local times ``HH:MM`` (the scene's UTC offset) from ``from_`` (``--from``; ``from`` is
        a Python keyword) to ``to``, every ``step_min`` minutes (defaults 06:00, 18:00, 30).
    times : sequence of str, optional
        Listed local times instead (``--times``).
    grid_deg : float or (float, float), optional
        The grid of every time's study (default 5°, 10°).
    fixed_view_deg : (float, float), optional
        The fixed view θr, φr in degrees (default nadir).
    area_m2, pfa, pd, range_limit_m : float, optional
        With a sensor: as :func:`polbrdf.detect` (same defaults).

    Raises
    ------
    ValueError
        For a bad argument, naming the keyword (also as the exception's ``argument``); for a
        bad scene or sensor file, naming file, line and key.
    """
    scene_file = scene_text = None
    if isinstance(scene, Scene):
        scene_text = (scene.to_toml(), "<polbrdf.Scene>")
    elif isinstance(scene, (str, os.PathLike)):
        scene_file = os.fspath(scene)
    else:
        raise TypeError(
            f"`scene` must be a polbrdf.Scene or the path of a scene file, not "
            f"{type(scene).__name__}"
        )
    given = {"area_m2": area_m2, "pfa": pfa, "pd": pd, "range_limit_m": range_limit_m}
    if sensor is None:
        for name, value in given.items():
            if value is not None:
                raise _invalid(name, "a detection option: give `sensor` too")
    grid = None
    if grid_deg is not None:
        g = [float(x) for x in np.atleast_1d(np.asarray(grid_deg, dtype=np.float64))]
        if len(g) not in (1, 2):
            raise _invalid("grid_deg", f"expected one or two steps, got {len(g)}")
        grid = (g[0], g[-1])
    fixed = None if fixed_view_deg is None else [float(x) for x in fixed_view_deg]
    if fixed is not None and len(fixed) != 2:
        raise _invalid("fixed_view_deg", f"expected (theta, phi), got {len(fixed)} values")
    try:
        columns, date_times, table, warnings = _polbrdf.daytime_task(
            scene_file,
            scene_text,
            None if sensor is None else os.fspath(sensor),
            None if target is None else os.fspath(target),
            None if background is None else os.fspath(background),
            date,
            None if times is None else [str(t) for t in times],
            (
                None if from_ is None else str(from_),
                None if to is None else str(to),
                None if step_min is None else float(step_min),
            ),
            grid,
            None if fixed is None else (fixed[0], fixed[1]),
            tuple(None if v is None else float(v) for v in given.values()),
        )
    except ValueError as e:
        # `from` is a Python keyword: its keyword here is `from_`.
        if getattr(e, "argument", None) == "from":
            e.argument = "from_"  # type: ignore[attr-defined]
        raise
    return DaytimeStudy(np.array(date_times, dtype=np.str_), tuple(columns), table, tuple(warnings))
