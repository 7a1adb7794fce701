//! Target against background over the viewing hemisphere (docs/model.md §11, §17–18): under
//! one collimated source (at a wavelength or over a band) or in a scene, the contrast map, the
//! best directions ranked and refined, and in a scene the polarization-null loci — as plain
//! values, with the `contrast.csv` table and the `best.json` document built from them.

use crate::error::{TaskError, TaskResult};
use crate::hemisphere::{deg, invalid_zeniths, view_grid, LightRequest};
use crate::scene::{contrast_warnings, observer, read_scene, Warning};
use crate::spectrum::{materials_at, NamedMaterial, SpectralRequest, SpectrumSource};
use polbrdf::analysis::contrast::{
    polarization_null, Contrast, ContrastMap, ContrastSample, Illumination, RankOptions, Ranking,
};
use polbrdf::analysis::scene::null_temperature;
use polbrdf::analysis::sky::Quality;
use polbrdf::{Material, Spectrum};
use polbrdf_io::Scene;
use std::path::PathBuf;

/// How the best directions are listed (degrees, as given).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RankRequest {
    /// The score.
    pub by: Ranking,
    /// How many directions (≥ 1).
    pub top: usize,
    /// Minimum angle between two listed directions, degrees, in [0, 180].
    pub min_separation_deg: f64,
    /// Largest viewing zenith angle ranked, degrees, in (0, 90).
    pub max_zenith_deg: f64,
    /// Refine each direction by brute force around its grid node.
    pub refine: bool,
}

impl Default for RankRequest {
    /// The defaults of [`RankOptions::default`], in degrees.
    fn default() -> Self {
        let d = RankOptions::default();
        Self {
            by: d.by,
            top: d.count,
            min_separation_deg: d.min_separation.to_degrees().round(),
            max_zenith_deg: d.max_zenith.to_degrees().round(),
            refine: d.refine,
        }
    }
}

impl RankRequest {
    /// The validated ranking options.
    ///
    /// # Errors
    /// [`TaskError::Invalid`] naming `top`, `min_separation_deg` or `max_zenith_deg`;
    /// [`TaskError::Limit`] for a `top` over [`crate::limits::TOP`].
    pub fn options(&self) -> TaskResult<RankOptions> {
        if self.top == 0 {
            return Err(TaskError::invalid("top", "must be at least 1"));
        }
        crate::limits::at_most("top", self.top, crate::limits::TOP)?;
        let sep = self.min_separation_deg;
        if !(sep.is_finite() && (0.0..=180.0).contains(&sep)) {
            return Err(TaskError::invalid(
                "min_separation_deg",
                format!("{sep}: must lie in [0, 180]"),
            ));
        }
        let max = self.max_zenith_deg;
        if !(max > 0.0 && max < 90.0) {
            return Err(TaskError::invalid(
                "max_zenith_deg",
                format!("{max}: must lie in (0, 90)"),
            ));
        }
        Ok(RankOptions {
            by: self.by,
            count: self.top,
            min_separation: sep.to_radians(),
            max_zenith: max.to_radians(),
            refine: self.refine,
        })
    }
}

/// Where target and background are compared.
#[derive(Debug, Clone, PartialEq)]
pub enum SourceRequest {
    /// Under one collimated source, per unit irradiance.
    Collimated {
        /// The source.
        light: LightRequest,
        /// The wavelength or band.
        spectral: SpectralRequest,
    },
    /// In a scene file (its materials unless the request names them).
    Scene(PathBuf),
    /// In a scene already read and validated by polbrdf-io's reader (an adapter holding the
    /// scene's text rather than a file, e.g. Python's `polbrdf.Scene`): as [`Self::Scene`].
    Loaded(Box<Scene>),
}

/// A contrast study.
#[derive(Debug, Clone, PartialEq)]
pub struct ContrastRequest {
    /// The target: a material file or preset (required without a scene's `[target]` material).
    pub target: Option<String>,
    /// The background, likewise.
    pub background: Option<String>,
    /// The source or the scene.
    pub source: SourceRequest,
    /// Grid steps `(Δθ, Δφ)`, degrees.
    pub grid_deg: (f64, f64),
    /// The ranking.
    pub rank: RankRequest,
}

