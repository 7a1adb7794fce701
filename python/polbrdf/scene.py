"""Scenes: what a surface sees — the spectrum, the sun, the sky and the atmosphere — as the
scene files of ``polbrdf radiance`` and ``polbrdf contrast --scene`` hold them.

:class:`Scene` and its tables have exactly the keys of a scene file (README, "Scene files"):
``Scene.band.step_um`` is ``[band] step_um``. A key left at ``None`` is absent from the file,
so the reader's default applies (``sky.dop_max``, ``atmosphere.transmittance``, …): no default
is written here. :meth:`Scene.from_toml` reads a file with the CLI's reader (the compiled
``polbrdf-io``: the same checks and the same messages, naming file, line and key), and
:func:`polbrdf.radiance` hands a scene to that reader again as the text :meth:`Scene.to_toml`
writes — Python reads no scene file itself and checks no value.
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal, TypeAlias

from . import _polbrdf

__all__ = ["Atmosphere", "Band", "Scene", "SceneObject", "Sky", "SkyModel", "Sun", "Surface"]

#: The sky models of ``[sky] model`` (the compiled module's ``vocabulary()["sky"]``; a test
#: checks that they agree).
SkyModel: TypeAlias = Literal["none", "uniform", "thermal", "profile", "cie-clear", "table"]

PathName: TypeAlias = "str | os.PathLike[str]"


@dataclass(frozen=True, kw_only=True)
class Band:
    """``[band]``: a band's response file (CSV ``wavelength_um,response``) and the quadrature
    step in µm (default: 1/16 of the band's width)."""

    response: PathName
    step_um: float | None = None


@dataclass(frozen=True, kw_only=True)
class Surface:
    """``[surface]``: the surface of :func:`polbrdf.radiance`; its temperature in K (``None``:
    no thermal emission)."""

    temperature_k: float | None = None


@dataclass(frozen=True, kw_only=True)
class SceneObject:
    """``[target]`` or ``[background]`` (for ``polbrdf contrast --scene``): a material file or a
    preset name, and a temperature in K."""

    material: PathName | None = None
    temperature_k: float | None = None


@dataclass(frozen=True, kw_only=True)
class Sun:
    """``[sun]``: its position, spectral irradiance on a plane normal to the beam
    (W·m⁻²·µm⁻¹) and Stokes vector (normalized to ``s0 = 1``; default unpolarized).

    The position is either the angles — ``zenith_deg`` (degrees, in [0, 90)) and
    ``azimuth_deg`` (degrees, default 0) — or placed by NREL SPA (docs/sun-position.md) from
    ``date_time`` (RFC 3339 with its UTC offset, ``"2026-06-21T12:00:00Z"``),
    ``latitude_deg`` and ``longitude_deg``, optionally ``elevation_m`` (default 0),
    ``pressure_hpa`` and ``temperature_c`` (refraction; default 1013.25 hPa, 15 °C; a pressure
    of 0 turns it off), ``delta_t_s`` (TT − UT1; default estimated from the date) and
    ``phi0_azimuth_deg`` (the compass azimuth of the surface's φ = 0 axis; default 0, north).
    The two ways exclude each other (the reader says which key is extra)."""

    zenith_deg: float | None = None
    azimuth_deg: float | None = None
    date_time: str | None = None
    latitude_deg: float | None = None
    longitude_deg: float | None = None
    elevation_m: float | None = None
    pressure_hpa: float | None = None
    temperature_c: float | None = None
    delta_t_s: float | None = None
    phi0_azimuth_deg: float | None = None
    irradiance: float
    stokes: Sequence[float] | None = None


@dataclass(frozen=True, kw_only=True)
class Sky:
    """``[sky]``: the model (default ``"none"``) and the keys it takes — ``radiance``
    (``"uniform"``, W·m⁻²·sr⁻¹·µm⁻¹), ``temperature_k`` (``"thermal"``, K), ``file``
    (``"profile"``: CSV ``zenith_deg,radiance``; ``"table"``: CSV
    ``theta_deg,phi_deg,s0,s1,s2,s3``), ``irradiance`` and ``dop_max`` (``"cie-clear"``:
    W·m⁻²·µm⁻¹ and the maximum degree of polarization, default
    :data:`polbrdf.DEFAULT_DOP_MAX`)."""

    model: SkyModel | None = None
    radiance: float | None = None
    temperature_k: float | None = None
    file: PathName | None = None
    irradiance: float | None = None
    dop_max: float | None = None


@dataclass(frozen=True, kw_only=True)
class Atmosphere:
    """``[atmosphere]``: the transmittance in [0, 1] (default 1) and the path radiance
    (W·m⁻²·sr⁻¹·µm⁻¹, default 0) between surface and sensor."""

    transmittance: float | None = None
    path_radiance: float | None = None


@dataclass(frozen=True, kw_only=True)
class PathToSensor:
    """``[path]``: the path to a detecting sensor (``polbrdf detect``, docs/detection.md): the
    extinction (``extinction_per_m``, m⁻¹, or ``visibility_km``) with the horizon radiance
    (``horizon_radiance``, W·m⁻²·sr⁻¹·µm⁻¹, or ``air_temperature_k``), or a ``table`` CSV with
    columns ``range_m, transmittance, path_radiance``."""

    extinction_per_m: float | None = None
    visibility_km: float | None = None
    horizon_radiance: float | None = None
    air_temperature_k: float | None = None
    table: PathName | None = None


@dataclass(frozen=True, kw_only=True)
class Scene:
    """A scene file's content: one wavelength (``wavelength_um``, µm) or a ``band``, and the
    tables ``surface``, ``target``, ``background``, ``sun``, ``sky``, ``atmosphere``, ``path`` (``None``:
    the table is absent). Relative file names are taken relative to the working directory
    (:meth:`from_toml` gives them joined to the scene file's folder)."""

    wavelength_um: float | None = None
    band: Band | None = None
    surface: Surface | None = None
    target: SceneObject | None = None
    background: SceneObject | None = None
    sun: Sun | None = None
    sky: Sky | None = None
    atmosphere: Atmosphere | None = None
    path: PathToSensor | None = None

    @classmethod
    def from_toml(cls, path: PathName) -> Scene:
        """Read a scene file with the CLI's reader. ``ValueError`` naming file, line and key for
        bad content (also of the files it names), ``OSError`` when it cannot be read. The file
        names it holds come back joined to its folder, as the reader finds them."""
        tables: dict[str, dict[str, Any]] = {}
        top: dict[str, Any] = {}
        for key, value in _polbrdf.read_scene_keys(os.fspath(path)):
            table, _, name = key.rpartition(".")
            if isinstance(value, list):
                value = tuple(value)
            (tables.setdefault(table, {}) if table else top)[name] = value
        for table, keys in tables.items():
            top[table] = _TABLES[table](**keys)
        return cls(**top)

    def to_toml(self) -> str:
        """The scene as scene-file text (``None`` keys and tables left out), which
        :meth:`from_toml`'s reader reads back."""
        lines = []
        for field in dataclasses.fields(self):
            value = getattr(self, field.name)
            if value is not None and not dataclasses.is_dataclass(value):
                lines.append(f"{field.name} = {_toml_value(field.name, value)}")
        for field in dataclasses.fields(self):
            table = getattr(self, field.name)
            if not dataclasses.is_dataclass(table):
                continue
            lines.append(f"\n[{field.name}]")
            for key in dataclasses.fields(table):
                value = getattr(table, key.name)
                if value is not None:
                    name = f"{field.name}.{key.name}"
                    lines.append(f"{key.name} = {_toml_value(name, value)}")
        return "\n".join(lines) + "\n"


#: The class of each table of a scene.
_TABLES: dict[str, type] = {
    "band": Band,
    "surface": Surface,
    "target": SceneObject,
    "background": SceneObject,
    "sun": Sun,
    "sky": Sky,
    "atmosphere": Atmosphere,
    "path": PathToSensor,
}


def _toml_value(name: str, value: object) -> str:
    """A TOML value: a string (a path as its text), a number, or an array of numbers. What the
    value means is the reader's to check."""
    if isinstance(value, (str, os.PathLike)):
        return json.dumps(os.fspath(value), ensure_ascii=False)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, Sequence):
        return "[" + ", ".join(_toml_value(name, v) for v in value) + "]"
    try:
        x = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise TypeError(
            f"scene key `{name}`: expected a number, a string or a sequence of numbers, got "
            f"{type(value).__name__}"
        ) from None
    return repr(x) if math.isfinite(x) else {math.inf: "inf", -math.inf: "-inf"}.get(x, "nan")
