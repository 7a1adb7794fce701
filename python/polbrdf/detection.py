"""Detection from Python: :func:`detect` (``polbrdf detect``) and :func:`detect_frame`
(``polbrdf detect --frame``).

Each is one call of the task layer (the Rust crate ``polbrdf-tasks``) that the CLI calls too:
the same validation, the same messages, the same numbers bit for bit (``detect.csv``'s rows,
``best.json``'s document, the frame's ``.npy`` arrays). The keywords are the CLI's options in
snake_case; a keyword left ``None`` takes the task layer's default, which is the CLI's
(docs/detection.md). ``detect.csv``'s column names come from the task layer too.
"""

from __future__ import annotations

import json
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, TypeAlias, TypedDict, Unpack

import numpy as np
from numpy.typing import NDArray

from . import _polbrdf
from ._polbrdf import FitResult
from .scene import Scene

if TYPE_CHECKING:  # pragma: no cover
    import xarray

__all__ = ["DetectFrame", "DetectOptions", "DetectStudy", "Feature", "detect", "detect_frame"]

#: The features a detector may use (``--features``): intensity, DoLP, or both combined.
Feature: TypeAlias = Literal["s0", "dolp", "s0+dolp"]

PathName: TypeAlias = "str | os.PathLike[str]"
_F64 = NDArray[np.float64]


class DetectOptions(TypedDict, total=False):
    """The keywords of :func:`detect` (and of :func:`detect_frame`, which adds ``seed``)."""

    target: PathName | None
    background: PathName | None
    grid_deg: float | Sequence[float] | None
    theta_deg: float | Sequence[float] | None
    phi_deg: float | Sequence[float] | None
    ranges_m: float | Sequence[float] | None
    no_search: bool
    range_limit_m: float | None
    area_m2: float | None
    pfa: float | None
    pd: float | None
    features: Sequence[Feature] | None
    sun_deg: Sequence[float] | None
    target_fit: FitResult | PathName | None
    background_fit: FitResult | PathName | None
    uncertainty_views: int | Literal["all"] | None


