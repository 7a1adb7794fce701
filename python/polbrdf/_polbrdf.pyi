"""Type stubs of the compiled module ``polbrdf._polbrdf`` (use it through ``polbrdf``)."""

from os import PathLike
from typing import Any, Literal, TypeAlias, TypedDict, final

import numpy as np
from numpy.typing import NDArray

# The closed sets of names, spelled as the Rust enums spell them (`vocabulary()` returns those;
# python/tests/test_typing.py checks that every Literal here is exactly one of its sets).
_Form: TypeAlias = Literal["standard", "paper"]
_AzimuthTerm: TypeAlias = Literal["none", "eq3"]
_Precision: TypeAlias = Literal["float64", "float32"]
_SkyModel: TypeAlias = Literal["none", "uniform", "thermal", "profile", "cie-clear", "table"]
_Parameter: TypeAlias = Literal[
    "n", "k", "sigma_deg", "b", "a", "tau_deg", "omega_deg", "rho_d", "rho_v"
]
_Quantity: TypeAlias = Literal[
    "brdf", "dolp", "brdf_s", "brdf_p",
    "m00", "m01", "m02", "m03", "m10", "m11", "m12", "m13",
    "m20", "m21", "m22", "m23", "m30", "m31", "m32", "m33",
]  # fmt: skip
_RankBy: TypeAlias = Literal["delta-dolp", "polarization-contrast"]
_LutQuantity: TypeAlias = Literal["mueller", "brdf", "dolp", "aolp"]
_Feature: TypeAlias = Literal["s0", "dolp", "s0+dolp"]
_VocabularySet: TypeAlias = Literal[
    "form", "azimuth_term", "precision", "layout", "sky", "quantity", "parameter", "scene_key",
    "rank_by", "lut_quantity", "feature", "mueller_column",
]

DEFAULT_DOP_MAX: float
"""The clear sky's default maximum degree of polarization δ_max (the core's)."""
LUT_CONVENTIONS: str
"""The lookup tables' convention attributes as a JSON object (the task layer's, as `polbrdf lut`)."""

__all__ = [
    "DEFAULT_DOP_MAX",
    "LUT_CONVENTIONS",
    "FitResult",
    "Material",
    "_fit_result_from_state",
    "_material_from_state",
    "albedo_task",
    "brdf_dolp_flat",
    "bridge_flat",
    "brightness_temperature_flat",
    "check_task",
    "cli_main",
    "contrast_task",
    "daytime_task",
    "derivative_step",
    "detect_task",
    "emission_task",
    "emissivity_flat",
    "evaluate_flat",
    "export_pbsdf_task",
    "fit_flat",
    "fit_measurements_task",
    "fit_pbsdf_task",
    "hemisphere_task",
    "index_flat",
    "lut_rows",
    "mueller_directions_flat",
    "mueller_flat",
    "planck_flat",
    "radiance_flat",
    "radiance_scene",
    "read_measurements_task",
    "read_pbsdf_task",
    "read_scene_keys",
    "sun_task",
    "vocabulary",
]

