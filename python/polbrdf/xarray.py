"""Lookup tables of the pBRDF as labelled arrays: ``polbrdf.lut`` (needs ``polbrdf[xarray]``).

A table covers materials × wavelengths × in-plane geometries ``(theta_i, theta_r, dphi)``; it is
an :class:`xarray.Dataset`, computed at once (``chunks=None``) or lazily with dask
(``chunks=...``), where each chunk is one call of the engine (the GIL released) — so that a
``dask.distributed`` cluster computes it as well as the threads of one process. Write it with
``Dataset.to_zarr`` / ``Dataset.to_netcdf``; read it back with ``xarray.open_zarr`` /
``xarray.open_dataset`` and interpolate with ``Dataset.interp``. See ``docs/scaling.md``.

Geometry (docs/model.md §1): the source is at azimuth ``phi_i = 0`` and the detector at
``phi_r = dphi`` (``dphi = φr − φi``); ``dphi = 180°`` is the specular (forward) half of the
plane of incidence, ``dphi = 0`` the backscatter half. The model is isotropic, so these three
angles and the wavelength are all a table needs.

Every value is that of a direct call: ``ds.mueller.sel(material=name)`` equals
``polbrdf.mueller(m, ti, 0, tr, dphi, wavelength_um=wl)`` on the broadcast coordinates, bit for
bit, whatever the chunks.

This module imports xarray (and dask when chunked); ``import polbrdf`` does not.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

import polbrdf
from polbrdf import FitResult, Material, _polbrdf

__all__ = ["CONTRAST", "QUANTITIES", "lut", "open_lut"]

#: Per-material quantities of a table (unpolarized illumination for the scalars): the
#: extension's ``vocabulary()["lut_quantity"]``, as ``polbrdf lut`` spells them.
QUANTITIES = tuple(_polbrdf.vocabulary()["lut_quantity"])
#: The Mueller columns ``m00 … m33`` of a table, row-major (the core's one list).
_MUELLER_COLUMNS = _polbrdf.vocabulary()["mueller_column"]
#: Target-against-background quantities (docs/model.md §11), from the brdf and dolp variables.
CONTRAST = ("delta_dolp", "intensity_ratio")

_GEOMETRY = ("wavelength", "theta_i", "theta_r", "dphi")
_DIMS = ("material", *_GEOMETRY)

#: The attributes that pin the conventions, shared with ``polbrdf lut`` (one file, owned by the
#: task layer and compiled into the extension): basis, S3 sign, directions, azimuth, units, model.
_CONVENTIONS: dict[str, str] = json.loads(_polbrdf.LUT_CONVENTIONS)

_VARIABLE_ATTRS = {
    "mueller": {"units": "sr-1", "long_name": "pBRDF (Mueller-matrix BRDF), psps basis"},
    "brdf": {"units": "sr-1", "long_name": "scalar BRDF F00"},
    "dolp": {"units": "1", "long_name": "degree of linear polarization, unpolarized input"},
    "aolp": {"units": "degree", "long_name": "angle of linear polarization, from s toward p"},
    "delta_dolp": {"units": "1", "long_name": "DoLP(target) - DoLP(background)"},
    "intensity_ratio": {"units": "1", "long_name": "BRDF(target) / BRDF(background)"},
}

_COORD_ATTRS = {
    "wavelength": {"units": "um", "long_name": "vacuum wavelength"},
    "theta_i": {"units": "degree", "long_name": "zenith angle of the direction to the source"},
    "theta_r": {"units": "degree", "long_name": "zenith angle of the direction to the detector"},
    "dphi": {"units": "degree", "long_name": "azimuth difference phi_r - phi_i"},
    "row": {"long_name": "Mueller matrix row (output Stokes component)"},
    "col": {"long_name": "Mueller matrix column (input Stokes component)"},
}


# --- inputs --------------------------------------------------------------------------------


def _materials(materials: Material | Sequence[Material] | Mapping[str, Material]) -> dict:
    """Names → materials, in order: the mapping's keys, else each material's name, else
    ``material<i>``."""
    if isinstance(materials, Material):
        materials = [materials]
    if isinstance(materials, Mapping):
        items = [(str(k), v) for k, v in materials.items()]
    elif isinstance(materials, Sequence) and not isinstance(materials, (str, bytes)):
        items = [(m.name if isinstance(m, Material) and m.name else f"material{i}", m)
                 for i, m in enumerate(materials)]  # fmt: skip
    else:
        raise TypeError(
            "`materials` must be a polbrdf.Material, a sequence of them or a mapping "
            f"name -> Material, not {type(materials).__name__}"
        )
    out: dict[str, Material] = {}
    for name, m in items:
        if not isinstance(m, Material):
            raise TypeError(f"material {name!r} is a {type(m).__name__}, not a polbrdf.Material")
        if name in out:
            raise ValueError(
                f"two materials are named {name!r}: give a mapping name -> Material with "
                "distinct names"
            )
        out[name] = m
    if not out:
        raise ValueError("`materials` is empty")
    return out


def _axis(name: str, values: ArrayLike, lo: float, hi: float | None) -> NDArray[np.float64]:
    """A table axis: 1-D, finite, strictly increasing, within [lo, hi] (or > lo for hi=None)."""
    arr = np.asarray(values)
    if arr.dtype.kind not in "biuf":
        raise TypeError(f"`{name}` must hold real numbers, got dtype {arr.dtype}")
    arr = np.atleast_1d(arr.astype(np.float64))
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(f"`{name}` must be a non-empty 1-D array, got shape {arr.shape}")
    bad = ~np.isfinite(arr) | (arr < lo) | ((arr > hi) if hi is not None else (arr <= lo))
    if bad.any():
        i = int(np.argmax(bad))
        where = f"in [{lo}, {hi}]" if hi is not None else f"> {lo}"
        raise ValueError(f"`{name}`[{i}] = {arr[i]} must be finite and {where}")
    if arr.size > 1 and not (np.diff(arr) > 0).all():
        i = int(np.argmax(~(np.diff(arr) > 0)))
        raise ValueError(
            f"`{name}` must be strictly increasing (a table axis): [{i}] = {arr[i]}, "
            f"[{i + 1}] = {arr[i + 1]}"
        )
    return np.ascontiguousarray(arr)


def _chunks(chunks: int | Mapping[str, int] | None, sizes: dict[str, int]) -> dict | None:
    """Chunk sizes per geometry dimension (the material dimension always has chunks of one)."""
    if chunks is None:
        return None
    if isinstance(chunks, (int, np.integer)) and not isinstance(chunks, bool):
        chunks = {d: int(chunks) for d in _GEOMETRY}
    if not isinstance(chunks, Mapping):
        raise TypeError("`chunks` must be None, an int or a mapping dimension -> int")
    unknown = set(chunks) - set(_DIMS)
    if unknown:
        raise ValueError(f"`chunks`: unknown dimension(s) {sorted(unknown)}; known: {_DIMS}")
    out = {}
    for d in _GEOMETRY:
        c = chunks.get(d, sizes[d])
        c = sizes[d] if c == -1 else c
        if not isinstance(c, (int, np.integer)) or isinstance(c, bool) or c < 1:
            raise ValueError(f"`chunks[{d!r}]` must be a positive int (or -1: whole), got {c!r}")
        out[d] = min(int(c), sizes[d])
    if chunks.get("material", 1) not in (1, -1):
        raise ValueError("`chunks['material']` must be 1: each material is its own engine call")
    return out


def _with(material: Material, name: str, value: float) -> Material:
    """``material`` with parameter ``name`` set to ``value`` (as the fit sets it: sigma_deg
    and b replace each other)."""
    d = material.to_dict()
    d[name] = value
    if name == "sigma_deg":
        d["b"] = None
    elif name == "b":
        d["sigma_deg"] = None
    return Material(**d)


def _covariance(name: str, material: Material, source: Any) -> dict[str, Any]:
    """The parameters, values and covariance of ``material`` from a :class:`FitResult`, a
    ``fit.json`` path (``polbrdf fit --output``) or a pair ``(names, covariance)``; parameters
    whose covariance is undefined (at a bound: NaN, ``null`` in fit.json) are left out (held
    fixed) and listed. The material's own values must be the fitted ones."""
    origin = "FitResult"
    if isinstance(source, FitResult):
        names, values = list(source.names), np.asarray(source.values, dtype=np.float64)
        cov = np.asarray(source.covariance, dtype=np.float64)
    elif isinstance(source, (str, os.PathLike)):
        origin = os.fspath(source)
        try:
            with open(source, encoding="utf-8") as f:
                doc = json.load(f)
        except json.JSONDecodeError as e:
            raise ValueError(f"{origin}:{e.lineno}:{e.colno}: not valid JSON: {e.msg}") from None
        try:
            names = [str(n) for n in doc["parameter_order"]]
            values = np.array([doc["parameters"][n]["value"] for n in names], dtype=np.float64)
            cov = np.array(
                [[math.nan if v is None else v for v in row] for row in doc["covariance"]],
                dtype=np.float64,
            )
        except (KeyError, TypeError, ValueError) as e:
            raise ValueError(
                f"{origin}: not a fit.json of `polbrdf fit` (needs `parameter_order`, "
                f"`parameters.<name>.value` and `covariance`): {type(e).__name__}: {e}"
            ) from None
    elif isinstance(source, Sequence) and len(source) == 2:
        origin = "(names, covariance)"
        names = [str(n) for n in source[0]]
        cov = np.asarray(source[1], dtype=np.float64)
        d = material.to_dict()
        values = np.array([d.get(n) if d.get(n) is not None else math.nan for n in names])
    else:
        raise TypeError(
            f"covariance of {name!r} must be a FitResult, the path of a fit.json or a pair "
            f"(names, covariance), not {type(source).__name__}"
        )
    p = len(names)
    if cov.shape != (p, p):
        raise ValueError(f"{origin}: covariance of shape {cov.shape} for {p} parameter(s)")
    d = material.to_dict()
    for n, v in zip(names, values):
        _polbrdf.derivative_step(n, 0.0)  # names a fit parameter (raises otherwise)
        mine = d.get(n)
        if mine is None or not math.isfinite(v) or abs(mine - v) > 1e-12 * max(abs(v), 1.0):
            raise ValueError(
                f"{origin}: parameter `{n}` = {v} of the fit, but material {name!r} has "
                f"`{n}` = {mine}: give the fitted material (FitResult.material or "
                "`polbrdf fit --material-out`)"
            )
    keep = [j for j in range(p) if np.isfinite(cov[j]).all() and np.isfinite(cov[:, j]).all()]
    return {
        "names": [names[j] for j in keep],
        "values": [float(values[j]) for j in keep],
        "covariance": cov[np.ix_(keep, keep)].tolist(),
        "held_fixed": [names[j] for j in range(p) if j not in keep],
        "source": origin,
    }