@dataclass(frozen=True)
class DetectStudy:
    """The result of :func:`detect`: the rows of ``detect.csv`` (one per view and range,
    view-major) and ``best.json``.

    - ``columns``: ``detect.csv``'s header;
    - ``study["theta_r_deg"]`` … ``study["pd"]``: the numeric columns as float64 arrays (one
      entry per row); ``study["feature"]`` and ``study["max_range_feature"]`` as string
      arrays; ``study["saturated"]`` as a bool array; ``study["max_range_m"]`` as float64 —
      the view's detection range, ``inf`` when beyond ``range_limit_m``, NaN when not
      detectable or not searched (``max_range_text`` holds the CSV's text:
      a number, ``"beyond"``, ``"not detectable"`` or empty); ``study["max_range_sigma_m"]``,
      ``study["max_range_lo95_m"]``, ``study["max_range_hi95_m"]``: the detection range's
      standard deviation and 95 % interval from the materials' fits (NaN where none);
    - ``view_max_range_m``: the detection range per view (as ``max_range_m``), zenith-major on
      a grid; ``grid``: the grid's ``(zeniths, azimuths)``, ``None`` for listed views;
    - ``best``: ``best.json`` as a dict (``best["views"]``: every view ranked by detection
      range); ``warnings``: the setup's notes (the CLI prints them).
    """

    columns: tuple[str, ...]
    rows: dict[str, NDArray[Any]] = field(repr=False)
    max_range_text: NDArray[np.str_] = field(repr=False)
    view_max_range_m: _F64 = field(repr=False)
    grid: tuple[int, int] | None
    ranges_m: tuple[float, ...]
    best: dict[str, Any] = field(default_factory=dict, repr=False)
    warnings: tuple[str, ...] = ()

    def __getitem__(self, name: str) -> NDArray[Any]:
        return self.rows[name]

    def __len__(self) -> int:
        return len(self.max_range_text)

    def to_xarray(self) -> xarray.Dataset:
        """The rows as an :class:`xarray.Dataset`: over ``(theta_r_deg, phi_r_deg)`` on a grid,
        over ``view`` for listed views, and over ``range_m`` when ranges were given (without
        them each view has one row, at its detection range). ``best.json`` is the attribute
        ``best_json`` (one string). Needs ``xarray``: ``pip install "polbrdf[xarray]"``."""
        try:
            import xarray as xr
        except ImportError as e:
            raise ImportError('to_xarray() needs xarray: pip install "polbrdf[xarray]"') from e
        n_views = len(self.view_max_range_m)
        per_view = len(self) // max(n_views, 1)
        theta = self.rows["theta_r_deg"].reshape(n_views, per_view)[:, 0]
        phi = self.rows["phi_r_deg"].reshape(n_views, per_view)[:, 0]
        if self.grid is not None:
            view_dims: tuple[str, ...] = ("theta_r_deg", "phi_r_deg")
            coords: dict[str, Any] = {
                "theta_r_deg": theta.reshape(self.grid)[:, 0],
                "phi_r_deg": phi.reshape(self.grid)[0],
            }
            view_shape: tuple[int, ...] = self.grid
        else:
            view_dims, view_shape = ("view",), (n_views,)
            coords = {"theta_r_deg": ("view", theta), "phi_r_deg": ("view", phi)}
        if self.ranges_m:
            dims, shape = (*view_dims, "range_m"), (*view_shape, per_view)
            coords["range_m"] = np.asarray(self.ranges_m)
        else:
            dims, shape = view_dims, view_shape
        per_view_columns = ("max_range_feature", *self.columns[-3:])
        skip = {"theta_r_deg", "phi_r_deg", "max_range_m", *per_view_columns}
        if self.ranges_m:
            skip.add("range_m")
        data = {
            name: (dims, np.asarray(v).reshape(shape))
            for name, v in self.rows.items()
            if name not in skip
        }
        data["max_range_m"] = (view_dims, self.view_max_range_m.reshape(view_shape))
        for name in per_view_columns:
            first = self.rows[name].reshape(n_views, per_view)[:, 0]
            data[name] = (view_dims, first.reshape(view_shape))
        return xr.Dataset(
            data, coords=coords, attrs={"best_json": json.dumps(self.best, ensure_ascii=False)}
        )


@dataclass(frozen=True)
class DetectFrame:
    """The result of :func:`detect_frame`: the simulated raw DoFP frame and its reconstruction
    at the study's best-ranked view and first range (docs/detection-frame.md).

    ``raw_counts`` (``2·side × 2·side``, counts, the mean over the frames averaged) and
    ``raw_saturated`` (bool, same shape); ``s0``, ``s1``, ``s2`` (electrons), ``dolp`` and
    ``aolp_deg`` (``side × side`` super-pixels; NaN where saturated): the arrays of the CLI's
    ``frame_*.npy``. ``side`` and ``target_side`` (super-pixels, the target a centred square),
    ``pixels_on_target`` and ``study`` (the :class:`DetectStudy` it comes from)."""

    raw_counts: _F64 = field(repr=False)
    raw_saturated: NDArray[np.bool_] = field(repr=False)
    s0: _F64 = field(repr=False)
    s1: _F64 = field(repr=False)
    s2: _F64 = field(repr=False)
    dolp: _F64 = field(repr=False)
    aolp_deg: _F64 = field(repr=False)
    side: int
    target_side: int
    pixels_on_target: float
    study: DetectStudy = field(repr=False)


def _invalid(name: str, message: str) -> ValueError:
    e = ValueError(f"invalid `{name}`: {message}")
    e.argument = name  # type: ignore[attr-defined]
    return e


def _floats(name: str, value: float | Sequence[float] | None) -> list[float] | None:
    if value is None:
        return None
    return [float(x) for x in np.atleast_1d(np.asarray(value, dtype=np.float64)).ravel()]


def _pair(
    name: str, value: float | Sequence[float] | None, one: bool
) -> tuple[float, float] | None:
    v = _floats(name, value)
    if v is None:
        return None
    if len(v) == 2:
        return v[0], v[1]
    if len(v) == 1 and one:
        return v[0], v[0]
    raise _invalid(name, f"expected two numbers, got {len(v)}")