@final
class Material:
    """A validated material of the simplified Maxwell–Beard model.

    The keyword arguments are exactly the keys of a material file: ``n`` (> 0), ``k`` (≥ 0) — or
    ``index`` ("library:<id>" or a refractiveindex.info YAML file) for a spectral index —,
    ``sigma_deg`` (roughness σ, degrees) or ``b`` (rad⁻²) — exactly one —, ``a`` (sr⁻¹; None =
    hemispherical normalization), ``form`` ("standard" | "paper"), ``shadowing``, ``tau_deg`` and
    ``omega_deg`` (degrees), ``azimuth_term`` ("none" | "eq3"), ``rho_d`` and ``rho_v`` (sr⁻¹),
    ``name``. Invalid values raise ``ValueError`` with the core's message.
    """

    def __new__(
        cls,
        n: float | None = None,
        k: float | None = None,
        sigma_deg: float | None = None,
        b: float | None = None,
        a: float | None = None,
        form: _Form | None = None,
        shadowing: bool | None = None,
        tau_deg: float | None = None,
        omega_deg: float | None = None,
        azimuth_term: _AzimuthTerm | None = None,
        rho_d: float | None = None,
        rho_v: float | None = None,
        name: str | None = None,
        index: str | None = None,
    ) -> Material: ...
    @staticmethod
    def from_toml(path: str | PathLike[str]) -> Material:
        """Load a material file; ``ValueError`` naming file and line for bad content,
        ``OSError`` (``FileNotFoundError``, …) when it cannot be read."""
    @staticmethod
    def from_toml_str(text: str, source: str = "<string>") -> Material:
        """Parse the text of a material file; ``source`` names it in error messages."""
    @staticmethod
    def preset(name: str) -> Material:
        """A built-in material; ``ValueError`` for an unknown name."""
    @staticmethod
    def presets() -> list[str]:
        """Names of the built-in materials."""
    @staticmethod
    def preset_descriptions() -> dict[str, str]:
        """``{name: description}`` of the built-in materials."""
    def to_toml(self) -> str:
        """The material as material-file text."""
    def to_dict(self) -> dict[str, Any]:
        """The material's keys (``None`` for unset optional ones), for ``Material(**d)``."""
    def __reduce__(self) -> tuple[Any, tuple[Any]]:
        """Pickle support at every protocol: the keys and a spectral index's data."""
    def __eq__(self, value: object, /) -> bool: ...
    def __ne__(self, value: object, /) -> bool: ...
    @property
    def n(self) -> float | None:
        """Real part of the refractive index; None for a spectral index."""
    @property
    def k(self) -> float | None:
        """Extinction coefficient; None for a spectral index."""
    @property
    def index(self) -> str | None:
        """Source of a spectral index ("library:<id>" or a YAML file's path), or None."""
    @property
    def wavelength_range(self) -> tuple[float, float] | None:
        """(λ_min, λ_max) in µm of a spectral index's data, or None."""
    @property
    def index_references(self) -> str | None:
        """References of a spectral index's source, or None."""
    @property
    def sigma_deg(self) -> float | None:
        """Roughness σ in degrees as given, or None."""
    @property
    def b(self) -> float | None:
        """Width b of D in rad⁻² as given, or None (see ``b_effective``)."""
    @property
    def a(self) -> float | None:
        """Amplitude a of D in sr⁻¹ as given, or None (see ``a_effective``)."""
    @property
    def form(self) -> _Form:
        """Either "standard" or "paper"."""
    @property
    def shadowing(self) -> bool:
        """Whether SO (eq. 3) is applied."""
    @property
    def tau_deg(self) -> float:
        """τ of eq. 3, degrees."""
    @property
    def omega_deg(self) -> float:
        """Ω of eq. 3, degrees."""
    @property
    def azimuth_term(self) -> _AzimuthTerm:
        """Either "none" or "eq3"."""
    @property
    def rho_d(self) -> float:
        """ρ_D, sr⁻¹."""
    @property
    def rho_v(self) -> float:
        """ρ_V, sr⁻¹."""
    @property
    def name(self) -> str | None:
        """The label, or None."""
    @property
    def a_effective(self) -> float:
        """Amplitude a of D actually used, sr⁻¹."""
    @property
    def b_effective(self) -> float:
        """Width b of D actually used, rad⁻²."""

def mueller_flat(
    material: Material,
    theta_i: NDArray[np.float64],
    phi_i: NDArray[np.float64],
    theta_r: NDArray[np.float64],
    phi_r: NDArray[np.float64],
    degrees: bool,
    wavelength_um: NDArray[np.float64] | None = None,
    out: NDArray[np.floating] | None = None,
    precision: _Precision = "float64",
    planar: bool = False,
) -> NDArray[np.floating]:
    """pBRDF (sr⁻¹) at n geometries of contiguous 1-D float64 angles, shape (n, 16) — (16, n)
    of planes when ``planar`` —, written into ``out`` when given (a C-contiguous array of that
    shape and the precision's dtype)."""

def mueller_directions_flat(
    material: Material,
    w_i: NDArray[np.float64],
    w_r: NDArray[np.float64],
    wavelength_um: NDArray[np.float64] | None = None,
    out: NDArray[np.floating] | None = None,
    precision: _Precision = "float64",
    planar: bool = False,
) -> NDArray[np.floating]:
    """pBRDF (sr⁻¹) at n pairs of direction vectors, (n, 3) C-contiguous float64 arrays (or
    (1, 3) for all), shape (n, 16); ``out`` and ``planar`` as for ``mueller_flat``."""