/// Where the comparison was made, resolved.
#[derive(Debug, Clone)]
pub enum Setting {
    /// One collimated source; `nodes` spectral nodes.
    Collimated {
        /// The source.
        light: Illumination,
        /// The spectrum.
        spectrum: Option<Spectrum>,
        /// Number of spectral nodes.
        nodes: usize,
    },
    /// A scene file.
    Scene(Box<Scene>),
}

/// The polarization-null loci `(θr, φr)` (rad) of a scene's target and background maps.
#[derive(Debug, Clone, PartialEq)]
pub struct NullLoci {
    /// On the target's map.
    pub target: Vec<(f64, f64)>,
    /// On the background's map.
    pub background: Vec<(f64, f64)>,
    /// Under a uniform sky, the temperature at which both lose their polarization everywhere.
    pub uniform_sky_temperature_k: Option<f64>,
}

/// The grid zeniths (rad) where each material's model is flagged invalid
/// ([`crate::hemisphere::invalid_zeniths`]: its emissivity outside `[0, 1]` at some spectral
/// node), as `polbrdf map` marks them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct InvalidZeniths {
    /// The target's.
    pub target: Vec<f64>,
    /// The background's.
    pub background: Vec<f64>,
}

impl InvalidZeniths {
    /// The zeniths where either model is flagged invalid, increasing: where a comparison of
    /// the two (ΔDoLP, the intensity ratio, …) rests on an invalid model.
    pub fn either(&self) -> Vec<f64> {
        let mut v: Vec<f64> = self
            .target
            .iter()
            .chain(&self.background)
            .copied()
            .collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v
    }
}

/// The result of [`contrast`].
#[derive(Debug, Clone)]
pub struct ContrastStudy {
    /// The target.
    pub target: NamedMaterial,
    /// The background.
    pub background: NamedMaterial,
    /// The source or the scene.
    pub setting: Setting,
    /// The problem (for further evaluations, e.g. at other directions).
    pub problem: Contrast,
    /// The map over the grid.
    pub map: ContrastMap,
    /// The best directions, best first.
    pub top: Vec<ContrastSample>,
    /// The ranking as requested (degrees).
    pub rank: RankRequest,
    /// The ranking as used (radians).
    pub options: RankOptions,
    /// In a scene, the null loci: computed where S2 vanishes identically (a scene symmetric
    /// about the normal), empty otherwise. `None` under a collimated source.
    pub nulls: Option<NullLoci>,
    /// The setup's warnings.
    pub warnings: Vec<Warning>,
    /// Where each model is flagged invalid.
    pub invalid_zeniths: InvalidZeniths,
}

/// Resolves a material: the request's, else the scene table's.
pub(crate) fn material_of(
    arg: Option<&str>,
    field: &str,
    scene: Option<&polbrdf_io::SceneObject>,
) -> TaskResult<NamedMaterial> {
    if let Some(a) = arg {
        return NamedMaterial::load(a, field);
    }
    match scene.and_then(|o| o.material.clone()) {
        Some((spec, name)) => Ok(NamedMaterial {
            spec,
            source: name.clone(),
            name,
            field: "scene".into(),
        }),
        None => Err(TaskError::usage(
            field,
            if scene.is_some() {
                format!("is required (or a `material` in the scene's [{field}] table)")
            } else {
                "is required".into()
            },
        )),
    }
}