def _path(name: str, value: Any) -> str | None:
    if value is None:
        return None
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(f"`{name}` must be a material file or a preset name (str or path)")
    return os.fspath(value)


def _fit(name: str, value: Any) -> FitResult | str | None:
    if value is None or isinstance(value, FitResult):
        return value
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    raise TypeError(
        f"`{name}` must be a polbrdf.FitResult or the path of a fit.json, not "
        f"{type(value).__name__}"
    )


def _options(kw: dict[str, Any]) -> Any:
    """The keywords as the task takes them (the stub's ``_DetectOptions``): checked,
    converted; ``None`` left to the task."""
    unknown = set(kw) - set(DetectOptions.__annotations__)
    if unknown:
        raise TypeError(f"unexpected keyword argument {min(unknown)!r}")
    theta, phi = _floats("theta_deg", kw.get("theta_deg")), _floats("phi_deg", kw.get("phi_deg"))
    if theta is not None and kw.get("grid_deg") is not None:
        raise _invalid("grid_deg", "give a grid or listed views (theta_deg), not both")
    if theta is None and phi is not None:
        raise _invalid("phi_deg", "phi_deg needs theta_deg")
    features = kw.get("features")
    if isinstance(features, str):
        features = [features]
    number = {n: kw.get(n) for n in ("range_limit_m", "area_m2", "pfa", "pd")}
    return {
        "target": _path("target", kw.get("target")),
        "background": _path("background", kw.get("background")),
        "grid_deg": _pair("grid_deg", kw.get("grid_deg"), one=True),
        "theta_deg": theta,
        "phi_deg": phi,
        "ranges_m": _floats("ranges_m", kw.get("ranges_m")),
        "no_search": bool(kw.get("no_search", False)),
        **{n: None if v is None else float(v) for n, v in number.items()},
        "features": None if features is None else [str(f) for f in features],
        "sun_deg": _pair("sun_deg", kw.get("sun_deg"), one=False),
        "target_fit": _fit("target_fit", kw.get("target_fit")),
        "background_fit": _fit("background_fit", kw.get("background_fit")),
        "uncertainty_views": kw.get("uncertainty_views"),
    }


def _run(
    scene: Scene | PathName,
    sensor: PathName,
    frame_seed: int | None,
    kw: dict[str, Any],
) -> tuple[DetectStudy, dict[str, Any] | None]:
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
    if not isinstance(sensor, (str, os.PathLike)):
        raise TypeError(f"`sensor` must be the path of a sensor file, not {type(sensor).__name__}")
    out = _polbrdf.detect_task(scene_file, scene_text, os.fspath(sensor), _options(kw), frame_seed)
    rows: dict[str, NDArray[Any]] = {
        c: out["values"][:, k] for k, c in enumerate(out["numeric_columns"])
    }
    rows["feature"] = np.array(out["feature"], dtype=np.str_)
    rows["saturated"] = out["saturated"]
    text = np.array(out["max_range_text"], dtype=np.str_)
    per_view = len(text) // max(len(out["max_range_m"]), 1)
    rows["max_range_m"] = np.repeat(out["max_range_m"], per_view)
    rows["max_range_feature"] = np.array(out["max_range_feature"], dtype=np.str_)
    for k, c in enumerate(out["uncertainty_columns"]):
        rows[c] = out["uncertainty"][:, k]
    study = DetectStudy(
        tuple(out["columns"]),
        rows,
        text,
        out["max_range_m"],
        out["grid"],
        tuple(out["ranges_m"]),
        json.loads(out["best"]),
        tuple(out["warnings"]),
    )
    return study, out["frame"]


