//! Detection (docs/detection.md): will a sensor see the target on its background, from which
//! views, by which feature, and out to what range. A scene (target, background, sun, sky and
//! `[path]`) and a sensor file make a [`Detector`]; the target's and the background's Stokes
//! radiance are observed over the sensor's band (weighted by its photon response for a
//! photon-counting camera) at every view, then carried through the path, the analyzers and the
//! noise to `d'`, `P_d` at each requested range and the detection range of each view.

pub mod out;
mod study;
pub mod uncertainty;
pub(crate) mod warnings;

pub use study::{DetectStudy, RangeUncertainty, ViewResult};

use crate::contrast::material_of;
use crate::error::{TaskError, TaskResult};
use crate::fit_covariance::FitCovariance;
use crate::hemisphere::view_grid;
use crate::spectrum::NamedMaterial;
use polbrdf::analysis::contrast::ViewGrid;
use polbrdf::analysis::detection::{Criteria, Detector, Feature, MaxRange, Path as AirPath};
use polbrdf::analysis::scene::{check_views, Observer};
use polbrdf::analysis::sky::Quality;
use polbrdf::analysis::Atmosphere;
use polbrdf::{Spectrum, Stokes};
use polbrdf_io::{Scene, SensorFile};
use std::path::PathBuf;
use uncertainty::{Propagation, DEFAULT_UNCERTAINTY_VIEWS};

/// Where the scene comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum SceneSource {
    /// A scene file.
    File(PathBuf),
    /// A scene already read (an adapter holding its text).
    Loaded(Box<Scene>),
}

/// Where the sensor comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum SensorSource {
    /// A sensor file.
    File(PathBuf),
    /// A sensor file already read.
    Loaded(Box<SensorFile>),
}

/// The views of a detection study.
#[derive(Debug, Clone, PartialEq)]
pub enum Views {
    /// A grid over the hemisphere, steps `(Δθ, Δφ)` in degrees.
    Grid((f64, f64)),
    /// Listed views `(θr, φr)` in degrees.
    List(Vec<(f64, f64)>),
}

impl Views {
    /// Every combination of the zeniths `theta_deg` with the azimuths `phi_deg` (zenith-major;
    /// no azimuth: 0°), as the adapters list views.
    pub fn listed(theta_deg: &[f64], phi_deg: &[f64]) -> Self {
        let phis: &[f64] = if phi_deg.is_empty() { &[0.0] } else { phi_deg };
        Views::List(
            theta_deg
                .iter()
                .flat_map(|t| phis.iter().map(move |p| (*t, *p)))
                .collect(),
        )
    }
}

/// A detection study (docs/detection.md).
#[derive(Debug, Clone, PartialEq)]
pub struct DetectRequest {
    /// The scene: target, background, sun, sky, `[path]`.
    pub scene: SceneSource,
    /// The sensor.
    pub sensor: SensorSource,
    /// The target material, replacing the scene's `[target]` material.
    pub target: Option<String>,
    /// The background material, likewise.
    pub background: Option<String>,
    /// The views.
    pub views: Views,
    /// Ranges (m) at which every view is evaluated (rows of `detect.csv`); may be empty with
    /// `search`.
    pub ranges_m: Vec<f64>,
    /// Search each view's detection range on `(0, range_limit_m]`.
    pub search: bool,
    /// The largest range searched (m).
    pub range_limit_m: f64,
    /// The target's area (m², a flat patch).
    pub area_m2: f64,
    /// False-alarm probability.
    pub pfa: f64,
    /// Required probability of detection.
    pub pd: f64,
    /// The features the detector may use (default all three).
    pub features: Vec<Feature>,
    /// The sun's `(zenith, azimuth)` in degrees, replacing the scene's `[sun]` position (its
    /// irradiance and Stokes vector kept): for a sweep over the time of day.
    pub sun_deg: Option<(f64, f64)>,
    /// The target material's fitted parameters and their covariance: gives the detection
    /// range an interval (docs/detection.md, "Uncertainty of the range"); needs `search`.
    pub target_fit: Option<FitSource>,
    /// The background material's, likewise.
    pub background_fit: Option<FitSource>,
    /// With a fit: the best-ranked views given an interval (`None`: every view).
    pub uncertainty_views: Option<usize>,
}

/// Where a material's fitted parameters and covariance come from.
#[derive(Debug, Clone, PartialEq)]
pub enum FitSource {
    /// A `fit.json` of `polbrdf fit`.
    File(PathBuf),
    /// A fit already read (e.g. from a `FitResult`).
    Loaded(Box<FitCovariance>),
}