/// The problem of a scene contrast: both observers, with the setup's warnings.
fn scene_problem(
    request: &ContrastRequest,
    scene: &Scene,
) -> TaskResult<(NamedMaterial, NamedMaterial, Contrast)> {
    let target = material_of(request.target.as_deref(), "target", Some(&scene.target))?;
    let background = material_of(
        request.background.as_deref(),
        "background",
        Some(&scene.background),
    )?;
    // Errors name the request field, or the scene's table the material came from.
    let what = |arg: &Option<String>, table: &str| match arg {
        Some(a) => (table.to_string(), a.clone()),
        None => (
            "scene".to_string(),
            format!("{}: [{table}] material", scene.path.display()),
        ),
    };
    let (tf, tw) = what(&request.target, "target");
    let (bf, bw) = what(&request.background, "background");
    let problem = Contrast::scene(
        observer(&target, scene, scene.target.temperature_k, (&tf, &tw))?,
        observer(
            &background,
            scene,
            scene.background.temperature_k,
            (&bf, &bw),
        )?,
    );
    Ok((target, background, problem))
}

/// The problem of a collimated contrast.
fn collimated_problem(
    request: &ContrastRequest,
    light: Illumination,
    spectrum: Option<&Spectrum>,
) -> TaskResult<(NamedMaterial, NamedMaterial, Contrast, usize)> {
    let target = material_of(request.target.as_deref(), "target", None)?;
    let background = material_of(request.background.as_deref(), "background", None)?;
    let (problem, count) = collimated_nodes(&target, &background, light, spectrum)?;
    Ok((target, background, problem, count))
}

/// The problem of a collimated contrast of two materials, and its number of spectral nodes.
fn collimated_nodes(
    target: &NamedMaterial,
    background: &NamedMaterial,
    light: Illumination,
    spectrum: Option<&Spectrum>,
) -> TaskResult<(Contrast, usize)> {
    let nodes = materials_at(&[target, background], spectrum)?;
    let count = nodes.len();
    let problem = Contrast::spectral(
        nodes
            .into_iter()
            .map(|(w, mut ms)| {
                let b = ms.remove(1);
                (w, ms.remove(0), b)
            })
            .collect(),
        light,
    );
    Ok((problem, count))
}

/// The setup of a scene contrast: both materials, the problem, the setting and the warnings.
type SceneSetup = (
    NamedMaterial,
    NamedMaterial,
    Contrast,
    Setting,
    Vec<Warning>,
);

/// The setup of a contrast in `scene`.
fn scene_setup(request: &ContrastRequest, scene: Scene) -> TaskResult<SceneSetup> {
    let warnings = contrast_warnings(&scene);
    let (t, b, problem) = scene_problem(request, &scene)?;
    Ok((t, b, problem, Setting::Scene(Box::new(scene)), warnings))
}

/// Runs a contrast study. Everything is validated (ranking, grid, source, files, materials)
/// before anything is computed.
///
/// # Errors
/// [`TaskError::Invalid`] / [`TaskError::Usage`] naming the request field; [`TaskError::Io`]
/// for the scene, band and material files; [`TaskError::Model`] for a source or grid the model
/// refuses.
pub fn contrast(request: &ContrastRequest) -> TaskResult<ContrastStudy> {
    contrast_with_progress(request, &mut |_, _| {})
}

/// [`contrast`], calling `progress(directions done, directions)` as the map of a scene is
/// computed (its sky integrals are the slow part: seconds at the default grid), from
/// `(0, n)` to `(n, n)`; under a collimated source (milliseconds) only `(n, n)` at the end.
/// The numbers are [`contrast`]'s, bit for bit.
///
/// # Errors
/// As [`contrast`].
pub fn contrast_with_progress(
    request: &ContrastRequest,
    progress: &mut dyn FnMut(usize, usize),
) -> TaskResult<ContrastStudy> {
    let options = request.rank.options()?;
    let (target, background, problem, setting, warnings) = match &request.source {
        SourceRequest::Scene(path) => {
            let _ = view_grid(request.grid_deg)?;
            scene_setup(request, read_scene(path)?)?
        }
        SourceRequest::Loaded(scene) => {
            let _ = view_grid(request.grid_deg)?;
            scene_setup(request, (**scene).clone())?
        }
        SourceRequest::Collimated { light, spectral } => {
            let light = light.illumination()?;
            let _ = view_grid(request.grid_deg)?;
            let spectrum = spectral.spectrum()?;
            let (t, b, problem, nodes) = collimated_problem(request, light, spectrum.as_ref())?;
            let setting = Setting::Collimated {
                light,
                spectrum,
                nodes,
            };
            (t, b, problem, setting, Vec::new())
        }
    };
    let grid = view_grid(request.grid_deg)?;
    let map = map_with_progress(&problem, &setting, &grid, progress);
    Ok(study(
        (target, background),
        (problem, map),
        setting,
        warnings,
        (request.rank, options),
    ))
}

