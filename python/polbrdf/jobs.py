"""More jobs of the command line, from Python: the validity check (:func:`check`), ``.pbsdf``
tables (:func:`export_pbsdf`, :func:`read_pbsdf`, :func:`fit_pbsdf`) and the measurement CSV
``polbrdf fit`` reads (:func:`read_measurements`, :func:`fit_measurements`); the band emissivity
of :func:`polbrdf.emissivity` comes through here too.

Each is one call of the task layer (the Rust crate ``polbrdf-tasks``) that ``polbrdf check``,
``polbrdf export``, ``polbrdf fit`` and ``polbrdf emission`` call: the same validation, the same
messages (a ``ValueError`` naming the keyword, also as the exception's ``argument``), the same
numbers bit for bit.
"""

from __future__ import annotations

import json
import os
from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from . import _polbrdf
from ._polbrdf import FitResult, Material
from .tasks import PathName, _spectral

__all__ = [
    "CheckReport",
    "Measurements",
    "PbsdfTable",
    "check",
    "export_pbsdf",
    "fit_measurements",
    "fit_pbsdf",
    "read_measurements",
    "read_pbsdf",
]

_F64 = NDArray[np.float64]


def _material(value: Material | PathName) -> Material | str:
    """A ``Material``, or a material file or preset name as text."""
    if isinstance(value, Material):
        return value
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    raise TypeError(
        "`material` must be a polbrdf.Material, a material file or a preset name, not "
        f"{type(value).__name__}"
    )


def _free(free: str | Sequence[str]) -> list[str]:
    if isinstance(free, str):
        return [f.strip() for f in free.split(",") if f.strip()]
    return [str(f) for f in free]


class CheckReport(NamedTuple):
    """The result of :func:`check`: ``material`` (its name), ``passes`` (every check at every
    spectral node), ``geometries`` (of the grid), ``nodes`` (one dict per spectral node:
    ``wavelength_um``, ``passes``, ``realizable`` with ``min_coherency`` — the smallest
    coherency eigenvalue over F00 — and where (``min_coherency_at_deg``: θi, φi, θr, φr),
    ``conserves_energy`` with the ``albedo`` at θi = 0°, 5°, …, 85°, ``reciprocity_expected``,
    ``reciprocal``, ``reciprocity_scalar``, ``reciprocity_matrix`` and where) and ``document``:
    the whole document ``polbrdf check --output`` writes."""

    material: str
    passes: bool
    geometries: int
    nodes: list[dict[str, Any]]
    document: dict[str, Any]


def check(
    material: Material | PathName,
    *,
    grid_deg: float | None = None,
    wavelength_um: float | None = None,
    band: PathName | None = None,
    band_step_um: float | None = None,
) -> CheckReport:
    """Physical validity of a parameter set: ``polbrdf check``.

    F realizable (coherency matrix positive semidefinite) over a grid of zenith step
    ``grid_deg`` (degrees in (0, 30], the relative azimuth twice that; ``None``: 5°, the CLI's
    default; at most 2·10⁶ geometries, a step of about 0.9°), the albedo ≤ 1 at every incidence
    angle, and reciprocity where the model form has it — at one wavelength or at every node of a
    band (the spectral keywords as :func:`polbrdf.contrast`'s). ``material`` is a
    :class:`Material`, a material file or a preset name.

    Raises ``ValueError`` naming the keyword for a bad argument (also as ``argument``), naming
    file, line and key for a bad file.
    """
    doc = json.loads(
        _polbrdf.check_task(
            _material(material),
            None if grid_deg is None else float(grid_deg),
            _spectral(wavelength_um, band, band_step_um),
        )
    )
    return CheckReport(doc["material"], doc["passes"], doc["geometries"], doc["nodes"], doc)


def _band_emission(
    material: Material,
    theta_deg: NDArray[np.float64],
    temperature_k: float | None,
    band: PathName | None,
    band_step_um: float | None,
) -> tuple[Any, ...]:
    """The emissivity at the flat view angles ``theta_deg`` over a band (``polbrdf emission
    --band``): the task's columns but the angles."""
    _, *columns = _polbrdf.emission_task(
        material,
        [float(t) for t in theta_deg],
        None if temperature_k is None else float(temperature_k),
        _spectral(None, band, band_step_um),
    )
    return tuple(columns)


def export_pbsdf(
    material: Material | PathName,
    path: PathName,
    *,
    bands_nm: Sequence[int] | None = None,
    grid: Sequence[int] | None = None,
) -> int:
    """Write a material as a Mitsuba 3 ``measured_polarized`` table (``.pbsdf``, docs/model.md
    §20): ``polbrdf export``, the same file byte for byte.

    ``bands_nm``: the band wavelengths in nm (integers, increasing; Mitsuba's plugin reads
    exactly five; ``None``: 450, 500, 550, 600, 650). ``grid``: nodes along φ_d, θ_d, θ_h (each
    2–4096, the table at most 4 GiB; ``None``: 37, 46, 91). The file is written atomically
    through the project's output layer. Returns the bytes of the matrices.
    """
    bands = None if bands_nm is None else [int(b) for b in bands_nm]
    nodes = None
    if grid is not None:
        g = [int(n) for n in grid]
        if len(g) != 3:
            e = ValueError(f"invalid `grid`: three node counts P, D, H are required, got {len(g)}")
            e.argument = "grid"  # type: ignore[attr-defined]
            raise e
        nodes = (g[0], g[1], g[2])
    out: int = _polbrdf.export_pbsdf_task(_material(material), os.fspath(path), bands, nodes)
    return out


