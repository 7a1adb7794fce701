"""The main jobs of the command line, from Python: a contrast study (:func:`contrast`), a
hemisphere map (:func:`hemisphere`) and the albedo (:func:`albedo`).

Each is one call of the task layer (the Rust crate ``polbrdf-tasks``) that ``polbrdf contrast``,
``polbrdf map`` and ``polbrdf albedo`` call too: the same validation, the same messages, the same
numbers bit for bit (``contrast.csv``'s columns, ``best.json``'s document, ``map.csv``, the
albedo table). Python only hands the arguments over and shapes the tables into maps over the
viewing grid.
"""

from __future__ import annotations

import json
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, NamedTuple, TypeAlias

import numpy as np
from numpy.typing import NDArray

from . import _polbrdf
from .scene import Scene

if TYPE_CHECKING:  # pragma: no cover
    import xarray

__all__ = [
    "AlbedoTable",
    "ContrastStudy",
    "HemisphereMap",
    "Illumination",
    "RankBy",
    "albedo",
    "contrast",
    "hemisphere",
]

#: The scores :func:`contrast` ranks directions by (``best.json``'s ``ranking.by``).
RankBy: TypeAlias = Literal["delta-dolp", "polarization-contrast"]

PathName: TypeAlias = "str | os.PathLike[str]"
_F64 = NDArray[np.float64]


@dataclass(frozen=True, kw_only=True)
class Illumination:
    """A collimated source, as the CLI's ``--sun-zenith-deg``, ``--sun-azimuth-deg`` and
    ``--stokes``: zenith angle in degrees in [0, 90), azimuth in degrees (``None``: the CLI's
    default, 0; the specular direction is 180° away) and the incident Stokes vector (psps basis,
    normalized to s0 = 1; ``None``: unpolarized). Maps are per unit irradiance."""

    sun_zenith_deg: float
    sun_azimuth_deg: float | None = None
    stokes: Sequence[float] | None = None

    def _light(self) -> tuple[float, float | None, tuple[float, float, float, float] | None]:
        s = None
        if self.stokes is not None:
            v = [float(x) for x in self.stokes]
            if len(v) != 4:
                raise ValueError(
                    f"invalid `stokes`: expected 4 values (s0, s1, s2, s3), got {len(v)}"
                )
            s = (v[0], v[1], v[2], v[3])
        azimuth = None if self.sun_azimuth_deg is None else float(self.sun_azimuth_deg)
        return float(self.sun_zenith_deg), azimuth, s


@dataclass(frozen=True)
class HemisphereMap:
    """Quantities over the viewing hemisphere on a grid of view zeniths × azimuths.

    - ``theta_r_deg`` (shape ``(n_theta,)``) and ``phi_r_deg`` (``(n_phi,)``): the grid;
    - ``columns`` and ``table`` (``(n_theta·n_phi, len(columns))``, zenith-major): the CLI's
      CSV table, column for column;
    - ``maps``: each column but the two angles as an array of shape ``(n_theta, n_phi)``, also
      reachable as ``result["dolp"]``;
    - ``invalid_zeniths_deg``: the grid zeniths (degrees, increasing) where the model is
      flagged invalid — its emissivity outside [0, 1] at some spectral node: it reflects more
      than it receives there — the ring of dots on ``polbrdf map``'s figures (empty for the
      ``paper`` form, which has no finite flag). In a :class:`ContrastStudy`, where either
      model is.
    """

    theta_r_deg: _F64
    phi_r_deg: _F64
    columns: tuple[str, ...]
    table: _F64
    maps: dict[str, _F64] = field(repr=False)
    invalid_zeniths_deg: _F64 = field(default_factory=lambda: np.empty(0), repr=False)

    def __getitem__(self, name: str) -> _F64:
        return self.maps[name]

    def _attrs(self) -> dict[str, Any]:
        return {}

    def to_xarray(self) -> xarray.Dataset:
        """The maps as an :class:`xarray.Dataset` over ``(theta_r_deg, phi_r_deg)`` (needs
        ``xarray``: ``pip install "polbrdf[xarray]"``)."""
        try:
            import xarray as xr
        except ImportError as e:
            raise ImportError(
                'to_xarray() needs xarray: pip install "polbrdf[xarray]"'
            ) from e
        dims = ("theta_r_deg", "phi_r_deg")
        return xr.Dataset(
            {name: (dims, m) for name, m in self.maps.items()},
            coords={"theta_r_deg": self.theta_r_deg, "phi_r_deg": self.phi_r_deg},
            attrs=self._attrs(),
        )