/// Blocks of a scene's map between two progress reports.
const PROGRESS_BLOCKS: usize = 100;

/// `problem.map(grid)`, a scene's in at most [`PROGRESS_BLOCKS`] blocks of whole zenith rows
/// with a progress report after each (the blocks give the same numbers bit for bit: tested).
fn map_with_progress(
    problem: &Contrast,
    setting: &Setting,
    grid: &polbrdf::ViewGrid,
    progress: &mut dyn FnMut(usize, usize),
) -> ContrastMap {
    let n = grid.len();
    if !matches!(setting, Setting::Scene(_)) {
        let map = problem.map(grid);
        progress(n, n);
        return map;
    }
    let dirs: Vec<(f64, f64)> = (0..n).map(|i| grid.direction(i)).collect();
    let mut samples = Vec::with_capacity(n);
    progress(0, n);
    // Whole zenith rows per block: a scene's sky integrals are shared along a row.
    let row = grid.phis().len().max(1);
    let rows = (n / row).div_ceil(PROGRESS_BLOCKS).max(1);
    for block in dirs.chunks(rows * row) {
        samples.extend(problem.at_all_with(block, Quality::Map));
        progress(samples.len(), n);
    }
    ContrastMap {
        grid: grid.clone(),
        samples,
    }
}

/// A contrast study under a collimated source of two materials already read (an adapter
/// holding the materials' text, e.g. the web explorer, parses them with
/// [`NamedMaterial::parse`]): as [`contrast`] with [`SourceRequest::Collimated`].
///
/// # Errors
/// As [`contrast`]: the ranking, the source, the grid, the spectrum, then the materials at it.
pub fn contrast_of(
    target: NamedMaterial,
    background: NamedMaterial,
    light: &LightRequest,
    spectral: &impl SpectrumSource,
    grid_deg: (f64, f64),
    rank: RankRequest,
) -> TaskResult<ContrastStudy> {
    let options = rank.options()?;
    let light = light.illumination()?;
    let grid = view_grid(grid_deg)?;
    let spectrum = spectral.spectrum()?;
    let (problem, nodes) = collimated_nodes(&target, &background, light, spectrum.as_ref())?;
    let setting = Setting::Collimated {
        light,
        spectrum,
        nodes,
    };
    let map = problem.map(&grid);
    Ok(study(
        (target, background),
        (problem, map),
        setting,
        Vec::new(),
        (rank, options),
    ))
}

/// The map, the ranking and the null loci of a problem set up.
fn study(
    (target, background): (NamedMaterial, NamedMaterial),
    (problem, map): (Contrast, ContrastMap),
    setting: Setting,
    warnings: Vec<Warning>,
    (rank, options): (RankRequest, RankOptions),
) -> ContrastStudy {
    let top = problem.rank(&map, &options);
    let nulls = match &setting {
        Setting::Scene(s) => Some(null_loci(&problem, &map, s)),
        Setting::Collimated { .. } => None,
    };
    let invalid_zeniths = invalid_regions(&problem, &setting, (&target, &background), &map.grid);
    ContrastStudy {
        target,
        background,
        setting,
        problem,
        map,
        top,
        rank,
        options,
        nulls,
        warnings,
        invalid_zeniths,
    }
}