class PbsdfTable(NamedTuple):
    """A ``.pbsdf`` table (:func:`read_pbsdf`): the axes ``phi_d``, ``theta_d``, ``theta_h``
    (radians, as stored), the band wavelengths ``wavelengths_nm`` and the matrices ``M`` of
    shape ``(P, D, H, bands, 4, 4)`` (float32, Mitsuba's plane-of-reflection frame, as
    stored)."""

    phi_d: _F64
    theta_d: _F64
    theta_h: _F64
    wavelengths_nm: list[int]
    M: NDArray[np.float32]


def read_pbsdf(path: PathName) -> PbsdfTable:
    """Read a ``.pbsdf`` table by the reader ``polbrdf fit`` uses (header and axes checked, a
    ``ValueError`` naming the file and the field for a defect); the memory is that of the data
    the file holds."""
    phi_d, theta_d, theta_h, bands, m = _polbrdf.read_pbsdf_task(os.fspath(path))
    return PbsdfTable(phi_d, theta_d, theta_h, list(bands), m)


def fit_pbsdf(
    material: Material | PathName,
    path: PathName,
    free: str | Sequence[str],
    *,
    subsample: int | None = None,
    starts: int = 2,
    seed: int = 1,
    exclude_inadmissible: bool = False,
) -> dict[str, Any]:
    """Fit a measured ``.pbsdf`` table band by band: ``polbrdf fit --data table.pbsdf``.

    ``material`` gives the start values and the fixed parameters; ``free`` the parameters to
    fit (as :func:`polbrdf.fit`'s). ``subsample`` keeps every N-th node along each axis
    (``None``: the smallest N keeping at most 20 000 cells); ``starts`` extra starts with
    ``seed``; ``exclude_inadmissible`` leaves out cells whose matrix is not physically
    realizable. Returns the document ``fit.json`` holds (``per_band``: one fit per band), equal
    to the CLI's.
    """
    doc: dict[str, Any] = json.loads(
        _polbrdf.fit_pbsdf_task(
            _material(material),
            os.fspath(path),
            _free(free),
            None if subsample is None else int(subsample),
            int(starts),
            int(seed),
            bool(exclude_inadmissible),
        )
    )
    return doc


class Measurements(NamedTuple):
    """A measurement CSV (:func:`read_measurements`): ``theta_i``, ``phi_i``, ``theta_r``,
    ``phi_r`` in **radians** (the geometries ``polbrdf fit`` fits; pass ``degrees=False`` to
    :func:`polbrdf.fit`), ``data`` (measured column → values, NaN where a row leaves the cell
    empty), ``sigma`` (column → 1-σ uncertainties, for the columns with ``sigma_<column>``),
    ``wavelength_um`` (``None`` without the column) and ``lines`` (the file's line of each
    row)."""

    theta_i: _F64
    phi_i: _F64
    theta_r: _F64
    phi_r: _F64
    data: dict[str, _F64]
    sigma: dict[str, _F64]
    wavelength_um: _F64 | None
    lines: list[int]


def read_measurements(path: PathName) -> Measurements:
    """Read a measurement CSV by the reader ``polbrdf fit --data`` uses (the four angle columns
    in degrees, optionally ``wavelength_um``, measured columns ``brdf``, ``dolp``, ``brdf_s``,
    ``brdf_p``, ``m00`` … ``m33``, each with an optional ``sigma_<column>``), checked as the fit
    checks it: a ``ValueError`` naming file, line and column for a defect."""
    lines, angles, names, values, sigmas, wavelengths = _polbrdf.read_measurements_task(
        os.fspath(path)
    )
    data = dict(zip(names, values))
    sigma = {n: s for n, s in zip(names, sigmas) if s is not None}
    return Measurements(*angles, data, sigma, wavelengths, list(lines))


def fit_measurements(
    material: Material,
    path: PathName,
    free: str | Sequence[str],
    *,
    starts: int = 2,
    seed: int = 1,
) -> FitResult:
    """Fit the measurement CSV ``path`` as ``polbrdf fit --data path --free …`` does — the same
    reader, the measurements in file order, the same fit — so the result equals the CLI's
    ``fit.json`` bit for bit. ``material`` gives the start values and the fixed parameters."""
    if not isinstance(material, Material):
        raise TypeError(f"`material` must be a polbrdf.Material, not {type(material).__name__}")
    return _polbrdf.fit_measurements_task(
        material, os.fspath(path), _free(free), int(starts), int(seed)
    )