/// The ranges of a study's rows when the adapters are not given any: 1000 m.
pub const DEFAULT_RANGES_M: [f64; 1] = [1000.0];

impl DetectRequest {
    /// The request `polbrdf detect --scene … --sensor …` and `polbrdf.detect(scene, sensor)`
    /// make without further options: [`DetectRequest::default`] with the rows at
    /// [`DEFAULT_RANGES_M`]. The adapters start from it and set what they are given, so that
    /// their defaults are these.
    pub fn new(scene: SceneSource, sensor: SensorSource) -> Self {
        Self {
            scene,
            sensor,
            ranges_m: DEFAULT_RANGES_M.to_vec(),
            ..Self::default()
        }
    }
}

impl Default for DetectRequest {
    /// A 1°×2° grid, range search to 10 km, a 1 m² target, `P_fa = 10⁻⁶`, `P_d = 0.9`, every
    /// feature, no fit (intervals for the best ten views when fits are given), no row ranges;
    /// scene and sensor empty paths (to be given). The adapters start from
    /// [`DetectRequest::new`].
    fn default() -> Self {
        let c = Criteria::default();
        Self {
            scene: SceneSource::File(PathBuf::new()),
            sensor: SensorSource::File(PathBuf::new()),
            target: None,
            background: None,
            views: Views::Grid(crate::hemisphere::DEFAULT_GRID_DEG),
            ranges_m: Vec::new(),
            search: true,
            range_limit_m: c.range_limit_m,
            area_m2: 1.0,
            pfa: c.pfa,
            pd: c.pd_required,
            features: c.features,
            sun_deg: None,
            target_fit: None,
            background_fit: None,
            uncertainty_views: Some(DEFAULT_UNCERTAINTY_VIEWS),
        }
    }
}

/// The scene of the request, with the sun moved when asked.
fn scene_of(request: &DetectRequest) -> TaskResult<Scene> {
    let mut scene = match &request.scene {
        SceneSource::File(p) => crate::scene::read_scene(p)?,
        SceneSource::Loaded(s) => (**s).clone(),
    };
    if scene.thermal.atmosphere != Atmosphere::default() {
        return Err(TaskError::Io(polbrdf_io::Error::File {
            path: scene.path.clone(),
            message: "[atmosphere] gives a fixed transmittance and path radiance; detection \
                      takes the path to the sensor from [path] (range-dependent): remove \
                      [atmosphere]"
                .into(),
        }));
    }
    if let Some((zenith, azimuth)) = request.sun_deg {
        let Some(sun) = scene.thermal.sun.as_mut() else {
            return Err(TaskError::usage(
                "sun_deg",
                format!("the scene {} has no [sun] to move", scene.path.display()),
            ));
        };
        let light = polbrdf::Illumination::from_degrees(zenith, azimuth, sun.stokes)?;
        sun.zenith = light.theta_i();
        sun.azimuth = light.phi_i();
    }
    Ok(scene)
}

/// The detector of the request and the sensor's spectrum.
fn detector_of(
    request: &DetectRequest,
    scene: &Scene,
    sensor: &SensorFile,
) -> TaskResult<(Detector, Spectrum)> {
    let spectrum = sensor.spectrum.clone();
    let nodes = spectrum.integral_nodes(&[]);
    let path = match &scene.air_path {
        Some(p) => p.path(&nodes)?,
        None => AirPath::none(),
    };
    let criteria = Criteria {
        pfa: request.pfa,
        pd_required: request.pd,
        range_limit_m: request.range_limit_m,
        features: request.features.clone(),
    };
    let field = |e: polbrdf::Error| match &e {
        polbrdf::Error::InvalidParameter { name, .. } => {
            let f = match *name {
                "area_m2" => "area_m2",
                "pfa" => "pfa",
                "pd" => "pd",
                "range_limit_m" => "range_limit_m",
                _ => return TaskError::Model(e),
            };
            TaskError::invalid(f, e.to_string())
        }
        polbrdf::Error::InconsistentParameters(_) => TaskError::invalid("features", e.to_string()),
        _ => TaskError::Model(e),
    };
    let detector =
        Detector::new(sensor.sensor.clone(), path, request.area_m2, criteria).map_err(field)?;
    Ok((detector, spectrum))
}