/// Where each model is flagged invalid, at the spectral nodes the problem evaluates it at: the
/// mean's nodes under a collimated source, the scene's integral nodes in a scene.
fn invalid_regions(
    problem: &Contrast,
    setting: &Setting,
    (target, background): (&NamedMaterial, &NamedMaterial),
    grid: &polbrdf::ViewGrid,
) -> InvalidZeniths {
    match setting {
        Setting::Collimated { .. } => {
            let nodes = problem.nodes();
            let t: Vec<&Material> = nodes.iter().map(|(_, t, _)| t).collect();
            let b: Vec<&Material> = nodes.iter().map(|(_, _, b)| b).collect();
            InvalidZeniths {
                target: invalid_zeniths(&t, grid),
                background: invalid_zeniths(&b, grid),
            }
        }
        Setting::Scene(scene) => {
            // The observers were built from the same materials at the same nodes, so these
            // build too; a material that did not would have no flag.
            let flagged = |m: &NamedMaterial| {
                let nodes = scene.spectrum.integral_nodes(&[&m.spec]);
                Spectrum::materials(&m.spec, &nodes).map_or_else(
                    |_| Vec::new(),
                    |ms| invalid_zeniths(&ms.iter().collect::<Vec<_>>(), grid),
                )
            };
            InvalidZeniths {
                target: flagged(target),
                background: flagged(background),
            }
        }
    }
}

/// The null locus is where S1 changes sign while S2 vanishes identically: in scenes symmetric
/// about the normal. Under a sun or an azimuth-dependent sky an S1 sign change is the AoLP
/// turning through ±45°, no null: none is listed.
fn null_loci(problem: &Contrast, map: &ContrastMap, scene: &Scene) -> NullLoci {
    if problem.is_azimuth_independent() {
        NullLoci {
            target: polarization_null(map, true),
            background: polarization_null(map, false),
            uniform_sky_temperature_k: null_temperature(&scene.thermal.sky, &scene.spectrum),
        }
    } else {
        NullLoci {
            target: Vec::new(),
            background: Vec::new(),
            uniform_sky_temperature_k: None,
        }
    }
}

/// The columns of a contrast table (`contrast.csv`), and of each direction in `best.json`.
pub const COLUMNS: [&str; 12] = [
    "theta_r_deg",
    "phi_r_deg",
    "dolp_target",
    "dolp_background",
    "delta_dolp",
    "intensity_target",
    "intensity_background",
    "intensity_ratio",
    "aolp_target_deg",
    "aolp_background_deg",
    "aolp_difference_deg",
    "polarization_contrast",
];

/// The extra column of a scene's table: S0 of the target − S0 of the background.
pub const SCENE_COLUMN: &str = "radiance_difference";

/// The values of [`COLUMNS`] of one direction.
pub fn row(s: &ContrastSample) -> Vec<f64> {
    vec![
        deg(s.theta_r),
        deg(s.phi_r),
        s.dolp_target(),
        s.dolp_background(),
        s.delta_dolp(),
        s.target.0[0],
        s.background.0[0],
        s.intensity_ratio(),
        s.target.aolp().to_degrees(),
        s.background.aolp().to_degrees(),
        s.aolp_difference().to_degrees(),
        s.polarization_contrast(),
    ]
}

impl ContrastStudy {
    /// Whether the study is in a scene.
    pub fn is_scene(&self) -> bool {
        matches!(self.setting, Setting::Scene(_))
    }

    /// The header of [`ContrastStudy::rows`]: [`COLUMNS`], and in a scene [`SCENE_COLUMN`].
    pub fn columns(&self) -> Vec<&'static str> {
        let mut c = COLUMNS.to_vec();
        if self.is_scene() {
            c.push(SCENE_COLUMN);
        }
        c
    }

    /// One row per grid direction (`contrast.csv`).
    pub fn rows(&self) -> impl Iterator<Item = Vec<f64>> + '_ {
        let scene = self.is_scene();
        self.map.samples.iter().map(move |s| {
            let mut r = row(s);
            if scene {
                r.push(s.radiance_difference());
            }
            r
        })
    }
}