def detect(
    scene: Scene | PathName,
    sensor: PathName,
    *,
    target: PathName | None = None,
    background: PathName | None = None,
    grid_deg: float | Sequence[float] | None = None,
    theta_deg: float | Sequence[float] | None = None,
    phi_deg: float | Sequence[float] | None = None,
    ranges_m: float | Sequence[float] | None = None,
    no_search: bool = False,
    range_limit_m: float | None = None,
    area_m2: float | None = None,
    pfa: float | None = None,
    pd: float | None = None,
    features: Sequence[Feature] | None = None,
    sun_deg: Sequence[float] | None = None,
    target_fit: FitResult | PathName | None = None,
    background_fit: FitResult | PathName | None = None,
    uncertainty_views: int | Literal["all"] | None = None,
) -> DetectStudy:
    """Will the sensor see the target on its background, from which views, by which feature
    and out to what range: ``polbrdf detect`` (docs/detection.md).

    Parameters
    ----------
    scene : Scene, or str or path
        The scene (``--scene``): target, background, sun, sky and ``[path]``.
    sensor : str or path
        The sensor file (``--sensor``).
    target, background : str or path, optional
        A material file or preset replacing the scene's (``--target``, ``--background``).
    grid_deg : float or (float, float), optional
        Grid steps Δθ, Δφ in degrees (``--grid-deg``; default 1°, 2°).
    theta_deg, phi_deg : float or sequence of float, optional
        Listed views instead of a grid (``--theta-deg``, ``--phi-deg``): every combination;
        ``phi_deg`` defaults to 0.
    ranges_m : float or sequence of float, optional
        Ranges (m) at which every view is evaluated (``--ranges-m``; default 1000). An empty
        list with the search: one row per view, at its detection range.
    no_search : bool
        Do not search each view's detection range (``--no-search``).
    range_limit_m, area_m2, pfa, pd : float, optional
        The largest range searched (m), the target's area (m²), the false-alarm probability
        and the required probability of detection (defaults 10 000, 1, 10⁻⁶, 0.9).
    features : sequence of {"s0", "dolp", "s0+dolp"}, optional
        The features the detector may use (``--features``; default all three).
    sun_deg : (float, float), optional
        The sun's zenith and azimuth (°), replacing the scene's ``[sun]`` position.
    target_fit, background_fit : FitResult, or str or path, optional
        The material's fit (``--target-fit``, ``--background-fit``): a :class:`FitResult` or a
        ``fit.json`` of ``polbrdf fit``, of the material used (its values must be the fit's).
        The detection range then carries its standard deviation and 95 % interval
        (``max_range_sigma_m``, ``max_range_lo95_m``, ``max_range_hi95_m``; docs/detection.md,
        "Uncertainty of the range").
    uncertainty_views : int or "all", optional
        With a fit: the best-ranked views given an interval (``--uncertainty-views``; default
        10).

    Returns
    -------
    DetectStudy
        ``detect.csv``'s rows as arrays (``study["d_prime"]``, …), ``study.best``
        (``best.json``), ``study.view_max_range_m``; ``study.to_xarray()``.

    Raises
    ------
    ValueError
        For a bad argument, naming the keyword (also as the exception's ``argument``); for a
        bad scene or sensor file, naming file, line and key.
    OSError
        When a file cannot be read.
    """
    kw = dict(locals())
    del kw["scene"], kw["sensor"]
    study, _ = _run(scene, sensor, None, kw)
    return study


def detect_frame(
    scene: Scene | PathName,
    sensor: PathName,
    *,
    seed: int = 0,
    **options: Unpack[DetectOptions],
) -> DetectFrame:
    """The simulated camera frame of a detection study: ``polbrdf detect --frame --seed SEED``
    (docs/detection-frame.md) — at the study's best-ranked view (the first view without a
    range search) and its first range, for a photon-counting division-of-focal-plane camera.
    The keywords as :func:`detect`'s; the same seed gives the same frame, bit for bit.

    Raises
    ------
    ValueError
        As :func:`detect`; naming ``frame`` for a sensor that cannot be simulated (a thermal
        NEL/NETD sensor, or not DoFP).
    """
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise _invalid("seed", f"{seed!r}: expected an integer ≥ 0")
    study, f = _run(scene, sensor, int(seed), dict(options))
    assert f is not None
    return DetectFrame(
        f["raw_counts"],
        f["raw_saturated"],
        f["s0"],
        f["s1"],
        f["s2"],
        f["dolp"],
        f["aolp_deg"],
        int(f["side"]),
        int(f["target_side"]),
        float(f["pixels_on_target"]),
        study,
    )