def brdf_dolp_flat(
    material: Material,
    theta_i: NDArray[np.float64],
    phi_i: NDArray[np.float64],
    theta_r: NDArray[np.float64],
    phi_r: NDArray[np.float64],
    degrees: bool,
    wavelength_um: NDArray[np.float64] | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """BRDF (sr⁻¹) and DoLP at n geometries, two arrays of length n."""

def index_flat(
    material: Material, wavelength_um: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """n and k of the material at each wavelength (µm)."""

def derivative_step(name: str, value: float) -> float:
    """The fit's central-difference step 1e-6·max(|value|, scale) for parameter ``name``."""

def evaluate_flat(
    material: Material,
    theta_i: NDArray[np.float64],
    phi_i: NDArray[np.float64],
    theta_r: NDArray[np.float64],
    phi_r: NDArray[np.float64],
    degrees: bool,
    with_mueller: bool,
    wavelength_um: NDArray[np.float64] | None = None,
) -> tuple[
    NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64] | None
]:
    """BRDF, DoLP, AoLP (and the (n, 16) pBRDF) at n geometries."""

def planck_flat(
    wavelength_um: NDArray[np.float64], temperature_k: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Planck's law B_λ (W·m⁻²·sr⁻¹·µm⁻¹) at n (λ in µm, T in K) pairs; ValueError (with
    ``argument`` and ``index``) for an element not finite and > 0."""

def brightness_temperature_flat(
    wavelength_um: NDArray[np.float64], radiance: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Brightness temperature (K) of n spectral radiances (W·m⁻²·sr⁻¹·µm⁻¹) at λ (µm)."""

def emissivity_flat(
    material: Material,
    theta_r: NDArray[np.float64],
    degrees: bool,
    wavelength_um: NDArray[np.float64] | None = None,
) -> tuple[
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.bool_],
]:
    """Emissivity at n view zeniths (each at its wavelength, µm): eps (n, 4), eps_b (n, 4),
    eps_s, eps_p, dolp, reciprocity_residual, valid (n)."""

def radiance_flat(
    material: Material,
    theta_r: NDArray[np.float64],
    phi_r: NDArray[np.float64],
    degrees: bool,
    wavelength_um: float | None = None,
    band: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None,
    band_step_um: float | None = None,
    temperature_k: float | None = None,
    sky: _SkyModel | None = None,
    sky_radiance: float | None = None,
    sky_temperature_k: float | None = None,
    sky_profile: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None,
    transmittance: float | None = None,
    path_radiance: float | None = None,
    sun: tuple[float, float, float, tuple[float, float, float, float]] | None = None,
    sky_irradiance: float | None = None,
    dop_max: float | None = None,
    sky_table: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]
    | None = None,
) -> tuple[
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
]:
    """Observed Stokes radiance at n views: stokes, emitted, reflected (n, 4), dolp, aolp (n);
    W·m⁻²·sr⁻¹·µm⁻¹ at one wavelength, W·m⁻²·sr⁻¹ over a band. ``sun`` = (zenith, azimuth
    (unit of the views), irradiance W·m⁻²·µm⁻¹, stokes normalized here to s0 = 1);
    ``sky_table`` = (theta_deg, phi_deg, stokes (n_theta·n_phi, 4), θ-major); ``None``: the
    scene files' default."""

def radiance_scene(
    material: Material,
    text: str,
    source: str,
    theta_r: NDArray[np.float64],
    phi_r: NDArray[np.float64],
    degrees: bool,
) -> tuple[
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
]:
    """As ``radiance_flat`` for the scene of scene-file text ``text`` (read by polbrdf-io's
    reader; ``source`` names it in messages); a [target] or [background] is refused."""

def read_scene_keys(path: str | PathLike[str]) -> list[tuple[str, float | list[float] | str]]:
    """The keys of a scene file read by polbrdf-io's reader, [(dotted name, value)], file
    names joined to its folder."""

_Light: TypeAlias = tuple[float, float | None, tuple[float, float, float, float] | None]
_Spectral: TypeAlias = tuple[float | None, str | PathLike[str] | None, float | None]

def contrast_task(
    target: str | None,
    background: str | None,
    scene_file: str | PathLike[str] | None,
    scene_text: tuple[str, str] | None,
    light: _Light | None,
    spectral: _Spectral,
    grid_deg: tuple[float, float] | None,
    rank_by: _RankBy | None,
    top: int | None,
    min_separation_deg: float | None,
    max_zenith_deg: float | None,
    refine: bool | None,
) -> tuple[
    list[str],
    NDArray[np.float64],
    tuple[int, int],
    str,
    list[str],
    list[NDArray[np.float64]],
]:
    """The task layer's contrast study (``polbrdf contrast``): exactly one of a scene file,
    a scene's text ``(text, source)`` or a collimated ``light`` = (zenith °, azimuth °, stokes);
    ``None``: the task's default. Returns the columns, the table (zenith-major), the grid's
    (zeniths, azimuths), ``best.json`` as JSON text, the setup's warnings and the grid zeniths
    (degrees) where either model, the target's and the background's is flagged invalid."""