# --- the kernel: one engine call per block -------------------------------------------------


def _components(quantities: Sequence[str]) -> list[tuple[str, slice]]:
    """The packed layout of a block's last axis: (quantity, slice)."""
    out, at = [], 0
    for q in QUANTITIES:
        if q in quantities:
            width = 16 if q == "mueller" else 1
            out.append((q, slice(at, at + width)))
            at += width
    return out


def _engine(
    material: Material, coords: Sequence[NDArray[np.float64]], layout: list[tuple[str, slice]]
) -> NDArray[np.float64]:
    """The rows of the grid ``coords = (wavelength, theta_i, theta_r, dphi)`` by the task layer
    (``polbrdf_tasks::lut``, the rows ``polbrdf lut`` writes; the GIL released): the quantities
    packed along a last axis of ``(W, I, R, P, C)``."""
    wl, ti, tr, dp = coords
    shape = (len(wl), len(ti), len(tr), len(dp))
    rows = _polbrdf.lut_rows(
        material, wl.tolist(), ti.tolist(), tr.tolist(), dp.tolist(), [q for q, _ in layout]
    )
    return rows.reshape(shape + (layout[-1][1].stop,))


def _block(
    material: Material,
    coords: Sequence[NDArray[np.float64]],
    layout: list[tuple[str, slice]],
    unc: dict[str, Any] | None,
) -> NDArray[np.float64]:
    """The packed values of a block, and with ``unc`` their standard errors after them
    (``(W, I, R, P, 2C)``): linear propagation ``σ² = J Σ Jᵀ`` with ``J`` the central
    differences of the engine output in the fitted (natural) parameters, stepped as the fit
    steps (``polbrdf_fit::Param::derivative_step``); one engine call per perturbed set."""
    value = _engine(material, coords, layout)
    if unc is None:
        return value
    names, x, cov = unc["names"], unc["values"], np.asarray(unc["covariance"])
    jac = []
    for n, xj in zip(names, x):
        h = _polbrdf.derivative_step(n, xj)
        plus = _engine(_with(material, n, xj + h), coords, layout)
        if xj - h > 0.0:
            minus, step = _engine(_with(material, n, xj - h), coords, layout), 2.0 * h
        else:  # at the domain's edge: forward difference, as the fit does
            minus, step = value, h
        jac.append((plus - minus) / step)
    var = np.zeros_like(value)
    for a, ja in enumerate(jac):
        for b, jb in enumerate(jac):
            if cov[a, b] != 0.0:
                var += cov[a, b] * ja * jb
    return np.concatenate([value, np.sqrt(np.maximum(var, 0.0))], axis=-1)


