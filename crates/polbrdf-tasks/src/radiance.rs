//! The observed Stokes radiance of one surface in a scene (docs/model.md §17) at a set of view
//! directions: its thermal emission, the sun and sky it reflects, and the atmosphere.

use crate::error::{TaskError, TaskResult};
use crate::scene::{check_single_surface, observer, read_scene};
use crate::spectrum::NamedMaterial;
use polbrdf::analysis::scene::Observer;
use polbrdf::Stokes;
use polbrdf_io::Scene;
use std::path::PathBuf;

/// The view directions of a radiance request, degrees.
#[derive(Debug, Clone, PartialEq)]
pub enum Views {
    /// Every combination of the zenith angles (in [0, 90); empty: 0, 5, …, 85) and the
    /// azimuths (finite; empty: 0).
    Grid {
        /// View zenith angles.
        theta_deg: Vec<f64>,
        /// View azimuths.
        phi_deg: Vec<f64>,
    },
    /// The directions `(θr, φr)` as listed (e.g. read from a views CSV, already checked).
    List(Vec<(f64, f64)>),
}

impl Views {
    /// The zenith angles and azimuths of a grid, defaults filled in and checked.
    ///
    /// # Errors
    /// [`TaskError::Invalid`] naming `theta_deg` or `phi_deg`.
    pub fn grid_axes(theta_deg: &[f64], phi_deg: &[f64]) -> TaskResult<(Vec<f64>, Vec<f64>)> {
        let thetas: Vec<f64> = if theta_deg.is_empty() {
            (0..18).map(|k| 5.0 * f64::from(k)).collect()
        } else {
            theta_deg.to_vec()
        };
        let phis = if phi_deg.is_empty() {
            vec![0.0]
        } else {
            phi_deg.to_vec()
        };
        if let Some(bad) = thetas.iter().find(|t| !(**t >= 0.0 && **t < 90.0)) {
            return Err(TaskError::invalid(
                "theta_deg",
                format!("{bad}: the view zenith angle must lie in [0, 90)"),
            ));
        }
        if let Some(bad) = phis.iter().find(|p| !p.is_finite()) {
            return Err(TaskError::invalid(
                "phi_deg",
                format!("{bad}: must be finite"),
            ));
        }
        Ok((thetas, phis))
    }

    /// The directions, degrees, zenith-major for a grid.
    ///
    /// # Errors
    /// As [`Views::grid_axes`].
    pub fn directions(&self) -> TaskResult<Vec<(f64, f64)>> {
        match self {
            Views::List(v) => Ok(v.clone()),
            Views::Grid { theta_deg, phi_deg } => {
                let (thetas, phis) = Self::grid_axes(theta_deg, phi_deg)?;
                Ok(thetas
                    .iter()
                    .flat_map(|t| phis.iter().map(move |p| (*t, *p)))
                    .collect())
            }
        }
    }
}

/// The most work a radiance request may imply ([`polbrdf::analysis::scene::Observer::work`]):
/// 10⁸ evaluations at one spectral node, about 2 minutes on one core of the reference host
/// (docs/io.md "Resource model"): 10⁸ views × spectral nodes of a scene without an
/// azimuth-dependent sky, 10⁵ under a cie-clear or table sky.
pub const MAX_WORK: f64 = 1e8;

/// The field of [`check_work`]'s error: the views as a whole (a grid's two axes or a list).
pub const VIEWS_FIELD: &str = "views";

/// Refuses, before anything is computed, an observation of `views` views whose work exceeds
/// [`MAX_WORK`].
///
/// # Errors
/// [`TaskError::Usage`] of the field [`VIEWS_FIELD`] (the adapters name their options or
/// arguments for it), its message naming the views, the spectral nodes, the sky, the work and
/// the limit.
pub fn check_work(observer: &Observer, views: usize) -> TaskResult<()> {
    let work = observer.work(views);
    if work <= MAX_WORK {
        return Ok(());
    }
    let sky = if observer.has_azimuth_sky() {
        "under an azimuth-dependent sky (one sky integral per view and node)"
    } else {
        "without an azimuth-dependent sky"
    };
    Err(TaskError::usage(
        VIEWS_FIELD,
        format!(
            "{views} view(s) × {} spectral node(s) {sky} imply {work:.3e} units of work, at \
             most {MAX_WORK:.0e} (about 2 minutes on one core; see docs/io.md, Resource model): \
             give fewer views, or a coarser band step",
            observer.spectral_nodes()
        ),
    ))
}

/// A radiance request.
#[derive(Debug, Clone, PartialEq)]
pub struct RadianceRequest {
    /// A material file or a preset name.
    pub material: String,
    /// The scene file: spectrum, `[surface]`, sun, sky, atmosphere (no `[target]` or
    /// `[background]`: those are for a contrast).
    pub scene: PathBuf,
    /// The view directions.
    pub views: Views,
}

/// The result of [`radiance`].
#[derive(Debug, Clone)]
pub struct RadianceTable {
    /// The material.
    pub material: NamedMaterial,
    /// The scene.
    pub scene: Scene,
    /// `(θr, φr)` in degrees and the observed Stokes radiance, per view.
    pub rows: Vec<(f64, f64, Stokes)>,
}

impl RadianceTable {
    /// The columns of the table (a contract: other tools build on it).
    pub const COLUMNS: [&'static str; 8] = [
        "theta_r_deg",
        "phi_r_deg",
        "s0",
        "s1",
        "s2",
        "s3",
        "dolp",
        "aolp_deg",
    ];

    /// The values of [`RadianceTable::COLUMNS`], one row per view.
    pub fn values(&self) -> impl Iterator<Item = [f64; 8]> + '_ {
        self.rows.iter().map(|(t, p, s)| {
            [
                *t,
                *p,
                s.0[0],
                s.0[1],
                s.0[2],
                s.0[3],
                s.dolp(),
                s.aolp().to_degrees(),
            ]
        })
    }
}

/// The observed Stokes radiance at each view: W·m⁻²·sr⁻¹·µm⁻¹ at one wavelength,
/// W·m⁻²·sr⁻¹ over a band (`∫R(λ)·S(λ)dλ`).
///
/// # Errors
/// [`TaskError::Invalid`] naming `theta_deg`, `phi_deg` or `material`; [`TaskError::Io`] for
/// the scene file (also a scene with `[target]` or `[background]`, naming the file and the
/// table) and the material file.
pub fn radiance(request: &RadianceRequest) -> TaskResult<RadianceTable> {
    let views = request.views.directions()?;
    let scene = read_scene(&request.scene)?;
    check_single_surface(&scene)?;
    let material = NamedMaterial::load(&request.material, "material")?;
    let observer = observer(
        &material,
        &scene,
        scene.thermal.surface_temperature_k,
        ("material", &request.material),
    )?;
    check_work(&observer, views.len())?;
    let radians: Vec<(f64, f64)> = views
        .iter()
        .map(|(t, p)| (t.to_radians(), p.to_radians()))
        .collect();
    let observed = observer.observe(&radians);
    let rows = views
        .iter()
        .zip(&observed)
        .map(|((t, p), r)| (*t, *p, r.stokes))
        .collect();
    Ok(RadianceTable {
        material,
        scene,
        rows,
    })
}