def hemisphere_task(
    material: str,
    light: _Light,
    spectral: _Spectral,
    grid_deg: tuple[float, float] | None,
) -> tuple[list[str], NDArray[np.float64], tuple[int, int], NDArray[np.float64]]:
    """The task layer's hemisphere map (``polbrdf map``): the columns, the table
    (zenith-major), the grid's (zeniths, azimuths) and the grid zeniths (degrees) where the
    model is flagged invalid."""

def cli_main(argv: list[str]) -> int:
    """Run the ``polbrdf`` command line (argv[0] the program name); return its exit code."""

def albedo_task(
    material: str, theta_i_deg: list[float], spectral: _Spectral
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The task layer's albedo (``polbrdf albedo``): theta_i_deg, albedo, surface, volume;
    an empty ``theta_i_deg`` takes the task's default angles."""

def check_task(material: str | Material, grid_deg: float | None, spectral: _Spectral) -> str:
    """The task layer's validity check (``polbrdf check --output``): its document as JSON
    text."""

def emission_task(
    material: str | Material,
    theta_deg: list[float],
    temperature_k: float | None,
    spectral: _Spectral,
) -> tuple[
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.bool_],
]:
    """The task layer's emissivity (``polbrdf emission``): theta_deg, eps (n, 4), eps_b (n, 4),
    eps_s, eps_p, dolp, reciprocity_residual, valid; an empty ``theta_deg`` takes 0, 1, …, 89."""

def lut_rows(
    material: Material,
    wavelength_um: list[float],
    theta_i_deg: list[float],
    theta_r_deg: list[float],
    dphi_deg: list[float],
    quantities: list[_LutQuantity],
) -> NDArray[np.float64]:
    """The task layer's lookup-table rows of one material (``polbrdf lut``): (W·I·R·P, columns)."""

def export_pbsdf_task(
    material: str | Material,
    path: str | PathLike[str],
    bands_nm: list[int] | None,
    grid: tuple[int, int, int] | None,
) -> int:
    """The task layer's ``.pbsdf`` export (``polbrdf export``); the bytes of the matrices."""

def read_pbsdf_task(
    path: str | PathLike[str],
) -> tuple[
    NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], list[int], NDArray[np.float32]
]:
    """A ``.pbsdf`` table: phi_d, theta_d, theta_h (rad), bands (nm), M (P, D, H, bands, 4, 4)."""

def fit_pbsdf_task(
    material: str | Material,
    path: str | PathLike[str],
    free: list[_Parameter],
    subsample: int | None,
    starts: int,
    seed: int,
    exclude_inadmissible: bool,
) -> str:
    """The task layer's band fit of a ``.pbsdf`` table (``polbrdf fit``): fit.json as text."""

def read_measurements_task(
    path: str | PathLike[str],
) -> tuple[
    list[int],
    list[NDArray[np.float64]],
    list[_Quantity],
    list[NDArray[np.float64]],
    list[NDArray[np.float64] | None],
    NDArray[np.float64] | None,
]:
    """A measurement CSV (``polbrdf fit --data``): lines, angles (rad), columns, values (NaN:
    not measured), sigmas, wavelengths."""

def fit_measurements_task(
    material: Material, path: str | PathLike[str], free: list[_Parameter], starts: int, seed: int
) -> FitResult:
    """The fit of a measurement CSV as ``polbrdf fit --data`` runs it."""
def sun_task(
    date_time: str,
    latitude_deg: float,
    longitude_deg: float,
    elevation_m: float | None,
    pressure_hpa: float | None,
    temperature_c: float | None,
    delta_t_s: float | None,
    phi0_azimuth_deg: float | None,
) -> str:
    """The task layer's sun position (``polbrdf sun``): its JSON document."""
def daytime_task(
    scene_file: str | PathLike[str] | None,
    scene_text: tuple[str, str] | None,
    sensor: str | PathLike[str] | None,
    target: str | None,
    background: str | None,
    date: str | None,
    times: list[str] | None,
    range: tuple[str | None, str | None, float | None],
    grid_deg: tuple[float, float] | None,
    fixed_view_deg: tuple[float, float] | None,
    criteria: tuple[float | None, float | None, float | None, float | None],
) -> tuple[list[str], list[str], NDArray[np.float64], list[str]]:
    """A time-of-day sweep as ``polbrdf daytime`` runs it: the columns after ``date_time``,
    the rows' date-times, the table and the setup's warnings; use :func:`polbrdf.daytime`."""
class _DetectOptions(TypedDict):
    """The keywords of :func:`polbrdf.detect` as the task takes them (``None``: its default)."""

    target: str | None
    background: str | None
    grid_deg: tuple[float, float] | None
    theta_deg: list[float] | None
    phi_deg: list[float] | None
    ranges_m: list[float] | None
    no_search: bool
    range_limit_m: float | None
    area_m2: float | None
    pfa: float | None
    pd: float | None
    features: list[_Feature] | None
    sun_deg: tuple[float, float] | None
    target_fit: FitResult | str | None
    background_fit: FitResult | str | None
    uncertainty_views: int | str | None