def _lazy(
    material: Material,
    coords: Sequence[NDArray[np.float64]],
    chunks: dict[str, int],
    layout: list[tuple[str, slice]],
    unc: dict[str, Any] | None,
) -> Any:
    import dask.array as da

    width = layout[-1][1].stop * (1 if unc is None else 2)
    sizes = [len(c) for c in coords]
    normal = da.core.normalize_chunks(
        tuple(chunks[d] for d in _GEOMETRY) + (width,), tuple(sizes) + (width,)
    )

    def block(block_info: dict | None = None) -> NDArray[np.float64]:
        loc = block_info[None]["array-location"]  # type: ignore[index]
        part = [c[a:b] for c, (a, b) in zip(coords, loc[:4])]
        return _block(material, part, layout, unc)

    return da.map_blocks(block, chunks=normal, dtype=np.float64, meta=np.empty((0,) * 5))


# --- the table -----------------------------------------------------------------------------


def lut(
    materials: Material | Sequence[Material] | Mapping[str, Material],
    wavelength_um: ArrayLike,
    theta_i: ArrayLike,
    theta_r: ArrayLike,
    dphi: ArrayLike,
    *,
    quantities: Sequence[str] = ("mueller", "brdf", "dolp"),
    chunks: int | Mapping[str, int] | None = None,
    covariance: Mapping[str, Any] | None = None,
    contrast: tuple[str, str] | None = None,
) -> xr.Dataset:
    """A lookup table of the pBRDF over materials × wavelengths × in-plane geometries.

    Parameters
    ----------
    materials : Material, sequence of Material, or mapping name -> Material
        The ``material`` coordinate (strings): the mapping's keys, else each material's
        ``name``, else ``material<i>``; names must be distinct.
    wavelength_um : array_like
        Vacuum wavelengths in µm (1-D, strictly increasing, > 0): a spectral index is
        evaluated there; a constant index does not depend on it (give one wavelength).
    theta_i, theta_r, dphi : array_like
        Zenith angles of the directions to the source and to the detector, in [0°, 180°], and
        the azimuth difference ``dphi = φr − φi`` in degrees; 1-D, strictly increasing.
    quantities : sequence of str
        Any of ``"mueller"`` (dims ``material, wavelength, theta_i, theta_r, dphi, row, col``),
        ``"brdf"``, ``"dolp"``, ``"aolp"`` (dims without ``row, col``).
    chunks : int or mapping dim -> int, optional
        ``None``: computed now (NumPy). Otherwise a lazy dask-backed dataset with these chunk
        sizes along ``wavelength, theta_i, theta_r, dphi`` (an int: all four; a missing or -1
        entry: the whole axis); the material dimension has chunks of 1. Every chunk is one
        engine call (and ``2p`` more with ``covariance``), the GIL released.
    covariance : mapping name -> FitResult | fit.json path | (names, covariance), optional
        Fitted materials: adds ``<q>_stderr`` for every quantity — the standard error by linear
        propagation ``σ_q² = J Σ Jᵀ`` through the engine's Jacobian in the fitted parameters
        (central differences with the fit's steps). Materials not in the mapping get NaN. The
        material given must carry the fitted values.
    contrast : (target, background), optional
        Adds ``delta_dolp = dolp_t − dolp_b`` and ``intensity_ratio = brdf_t / brdf_b`` (1 when
        both are 0, +inf when only the background is) over the geometry dims, as
        ``polbrdf contrast`` defines them (docs/model.md §11), and with ``covariance`` their
        standard errors, the two fits taken as independent.

    Returns
    -------
    xarray.Dataset
        Coordinates in degrees and µm, attributes pinning the conventions (basis, S3 sign,
        directions, azimuth, units), the materials' parameters (``materials_json``), the
        uncertainty inputs (``uncertainty_json``) and ``polbrdf_version``.
    """
    req = _request(
        materials, wavelength_um, theta_i, theta_r, dphi, quantities, chunks, covariance, contrast
    )
    # The contrast needs brdf and dolp: computed when not asked for, and dropped below.
    for_contrast = [q for q in ("brdf", "dolp") if contrast and q not in req.quantities]
    layout = _components(req.quantities + for_contrast)
    ds = _dataset(req, layout, _packed(req, layout))
    if contrast is not None:
        _add_contrast(ds, contrast, bool(req.unc))
    qs = req.quantities
    ds = ds[[v for v in ds.data_vars if v.removesuffix("_stderr") in qs or v.startswith(CONTRAST)]]
    ds.attrs.update(_CONVENTIONS)
    ds.attrs["polbrdf_version"] = polbrdf.__version__
    ds.attrs["materials_json"] = json.dumps(
        {n: m.to_dict() for n, m in req.mats.items()}, ensure_ascii=False
    )
    if req.unc:
        ds.attrs["uncertainty_json"] = json.dumps(req.unc, ensure_ascii=False)
    return ds


