"""polbrdf — the simplified Maxwell–Beard polarimetric BRDF, for NumPy.

The model of Zhuansun et al., *Infrared and Laser Engineering* 44(3), 2015, as pinned by the
project's ``docs/model.md``; the computation is the Rust core ``polbrdf`` (parallel, the GIL
released while it runs).

Units
-----
- Angles are in **degrees** by default (``degrees=False``: radians). Directions point away from
  the surface; ``theta`` is the zenith angle, ``phi`` the azimuth; specular reflection is
  ``theta_r = theta_i``, ``phi_r = phi_i + 180``. Zenith angles in [90°, 180°] are valid and
  give a zero pBRDF; NaN, ±inf and zenith angles outside [0°, 180°] raise ``ValueError``.
- BRDF and pBRDF (Mueller-matrix BRDF) values are in **sr⁻¹**; the 4×4 matrices are in the psps
  (SCATMECH) Stokes basis, row-major: ``S_out = F @ S_in`` (eq. 12).
- DoLP and DoP are dimensionless in [0, 1]; AoLP is in (−90°, 90°] (or radians), measured from
  the reflected beam's s axis toward its p axis.
- Thermal emission: wavelengths in **µm**, temperatures in **K**, spectral radiance in
  **W·m⁻²·sr⁻¹·µm⁻¹** (:func:`planck`, :func:`radiance` at one wavelength), band radiance in
  **W·m⁻²·sr⁻¹** (:func:`radiance` over a band); emissivities are dimensionless. Daylight
  (:func:`radiance` with ``sun=`` or ``sky="cie-clear"``): spectral irradiances in
  **W·m⁻²·µm⁻¹**.

Example
-------
>>> import numpy as np, polbrdf
>>> paint = polbrdf.Material.preset("paint")
>>> theta = np.linspace(0, 80, 5)
>>> polbrdf.dolp(paint, theta, 0, theta, 180).round(3)    # specular DoLP vs angle
array([0.   , 0.103, 0.481, 0.915, 0.446])
>>> polbrdf.mueller(paint, theta, 0, theta, 180).shape
(5, 4, 4)

Evaluation functions broadcast their four angle arguments like NumPy ufuncs (scalars, lists,
arrays of any real dtype, any strides); the result has the broadcast shape (``+ (4, 4)`` for
:func:`mueller`). Thread count: rayon's default (all cores); set ``RAYON_NUM_THREADS`` before
the first call to change it.
"""

from __future__ import annotations

try:
    from ._polbrdf import DEFAULT_DOP_MAX, FitResult, Material
except ImportError as _e:  # pragma: no cover - only when the extension was never built
    raise ImportError(
        "polbrdf's compiled extension (polbrdf._polbrdf) is missing. Install the package with "
        "`pip install ./python` from the repository root; if you did, you may be importing the "
        "source folder python/polbrdf instead of the installed package (run from elsewhere)."
    ) from _e

from ._common import MAX_DIMS as MAX_DIMS
from ._evaluate import brdf, dolp, evaluate, index, mueller, mueller_directions
from ._fit import MAX_STARTS as MAX_STARTS
from ._fit import fit
from ._radiance import radiance
from ._results import Emissivity, Evaluation, Radiance
from ._stokes import stokes_aolp, stokes_dolp, stokes_dop
from ._thermal import brightness_temperature, emissivity, planck
from .detection import DetectFrame, DetectStudy, detect, detect_frame
from .jobs import (
    CheckReport,
    Measurements,
    PbsdfTable,
    check,
    export_pbsdf,
    fit_measurements,
    fit_pbsdf,
    read_measurements,
    read_pbsdf,
)
from .scene import Atmosphere, Band, PathToSensor, Scene, SceneObject, Sky, Sun, Surface
from .sun import DaytimeStudy, daytime, sun_position
from .tasks import (
    AlbedoTable,
    ContrastStudy,
    HemisphereMap,
    Illumination,
    albedo,
    contrast,
    hemisphere,
)

__all__ = [
    "DEFAULT_DOP_MAX",
    "AlbedoTable",
    "Atmosphere",
    "Band",
    "CheckReport",
    "ContrastStudy",
    "DaytimeStudy",
    "DetectFrame",
    "DetectStudy",
    "Emissivity",
    "Evaluation",
    "FitResult",
    "HemisphereMap",
    "Illumination",
    "Material",
    "Measurements",
    "PathToSensor",
    "PbsdfTable",
    "Radiance",
    "Scene",
    "SceneObject",
    "Sky",
    "Sun",
    "Surface",
    "__version__",
    "albedo",
    "brdf",
    "brightness_temperature",
    "check",
    "contrast",
    "daytime",
    "detect",
    "detect_frame",
    "dolp",
    "emissivity",
    "evaluate",
    "export_pbsdf",
    "fit",
    "fit_measurements",
    "fit_pbsdf",
    "hemisphere",
    "index",
    "mueller",
    "mueller_directions",
    "planck",
    "radiance",
    "read_measurements",
    "read_pbsdf",
    "stokes_aolp",
    "stokes_dolp",
    "stokes_dop",
    "sun_position",
]

try:
    from importlib.metadata import PackageNotFoundError, version

    __version__: str = version("polbrdf")
except PackageNotFoundError:  # pragma: no cover
    __version__ = "unknown"


# --- Lookup tables (optional extra `polbrdf[xarray]`; imported on first use) ----------------


def __getattr__(name: str) -> object:
    """``polbrdf.lut``, ``polbrdf.open_lut``: :mod:`polbrdf.xarray`'s, imported on first use so that
    ``import polbrdf`` does not import xarray."""
    if name in ("lut", "open_lut", "xarray"):
        import importlib

        try:
            _lut_module = importlib.import_module(".xarray", __name__)
        except ImportError as e:
            raise ImportError(
                f"polbrdf.{name} needs the optional extra: pip install 'polbrdf[xarray]' ({e})"
            ) from e
        return _lut_module if name == "xarray" else getattr(_lut_module, name)
    raise AttributeError(f"module 'polbrdf' has no attribute {name!r}")