@dataclass(frozen=True)
class ContrastStudy(HemisphereMap):
    """The result of :func:`contrast`: the maps of ``contrast.csv`` (see :class:`HemisphereMap`;
    in a scene also ``radiance_difference``), ``best`` — the document ``best.json`` holds, as
    a dict: the ranked directions (``best["top"]``), the ranking, materials, grid, source or
    scene and, in a scene, the polarization-null loci — the setup's ``warnings`` (valid but
    probably unintended: the CLI prints them), and where each model is flagged invalid:
    ``invalid_zeniths_target_deg`` and ``invalid_zeniths_background_deg`` (marked on the DoLP
    map of each), ``invalid_zeniths_deg`` where either is (marked on the maps comparing them)."""

    best: dict[str, Any] = field(default_factory=dict, repr=False)
    warnings: tuple[str, ...] = ()
    invalid_zeniths_target_deg: _F64 = field(default_factory=lambda: np.empty(0), repr=False)
    invalid_zeniths_background_deg: _F64 = field(
        default_factory=lambda: np.empty(0), repr=False
    )

    @property
    def top(self) -> list[dict[str, float]]:
        """The best directions, best first (``best.json``'s ``top``)."""
        return list(self.best["top"])

    @property
    def null_loci(self) -> dict[str, Any] | None:
        """In a scene, ``best.json``'s ``polarization_null``; ``None`` under a collimated
        source."""
        return self.best.get("polarization_null")

    def _attrs(self) -> dict[str, Any]:
        # One string: netCDF and Zarr attributes hold no nested dicts.
        return {"best_json": json.dumps(self.best, ensure_ascii=False)}


def _maps(
    columns: Sequence[str], table: _F64, shape: tuple[int, int]
) -> tuple[_F64, _F64, dict[str, _F64]]:
    """The grid and the maps of a zenith-major table."""
    n_theta, n_phi = shape
    t = table[:, 0].reshape(n_theta, n_phi)
    p = table[:, 1].reshape(n_theta, n_phi)
    maps = {c: table[:, k].reshape(n_theta, n_phi) for k, c in enumerate(columns) if k >= 2}
    return t[:, 0].copy(), p[0].copy(), maps


def _grid(grid: float | Sequence[float] | None) -> tuple[float, float] | None:
    """``grid``: one step for both angles or ``(Δθ, Δφ)`` in degrees (the CLI's ``--grid-deg``);
    ``None``: the task's default."""
    if grid is None:
        return None
    if isinstance(grid, (int, float)):
        return float(grid), float(grid)
    g = [float(x) for x in grid]
    if len(g) not in (1, 2):
        raise ValueError(
            f"invalid `grid`: expected one step or (theta_step_deg, phi_step_deg), got {len(g)} "
            "values"
        )
    return (g[0], g[-1])


def _material(name: str, value: PathName | None) -> str | None:
    if value is None:
        return None
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(
            f"`{name}` must be a material file or a preset name (str or path), not "
            f"{type(value).__name__}"
        )
    return os.fspath(value)


def _spectral(
    wavelength_um: float | None, band: PathName | None, band_step_um: float | None
) -> tuple[float | None, str | None, float | None]:
    return (
        None if wavelength_um is None else float(wavelength_um),
        None if band is None else os.fspath(band),
        None if band_step_um is None else float(band_step_um),
    )


def contrast(
    target: PathName | None,
    background: PathName | None,
    source: Scene | Illumination | PathName,
    *,
    grid: float | Sequence[float] | None = None,
    rank_by: RankBy | None = None,
    top: int | None = None,
    min_separation_deg: float | None = None,
    max_zenith_deg: float | None = None,
    refine: bool | None = None,
    wavelength_um: float | None = None,
    band: PathName | None = None,
    band_step_um: float | None = None,
) -> ContrastStudy:
    """Target against background over the viewing hemisphere: ``polbrdf contrast``.

    Parameters
    ----------
    target, background : str or path, optional
        A material file or a preset name each (``--target``/``--background``); in a scene,
        ``None`` takes the scene's ``[target]``/``[background]`` material.
    source : Illumination, Scene, or str or path
        A collimated source (:class:`Illumination`; ``--sun-zenith-deg`` …): the reflections of
        both materials per unit irradiance. Or a scene: a :class:`polbrdf.Scene`, or the path of
        a scene file (``--scene``), whose ``[target]`` and ``[background]`` are compared by their
        observed Stokes radiances (emission, sun, sky, atmosphere).
    grid : float or (float, float), optional
        Grid steps Δθ, Δφ in degrees (``--grid-deg``; default 1°, 2°).
    rank_by : {"delta-dolp", "polarization-contrast"}, optional
        The score of the best directions (default ``"delta-dolp"``).
    top, min_separation_deg, max_zenith_deg, refine : optional
        How many directions, at least how far apart (°), up to which zenith (°), refined by
        brute force around each grid node (``--top``, ``--min-separation-deg``,
        ``--max-zenith-deg``, ``--no-refine``; defaults 10, 10°, 80°, ``True``).
    wavelength_um, band, band_step_um : optional
        Under a collimated source: one wavelength (µm), or a band response file (CSV
        ``wavelength_um,response``) with its quadrature step (µm); a scene has its own.

    Returns
    -------
    ContrastStudy
        The maps (``study["delta_dolp"]``, …), ``study.best`` (``best.json``), ``study.top``,
        ``study.null_loci``, ``study.warnings``; ``study.to_xarray()``.

    Raises
    ------
    ValueError
        For a bad argument, naming the keyword (also as the exception's ``argument``); for a
        bad material, band or scene file, naming file, line and key.
    OSError
        When a file cannot be read.
    """
    scene_file = scene_text = light = None
    if isinstance(source, Illumination):
        light = source._light()
    elif isinstance(source, Scene):
        scene_text = (source.to_toml(), "<polbrdf.Scene>")
    elif isinstance(source, (str, os.PathLike)):
        scene_file = os.fspath(source)
    else:
        raise TypeError(
            "`source` must be a polbrdf.Illumination, a polbrdf.Scene or the path of a scene "
            f"file, not {type(source).__name__}"
        )
    if light is None:
        for name, value in (
            ("wavelength_um", wavelength_um),
            ("band", band),
            ("band_step_um", band_step_um),
        ):
            if value is not None:
                e = ValueError(
                    f"invalid `{name}`: a scene has its own spectrum (`wavelength_um` or "
                    "[band]); this keyword is for a collimated source"
                )
                e.argument = name  # type: ignore[attr-defined]
                raise e
    columns, table, shape, best, warnings, (bad, bad_t, bad_b) = _polbrdf.contrast_task(
        _material("target", target),
        _material("background", background),
        scene_file,
        scene_text,
        light,
        _spectral(wavelength_um, band, band_step_um),
        _grid(grid),
        rank_by,
        top,
        min_separation_deg,
        max_zenith_deg,
        refine,
    )
    theta, phi, maps = _maps(columns, table, shape)
    return ContrastStudy(
        theta, phi, tuple(columns), table, maps, bad, json.loads(best), tuple(warnings), bad_t, bad_b
    )