class _Request(NamedTuple):
    """The arguments of :func:`lut`, checked and normalized."""

    #: Names → materials (:func:`_materials`).
    mats: dict[str, Material]
    #: The quantities asked for, without repeats, in the order given.
    quantities: list[str]
    #: The axes ``(wavelength, theta_i, theta_r, dphi)`` (:func:`_axis`).
    coords: tuple[NDArray[np.float64], ...]
    #: The length of each geometry dimension.
    sizes: dict[str, int]
    #: Chunk sizes per geometry dimension, ``None`` to compute at once (:func:`_chunks`).
    chunk: dict[str, int] | None
    #: The uncertainty inputs per material given a covariance (:func:`_covariance`).
    unc: dict[str, dict[str, Any]]


def _request(
    materials: Material | Sequence[Material] | Mapping[str, Material],
    wavelength_um: ArrayLike,
    theta_i: ArrayLike,
    theta_r: ArrayLike,
    dphi: ArrayLike,
    quantities: Sequence[str],
    chunks: int | Mapping[str, int] | None,
    covariance: Mapping[str, Any] | None,
    contrast: tuple[str, str] | None,
) -> _Request:
    """The arguments of :func:`lut` checked and normalized, raising on the first bad one in
    this order: materials, quantities, axes, chunks, every wavelength inside each material's
    index data, the contrast pair, the covariances."""
    mats = _materials(materials)
    qs = list(dict.fromkeys(quantities))
    unknown = [q for q in qs if q not in QUANTITIES]
    if unknown or not qs:
        raise ValueError(f"unknown quantities {unknown}; choose from {QUANTITIES}")
    coords = (
        _axis("wavelength_um", wavelength_um, 0.0, None),
        _axis("theta_i", theta_i, 0.0, 180.0),
        _axis("theta_r", theta_r, 0.0, 180.0),
        _axis("dphi", dphi, -math.inf, math.inf),
    )
    sizes = dict(zip(_GEOMETRY, (len(c) for c in coords)))
    chunk = _chunks(chunks, sizes)
    for name, m in mats.items():  # a wavelength outside an index's data: refused now
        try:
            polbrdf.index(m, coords[0])
        except ValueError as e:
            raise ValueError(f"material {name!r}: {e}") from None
    if contrast is not None and (len(contrast) != 2 or any(c not in mats for c in contrast)):
        raise ValueError(
            f"`contrast` must name two of the materials {list(mats)}, got {contrast!r}"
        )
    covariance = dict(covariance or {})
    extra = set(covariance) - set(mats)
    if extra:
        raise ValueError(f"`covariance` names unknown material(s) {sorted(extra)}")
    unc = {n: _covariance(n, mats[n], s) for n, s in covariance.items()}
    return _Request(mats, qs, coords, sizes, chunk, unc)