/// Views `(θr, φr)` in radians, and the grid they come from.
type ViewsRad = (Vec<(f64, f64)>, Option<ViewGrid>);

/// The views in radians, and the grid for grid views.
fn views_of(views: &Views) -> TaskResult<ViewsRad> {
    match views {
        Views::Grid(steps) => {
            let grid = view_grid(*steps)?;
            Ok((
                (0..grid.len()).map(|i| grid.direction(i)).collect(),
                Some(grid),
            ))
        }
        Views::List(list) => {
            if list.is_empty() {
                return Err(TaskError::invalid("theta_deg", "no view listed"));
            }
            let rad: Vec<(f64, f64)> = list
                .iter()
                .map(|(t, p)| (t.to_radians(), p.to_radians()))
                .collect();
            check_views(&rad).map_err(|e| TaskError::invalid("theta_deg", e.to_string()))?;
            Ok((rad, None))
        }
    }
}

/// Checks the request's ranges.
fn check_ranges(request: &DetectRequest) -> TaskResult<()> {
    if request.ranges_m.is_empty() && !request.search {
        return Err(TaskError::usage(
            "ranges_m",
            "give ranges, or a range search, or both",
        ));
    }
    if let Some(r) = request
        .ranges_m
        .iter()
        .find(|r| !(r.is_finite() && **r > 0.0))
    {
        return Err(TaskError::invalid(
            "ranges_m",
            format!("{r}: a range must be finite and > 0 (m)"),
        ));
    }
    Ok(())
}

/// How the scene is observed over the sensor's spectrum: over the band itself, or — when
/// nothing in the scene depends on the wavelength (constant refractive indices, no thermal
/// emission, no blackbody sky: the sun's and the sky's spectral radiances are constant across
/// a band) — at the band's centre, the result scaled by `∫ weight dλ`, which is then exact and
/// a band's quadrature nodes fewer times cheaper (docs/detection.md).
fn observation(
    scene: &Scene,
    materials: [&NamedMaterial; 2],
    spectrum: &Spectrum,
) -> (Spectrum, f64) {
    let flat = materials.iter().all(|m| !m.spec.is_spectral())
        && scene.target.temperature_k.is_none()
        && scene.background.temperature_k.is_none()
        && !matches!(
            scene.thermal.sky,
            polbrdf::analysis::SkyModel::Thermal { .. }
        );
    match spectrum {
        Spectrum::Band(band, _) if flat => {
            let total: f64 = spectrum.integral_nodes(&[]).iter().map(|n| n.1).sum();
            let (lo, hi) = band.range();
            (Spectrum::Wavelength(0.5 * (lo + hi)), total)
        }
        _ => (spectrum.clone(), 1.0),
    }
}

/// The target, the background and their observers.
type Observers = (NamedMaterial, NamedMaterial, Observer, Observer);

/// The observers of the target and the background over the sensor's spectrum, the spectrum
/// they observe over and the factor their observations are scaled by ([`observation`]).
fn observers(
    request: &DetectRequest,
    scene: &Scene,
    spectrum: &Spectrum,
) -> TaskResult<(Observers, Spectrum, f64)> {
    let target = material_of(request.target.as_deref(), "target", Some(&scene.target))?;
    let background = material_of(
        request.background.as_deref(),
        "background",
        Some(&scene.background),
    )?;
    let (spectrum, scale) = observation(scene, [&target, &background], spectrum);
    let observe = |m: &NamedMaterial, t: Option<f64>| {
        let thermal = scene.thermal.with_surface_temperature(t);
        Observer::new(&m.spec, &thermal, &spectrum)
            .map_err(|e| TaskError::invalid(&m.field, format!("{}: {e}", m.source)))
    };
    let ot = observe(&target, scene.target.temperature_k)?;
    let ob = observe(&background, scene.background.temperature_k)?;
    Ok(((target, background, ot, ob), spectrum, scale))
}

/// The ranges of a view's rows: the request's; without them (a search only), the view's
/// detection range, or the range limit when it is beyond it or the target is not detectable
/// (docs/detection.md).
fn row_ranges(ranges: &[f64], max_range: Option<MaxRange>, limit: f64) -> Vec<f64> {
    if !ranges.is_empty() {
        return ranges.to_vec();
    }
    match max_range {
        Some(MaxRange::At { range_m, .. }) => vec![range_m],
        _ => vec![limit],
    }
}