def hemisphere(
    material: PathName,
    illumination: Illumination,
    *,
    grid: float | Sequence[float] | None = None,
    wavelength_um: float | None = None,
    band: PathName | None = None,
    band_step_um: float | None = None,
) -> HemisphereMap:
    """The hemisphere map of one material under a collimated source: ``polbrdf map``.

    The BRDF (sr⁻¹) and the reflected Stokes vector per unit irradiance (``s0`` … ``s3``, with
    ``dolp`` and ``aolp_deg``) at every direction of the viewing grid, the response-weighted
    mean over a band's nodes. Arguments as :func:`contrast`'s; ``material`` a material file or
    a preset name.
    """
    if not isinstance(illumination, Illumination):
        raise TypeError(
            f"`illumination` must be a polbrdf.Illumination, not {type(illumination).__name__}"
        )
    name = _material("material", material)
    if name is None:
        raise TypeError("`material` must be a material file or a preset name, not None")
    columns, table, shape, invalid = _polbrdf.hemisphere_task(
        name,
        illumination._light(),
        _spectral(wavelength_um, band, band_step_um),
        _grid(grid),
    )
    theta, phi, maps = _maps(columns, table, shape)
    return HemisphereMap(theta, phi, tuple(columns), table, maps, invalid)


class AlbedoTable(NamedTuple):
    """The result of :func:`albedo`, one entry per incidence angle: ``theta_i_deg``, the
    directional–hemispherical reflectance ``albedo`` = ``surface`` + ``volume`` (its facet and
    volume parts), and ``exceeds_one`` (the parameters create energy there)."""

    theta_i_deg: _F64
    albedo: _F64
    surface: _F64
    volume: _F64
    exceeds_one: NDArray[np.bool_]


def albedo(
    material: PathName,
    theta_i_deg: float | Sequence[float] | None = None,
    *,
    wavelength_um: float | None = None,
    band: PathName | None = None,
    band_step_um: float | None = None,
) -> AlbedoTable:
    """Energy conservation of a material: ``polbrdf albedo``.

    The directional–hemispherical reflectance ``∫ f cosθr dΩr`` at each incidence angle
    ``theta_i_deg`` (degrees in [0, 90); ``None``: 0, 5, …, 85), the response-weighted mean over
    a band's nodes. ``material`` is a material file or a preset name; the spectral keywords as
    :func:`contrast`'s. ``ValueError`` naming the keyword for a bad argument.
    """
    name = _material("material", material)
    if name is None:
        raise TypeError("`material` must be a material file or a preset name, not None")
    angles = [] if theta_i_deg is None else [float(t) for t in np.atleast_1d(theta_i_deg)]
    if theta_i_deg is not None and not angles:
        e = ValueError("invalid `theta_i_deg`: no angle given (None takes 0, 5, …, 85)")
        e.argument = "theta_i_deg"  # type: ignore[attr-defined]
        raise e
    t, total, surface, volume = _polbrdf.albedo_task(
        name, angles, _spectral(wavelength_um, band, band_step_um)
    )
    return AlbedoTable(t, total, surface, volume, total > 1.0)