def _packed(req: _Request, layout: list[tuple[str, slice]]) -> Any:
    """The values of every material stacked along a first axis, ``(M, W, I, R, P, C)``, with
    their standard errors after them along the last (``2C``) when any material has a
    covariance (NaN for those without): a NumPy array, or a dask array when chunked."""
    per_material = []
    for name, m in req.mats.items():
        u = req.unc.get(name)
        if req.chunk is None:
            a = _block(m, req.coords, layout, u)
        else:
            a = _lazy(m, req.coords, req.chunk, layout, u)
        if req.unc and u is None:  # NaN standard errors for a material without covariance
            if req.chunk is None:
                a = np.concatenate([a, np.full_like(a, np.nan)], axis=-1)
            else:
                import dask.array as da

                a = da.concatenate([a, da.full_like(a, np.nan)], axis=-1)
        per_material.append(a)
    if req.chunk is None:
        return np.stack(per_material)
    import dask.array as da

    return da.stack(per_material)


def _dataset(req: _Request, layout: list[tuple[str, slice]], packed: Any) -> xr.Dataset:
    """The Dataset of the ``packed`` values: one variable per quantity of ``layout`` (and its
    ``_stderr`` when any material has a covariance), with their attributes, and the
    coordinates in degrees and µm."""
    width = layout[-1][1].stop
    shape = (len(req.mats), *req.sizes.values())
    data_vars = {}
    for q, s in layout:
        for suffix, offset in [("", 0)] + ([("_stderr", width)] if req.unc else []):
            v = packed[..., s.start + offset : s.stop + offset]
            attrs = dict(_VARIABLE_ATTRS[q])
            if suffix:
                attrs["long_name"] = "standard error of " + attrs["long_name"]
                attrs["method"] = "linear propagation J Sigma J^T, central differences"
            if q == "mueller":
                data_vars[q + suffix] = (_DIMS + ("row", "col"), v.reshape(shape + (4, 4)), attrs)
            else:
                data_vars[q + suffix] = (_DIMS, v.reshape(shape), attrs)
    coords = req.coords
    return xr.Dataset(
        data_vars,
        coords={
            # variable-length strings: netCDF's string type, Zarr v3's stable "string" dtype
            "material": np.array(list(req.mats), dtype=object),
            "wavelength": ("wavelength", coords[0], _COORD_ATTRS["wavelength"]),
            "theta_i": ("theta_i", coords[1], _COORD_ATTRS["theta_i"]),
            "theta_r": ("theta_r", coords[2], _COORD_ATTRS["theta_r"]),
            "dphi": ("dphi", coords[3], _COORD_ATTRS["dphi"]),
            "row": ("row", np.arange(4), _COORD_ATTRS["row"]),
            "col": ("col", np.arange(4), _COORD_ATTRS["col"]),
        },
    )


