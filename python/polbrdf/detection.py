"""Detection from Python: :func:`detect` (``polbrdf detect``) and :func:`detect_frame`
(``polbrdf detect --frame``).

Each is one call of the task layer (the Rust crate ``polbrdf-tasks``) that the CLI calls too:
the same validation, the same messages, the same numbers bit for bit (``detect.csv``'s rows,
``best.json``'s document, the frame's ``.npy`` arrays). The keywords are the CLI's options in
snake_case, with the CLI's defaults (docs/detection.md).
"""

from __future__ import annotations

import json
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, TypeAlias, get_args

import numpy as np
from numpy.typing import NDArray

from . import _polbrdf
from .scene import Scene

if TYPE_CHECKING:  # pragma: no cover
    import xarray

__all__ = ["DetectFrame", "DetectStudy", "Feature", "detect", "detect_frame"]

#: The features a detector may use (``--features``): intensity, DoLP, or both combined.
Feature: TypeAlias = Literal["s0", "dolp", "s0+dolp"]
#: Every feature (the default): the Literal's members, which a test holds equal to the
#: extension's ``vocabulary()["feature"]`` (the core's ``Feature::ALL``).
_ALL_FEATURES: tuple[Feature, ...] = get_args(Feature)

PathName: TypeAlias = "str | os.PathLike[str]"
_F64 = NDArray[np.float64]

#: The numeric columns of ``detect.csv``, in order (the first eleven).
_NUMERIC = (
    "theta_r_deg",
    "phi_r_deg",
    "range_m",
    "pixels_on_target",
    "snr_s0",
    "snr_dolp",
    "snr_combined",
    "polarization_contrast",
    "snr_polarization_contrast",
    "d_prime",
    "pd",
)


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
      a number, ``"beyond"``, ``"not detectable"`` or empty);
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
        skip = {"theta_r_deg", "phi_r_deg", "max_range_m", "max_range_feature"}
        if self.ranges_m:
            skip.add("range_m")
        data = {
            name: (dims, np.asarray(v).reshape(shape))
            for name, v in self.rows.items()
            if name not in skip
        }
        data["max_range_m"] = (view_dims, self.view_max_range_m.reshape(view_shape))
        feature = self.rows["max_range_feature"].reshape(n_views, per_view)[:, 0]
        data["max_range_feature"] = (view_dims, feature.reshape(view_shape))
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
    theta, phi = _floats("theta_deg", kw["theta_deg"]), _floats("phi_deg", kw["phi_deg"])
    views = None
    if theta is not None:
        if kw["grid_deg"] is not None:
            raise _invalid("grid_deg", "give a grid or listed views (theta_deg), not both")
        views = [(t, p) for t in theta for p in (phi if phi else [0.0])]
    elif phi is not None:
        raise _invalid("phi_deg", "phi_deg needs theta_deg")
    ranges = _floats("ranges_m", kw["ranges_m"])
    features = kw["features"]
    if isinstance(features, str):
        features = [features]
    for name in ("target", "background"):
        if kw[name] is not None and not isinstance(kw[name], (str, os.PathLike)):
            raise TypeError(f"`{name}` must be a material file or a preset name (str or path)")
    out = _polbrdf.detect_task(
        scene_file,
        scene_text,
        os.fspath(sensor),
        None if kw["target"] is None else os.fspath(kw["target"]),
        None if kw["background"] is None else os.fspath(kw["background"]),
        _pair("grid_deg", kw["grid_deg"], one=True),
        views,
        [1000.0] if ranges is None else ranges,
        not kw["no_search"],
        float(kw["range_limit_m"]),
        float(kw["area_m2"]),
        float(kw["pfa"]),
        float(kw["pd"]),
        [str(f) for f in features],
        _pair("sun_deg", kw["sun_deg"], one=False),
        frame_seed,
    )
    values = out["values"]
    rows: dict[str, NDArray[Any]] = {c: values[:, k] for k, c in enumerate(_NUMERIC)}
    rows["feature"] = np.array(out["feature"], dtype=np.str_)
    rows["saturated"] = out["saturated"]
    text = np.array(out["max_range_text"], dtype=np.str_)
    per_view = len(text) // max(len(out["max_range_m"]), 1)
    rows["max_range_m"] = np.repeat(out["max_range_m"], per_view)
    rows["max_range_feature"] = np.array(out["max_range_feature"], dtype=np.str_)
    study = DetectStudy(
        tuple(out["columns"]),
        rows,
        text,
        out["max_range_m"],
        out["grid"],
        tuple([1000.0] if ranges is None else ranges),
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
    range_limit_m: float = 10_000.0,
    area_m2: float = 1.0,
    pfa: float = 1e-6,
    pd: float = 0.9,
    features: Sequence[Feature] = _ALL_FEATURES,
    sun_deg: Sequence[float] | None = None,
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
    range_limit_m, area_m2, pfa, pd : float
        The largest range searched (m), the target's area (m²), the false-alarm probability
        and the required probability of detection (defaults 10 000, 1, 10⁻⁶, 0.9).
    features : sequence of {"s0", "dolp", "s0+dolp"}
        The features the detector may use (``--features``; default all three).
    sun_deg : (float, float), optional
        The sun's zenith and azimuth (°), replacing the scene's ``[sun]`` position.

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
    study, _ = _run(scene, sensor, None, locals())
    return study


def detect_frame(
    scene: Scene | PathName,
    sensor: PathName,
    *,
    seed: int = 0,
    target: PathName | None = None,
    background: PathName | None = None,
    grid_deg: float | Sequence[float] | None = None,
    theta_deg: float | Sequence[float] | None = None,
    phi_deg: float | Sequence[float] | None = None,
    ranges_m: float | Sequence[float] | None = None,
    no_search: bool = False,
    range_limit_m: float = 10_000.0,
    area_m2: float = 1.0,
    pfa: float = 1e-6,
    pd: float = 0.9,
    features: Sequence[Feature] = _ALL_FEATURES,
    sun_deg: Sequence[float] | None = None,
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
    kw = locals()
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise _invalid("seed", f"{seed!r}: expected an integer ≥ 0")
    study, f = _run(scene, sensor, int(seed), kw)
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