/// Runs a detection study. Everything is validated (ranges, views, scene, sensor, criteria,
/// materials) before anything is computed.
///
/// # Errors
/// [`TaskError::Invalid`] / [`TaskError::Usage`] naming the request field; [`TaskError::Io`]
/// for the scene and sensor files (naming file, line and key); [`TaskError::Model`] for what
/// the model refuses.
pub fn detect(request: &DetectRequest) -> TaskResult<DetectStudy> {
    check_ranges(request)?;
    let (dirs, grid) = views_of(&request.views)?;
    let scene = scene_of(request)?;
    let sensor = match &request.sensor {
        SensorSource::File(p) => polbrdf_io::read_sensor(p)?,
        SensorSource::Loaded(s) => (**s).clone(),
    };
    let (detector, spectrum) = detector_of(request, &scene, &sensor)?;
    if let Some(max) = detector.path.max_range() {
        if let Some(r) = request.ranges_m.iter().find(|r| **r > max) {
            return Err(TaskError::invalid(
                "ranges_m",
                format!("{r}: beyond the last row of the path table ({max} m; never extrapolated)"),
            ));
        }
    }
    let ((target, background, ot, ob), observed, scale) = observers(request, &scene, &spectrum)?;
    let fits = fits_of(request, [&target, &background])?;
    let quality = if grid.is_some() {
        Quality::Map
    } else {
        Quality::Full
    };
    let st = ot.observe_with(&dirs, quality);
    let sb = ob.observe_with(&dirs, quality);
    let mut views = Vec::with_capacity(dirs.len());
    let scaled = |s: &Stokes| Stokes(s.0.map(|x| x * scale));
    for (t, b) in st.iter().zip(&sb) {
        let (ts, bs) = (scaled(&t.stokes), scaled(&b.stokes));
        let max_range = if request.search {
            Some(detector.max_range(&ts, &bs, t.theta_r)?)
        } else {
            None
        };
        let at_ranges = row_ranges(&request.ranges_m, max_range, request.range_limit_m)
            .into_iter()
            .map(|r| detector.detect(&ts, &bs, t.theta_r, r))
            .collect::<Result<Vec<_>, _>>()?;
        views.push(ViewResult {
            theta_r: t.theta_r,
            phi_r: t.phi_r,
            target: ts,
            background: bs,
            at_ranges,
            max_range,
            range_uncertainty: None,
        });
    }
    if fits.iter().any(Option::is_some) {
        let propagation = Propagation {
            detector: &detector,
            scene: &scene,
            materials: [&target, &background],
            fits: [fits[0].as_ref(), fits[1].as_ref()],
            spectrum: &observed,
            scale,
            quality,
        };
        let order = out::ranked_order(&views);
        let n = request.uncertainty_views.unwrap_or(order.len());
        for &i in order.iter().take(n) {
            views[i].range_uncertainty = propagation.of_view(&views[i])?;
        }
    }
    let mut study = DetectStudy {
        scene: Box::new(scene),
        sensor: Box::new(sensor),
        target,
        background,
        detector,
        spectrum,
        grid,
        views,
        ranges_m: request.ranges_m.clone(),
        warnings: Vec::new(),
        fits,
        uncertainty_views: request.uncertainty_views,
    };
    study.warnings = warnings::warnings(&study);
    Ok(study)
}

/// The request's fits, read and checked against the materials (before anything is computed).
fn fits_of(
    request: &DetectRequest,
    materials: [&NamedMaterial; 2],
) -> TaskResult<[Option<FitCovariance>; 2]> {
    let sources = [
        ("target_fit", "target", &request.target_fit),
        ("background_fit", "background", &request.background_fit),
    ];
    if let Some((field, ..)) = sources.iter().find(|s| s.2.is_some()) {
        if !request.search {
            return Err(TaskError::usage(
                *field,
                "gives the detection range an interval, which needs the range search: it is \
                 off",
            ));
        }
        if request.uncertainty_views == Some(0) {
            return Err(TaskError::invalid(
                "uncertainty_views",
                "0: give at least one view (or every view)",
            ));
        }
    }
    let mut out = [None, None];
    for (k, (_, role, source)) in sources.into_iter().enumerate() {
        let fit = match source {
            None => continue,
            Some(FitSource::File(p)) => FitCovariance::read(p)?,
            Some(FitSource::Loaded(f)) => (**f).clone(),
        };
        fit.check_material(&materials[k].spec, role, &materials[k].source)?;
        out[k] = Some(fit);
    }
    Ok(out)
}