def _add_contrast(ds: xr.Dataset, pair: tuple[str, str], with_stderr: bool) -> None:
    """The contrast variables of ``pair = (target, background)`` (docs/model.md §11)."""
    t, b = (ds.sel(material=n, drop=True) for n in pair)
    zero_b, zero_t = b.brdf == 0.0, t.brdf == 0.0
    ratio = xr.where(zero_b, xr.where(zero_t, 1.0, np.inf), t.brdf / b.brdf.where(~zero_b))
    ds["delta_dolp"] = t.dolp - b.dolp
    ds["intensity_ratio"] = ratio
    if with_stderr:
        ds["delta_dolp_stderr"] = np.hypot(t.dolp_stderr, b.dolp_stderr)
        rel = np.hypot(t.brdf_stderr / t.brdf, b.brdf_stderr / b.brdf)
        ds["intensity_ratio_stderr"] = (abs(ratio) * rel).where(~zero_t & ~zero_b)
    for v in ("delta_dolp", "intensity_ratio"):
        ds[v].attrs = dict(_VARIABLE_ATTRS[v], target=pair[0], background=pair[1])
        if with_stderr:
            ds[v + "_stderr"].attrs = {
                "units": "1",
                "long_name": "standard error of " + _VARIABLE_ATTRS[v]["long_name"],
                "method": "linear propagation, target and background fits independent",
            }