def detect_task(
    scene_file: str | PathLike[str] | None,
    scene_text: tuple[str, str] | None,
    sensor: str | PathLike[str],
    options: _DetectOptions,
    frame_seed: int | None,
) -> dict[str, Any]:
    """A detection study as ``polbrdf detect`` runs it (``options``: the keywords of
    :func:`polbrdf.detect`, ``None`` taking the task's defaults; ``frame_seed``: with
    ``--frame``): the rows of ``detect.csv`` as arrays, ``best.json`` as JSON text, the
    frame's arrays; use :func:`polbrdf.detect`."""

def bridge_flat(
    name: str,
    values: NDArray[np.float64],
    angles: NDArray[np.float64],
    degrees: bool,
    y_down: bool,
) -> NDArray[np.float64]:
    """The core's bridge ``name`` (``polbrdf::geometry::bridges``) row by row: ``values``
    ``(n, w_v)`` and ``angles`` ``(n, w_a)`` to ``(n, w_out)``; use :mod:`polbrdf.bridges`."""

def vocabulary() -> dict[_VocabularySet, list[str]]:
    """Every closed set of names the module accepts, from the Rust enums."""

def _material_from_state(state: tuple[Any, Any]) -> Material:
    """The inverse of ``Material.__reduce__``."""

def _fit_result_from_state(state: Any, m: Material) -> FitResult:
    """The inverse of ``FitResult.__reduce__``."""

@final
class FitResult:
    """The outcome of :func:`polbrdf.fit`: fitted parameters with their uncertainties."""

    def __reduce__(self) -> tuple[Any, tuple[Any, Material]]:
        """Pickle support at every protocol: every field as plain values."""
    @property
    def names(self) -> list[str]:
        """Free parameters, in the order of every array."""
    @property
    def values(self) -> NDArray[np.float64]:
        """Fitted values (units of the material keys: degrees for sigma_deg, sr⁻¹ for ρ, a)."""
    @property
    def stderr(self) -> NDArray[np.float64]:
        """Standard errors, sqrt(diag(covariance)); NaN for a parameter at its bound."""
    @property
    def bounds(self) -> list[dict[str, Any] | None]:
        """Per parameter: None inside its domain, else {"bound": "lower", "upper_limit_95":
        float | None, "correlation_at_limit": NDArray | None} (profile-χ² one-sided limit)."""
    @property
    def covariance(self) -> NDArray[np.float64]:
        """Covariance matrix, shape (p, p)."""
    @property
    def correlation(self) -> NDArray[np.float64]:
        """Correlation matrix, shape (p, p)."""
    @property
    def parameters(self) -> dict[str, tuple[float, float]]:
        """{name: (value, stderr)}."""
    @property
    def chi2(self) -> float:
        """χ² = Σ ((model − data)/σ)², σ = 1 where none was given."""
    @property
    def reduced_chi2(self) -> float:
        """χ²/dof."""
    @property
    def dof(self) -> int:
        """Measured values − free parameters."""
    @property
    def uncertainty_from_residuals(self) -> bool:
        """True when some value had no σ: covariance scaled by χ²/dof."""
    @property
    def converged(self) -> bool:
        """Whether the minimizer met a convergence test."""
    @property
    def iterations(self) -> int:
        """Minimizer steps of the best start."""
    @property
    def message(self) -> str:
        """How the minimizer stopped."""
    @property
    def starts(self) -> tuple[int, int]:
        """(starts tried, starts that reached the best χ²)."""
    @property
    def warnings(self) -> list[str]:
        """Warnings about the data (e.g. repeated rows: uncertainties not meaningful)."""
    @property
    def material(self) -> Material:
        """The fitted material."""
    @property
    def residuals(self) -> NDArray[np.float64]:
        """Normalized residuals (model − data)/σ, one per measured value."""

def fit_flat(
    material: Material,
    theta_i: NDArray[np.float64],
    phi_i: NDArray[np.float64],
    theta_r: NDArray[np.float64],
    phi_r: NDArray[np.float64],
    names: list[_Quantity],
    values: list[NDArray[np.float64]],
    sigmas: list[NDArray[np.float64] | None],
    free: list[_Parameter],
    degrees: bool,
    starts: int,
    seed: int,
    wavelength_um: NDArray[np.float64] | None = None,
) -> FitResult:
    """Fit at n geometries; values NaN where not measured."""