# --- tables of the command line ------------------------------------------------------------


#: The most bytes of ``attrs.json`` read (as the CLI's bound on files read whole).
_MAX_SIDECAR_BYTES = 16 << 20


def _sidecar_json(meta_path: Path) -> Any:
    """``attrs.json``, parsed: at most 16 MiB, valid JSON of bounded nesting."""
    with open(meta_path, "rb") as f:
        raw = f.read(_MAX_SIDECAR_BYTES + 1)
    if len(raw) > _MAX_SIDECAR_BYTES:
        raise ValueError(f"{meta_path}: longer than 16 MiB: not a polbrdf lut sidecar")
    try:
        return json.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as e:
        raise ValueError(f"{meta_path}: not UTF-8 text ({e.reason})") from None
    except json.JSONDecodeError as e:
        raise ValueError(f"{meta_path}:{e.lineno}:{e.colno}: not valid JSON: {e.msg}") from None
    except RecursionError:
        raise ValueError(f"{meta_path}: JSON nested too deeply: not a polbrdf lut sidecar") from None


def _sidecar_bad(meta_path: Path, key: str, what: str) -> ValueError:
    return ValueError(f"{meta_path}: not a polbrdf lut sidecar: `{key}` {what}")


def _sidecar_coords(meta_path: Path, coords: Any, dims: list[str]) -> dict[str, list]:
    """The coordinates: material names (distinct strings), each geometry axis finite and
    strictly increasing."""
    if not isinstance(coords, dict) or any(d not in coords for d in dims):
        raise _sidecar_bad(meta_path, "coords", f"must map each of {dims} to a list")
    names = coords["material"]
    if not (isinstance(names, list) and all(isinstance(n, str) for n in names)):
        raise _sidecar_bad(meta_path, "coords.material", "must be a list of names")
    if len(set(names)) != len(names):
        raise _sidecar_bad(meta_path, "coords.material", "names a material twice")
    out: dict[str, list] = {"material": names}
    for d in _GEOMETRY:
        v = coords[d]
        ok = isinstance(v, list) and all(
            isinstance(x, (int, float)) and not isinstance(x, bool) for x in v
        )
        if not ok:
            raise _sidecar_bad(meta_path, f"coords.{d}", "must be a list of numbers")
        a = np.asarray(v, dtype=np.float64)
        if not np.all(np.isfinite(a)):
            raise _sidecar_bad(meta_path, f"coords.{d}", "holds a value that is not finite")
        if np.any(np.diff(a) <= 0):
            raise _sidecar_bad(meta_path, f"coords.{d}", "must increase strictly")
        out[d] = v
    return out


def _sidecar_table(meta_path: Path, folder: Path, name: Any) -> Path:
    """The table file ``attrs.json`` names: a plain file name inside the folder."""
    if not isinstance(name, str) or name in ("", ".", "..") or Path(name).name != name:
        raise _sidecar_bad(meta_path, "table", "must name a file inside the folder")
    return folder / name


def _read_sidecar(folder: Path, meta_path: Path) -> tuple:
    """``attrs.json``, checked: each key of the type and range ``polbrdf lut`` writes, else a
    ``ValueError`` naming the file and the key."""
    meta = _sidecar_json(meta_path)
    if not isinstance(meta, dict):  # a bad file, not a bad argument: ValueError, as documented
        raise ValueError(f"{meta_path}: not a polbrdf lut sidecar: not a JSON object")  # noqa: TRY004
    for key in ("format", "dims", "shape", "columns", "coords", "attrs", "quantities", "table"):
        if key not in meta:
            raise _sidecar_bad(meta_path, key, "is missing")
    if meta["format"] != "polbrdf-lut 1":
        raise _sidecar_bad(meta_path, "format", f"is {meta['format']!r}, not 'polbrdf-lut 1'")
    dims, shape = meta["dims"], meta["shape"]
    if dims != list(_DIMS):
        raise _sidecar_bad(meta_path, "dims", f"must be {list(_DIMS)}")
    if not (
        isinstance(shape, list)
        and len(shape) == len(_DIMS)
        and all(isinstance(n, int) and not isinstance(n, bool) and n >= 1 for n in shape)
    ):
        raise _sidecar_bad(meta_path, "shape", f"must be {len(_DIMS)} counts >= 1")
    columns, quantities, attrs = meta["columns"], meta["quantities"], meta["attrs"]
    if not (isinstance(columns, list) and all(isinstance(c, str) for c in columns)):
        raise _sidecar_bad(meta_path, "columns", "must be a list of names")
    if not (isinstance(quantities, list) and quantities and set(quantities) <= set(QUANTITIES)):
        raise _sidecar_bad(meta_path, "quantities", f"must be a list of {list(QUANTITIES)}")
    for q in quantities:
        need = _MUELLER_COLUMNS if q == "mueller" else ["aolp_deg" if q == "aolp" else q]
        at = columns.index(need[0]) if need[0] in columns else -1
        if at < 0 or columns[at : at + len(need)] != need:
            raise _sidecar_bad(meta_path, "columns", f"lack the column(s) of quantity {q!r}")
    if not isinstance(attrs, dict):
        raise _sidecar_bad(meta_path, "attrs", "must be a JSON object")
    coords = _sidecar_coords(meta_path, meta["coords"], dims)
    if [len(coords[d]) for d in dims] != shape:
        raise _sidecar_bad(meta_path, "shape", f"{shape} does not match the coordinates")
    table = _sidecar_table(meta_path, folder, meta["table"])
    return tuple(shape), columns, coords, dict(attrs), quantities, table


def open_lut(path: str | os.PathLike) -> xr.Dataset:
    """Open a table written by ``polbrdf lut --config lut.toml --out DIR`` as the Dataset
    :func:`lut` gives for the same configuration: same variables, dimensions, coordinates and
    attributes, the values memory-mapped from ``DIR/table.npy`` (nothing is read until used).

    ``DIR/table.npy`` holds one row per (material, wavelength, theta_i, theta_r, dphi), in C
    order, its columns (a structured dtype of ``<f8`` fields) ``m00 … m33``, ``brdf``,
    ``dolp``, ``aolp_deg`` as configured; ``DIR/attrs.json`` the dimensions, coordinates,
    columns and attributes.

    Raises ``ValueError`` when the directory is not such a table (naming the file and what is
    wrong) and ``OSError`` when it cannot be read.
    """
    folder = Path(path)
    meta_path = folder / "attrs.json"
    shape, columns, coords, attrs, quantities, table_path = _read_sidecar(folder, meta_path)
    try:
        table = np.load(table_path, mmap_mode="r")
    except (EOFError, ValueError) as e:  # a truncated or malformed .npy file
        raise ValueError(f"{table_path}: not a .npy table: {type(e).__name__}: {e}") from None
    fields = table.dtype.names or ()
    if list(fields) != columns or any(table.dtype[f] != np.dtype("<f8") for f in fields):
        raise ValueError(f"{table_path}: columns {list(fields)}, attrs.json says {columns}")
    rows = math.prod(shape)
    if table.shape != (rows,):
        raise ValueError(
            f"{table_path}: {table.shape[0]} rows, attrs.json's shape {shape} needs {rows}"
        )
    raw = table.view(np.float64).reshape(shape + (len(columns),))  # a view of the mapping
    data_vars = {}
    for q in quantities:
        if q == "mueller":
            at = columns.index(_MUELLER_COLUMNS[0])
            values, var_dims = (
                raw[..., at : at + 16].reshape(shape + (4, 4)),
                _DIMS + ("row", "col"),
            )
        else:
            values, var_dims = raw[..., columns.index("aolp_deg" if q == "aolp" else q)], _DIMS
        data_vars[q] = (var_dims, values, dict(_VARIABLE_ATTRS[q]))
    ds = xr.Dataset(
        data_vars,
        coords={
            "material": np.array(coords["material"], dtype=object),
            **{d: (d, np.asarray(coords[d], dtype=np.float64), _COORD_ATTRS[d]) for d in _GEOMETRY},
            "row": ("row", np.arange(4), _COORD_ATTRS["row"]),
            "col": ("col", np.arange(4), _COORD_ATTRS["col"]),
        },
    )
    ds.attrs.update(attrs)
    return ds
