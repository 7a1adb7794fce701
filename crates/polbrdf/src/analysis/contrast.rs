//! Target against background: polarization contrast over the viewing hemisphere, and the best
//! viewing directions (docs/model.md §11).
//!
//! Both materials are lit from the same direction by the same input Stokes vector
//! ([`Illumination`]) and looked at from every direction of a regular grid over the viewing
//! hemisphere ([`ViewGrid`]). At each direction the reflected Stokes vectors
//! `S_t = F_target·S_in` and `S_b = F_background·S_in` (per unit incident irradiance, psps basis
//! of the reflected beam, which is the same for both) give ([`ContrastSample`]):
//!
//! | quantity | definition |
//! |---|---|
//! | `dolp_target`, `dolp_background` | `sqrt(S1² + S2²)/S0` of `S_t`, `S_b` (eq. 13) |
//! | `delta_dolp` | `DoLP_t − DoLP_b` |
//! | `intensity_ratio` | `S0_t / S0_b` (the BRDF ratio for unpolarized input) |
//! | `aolp_difference` | `AoLP_t − AoLP_b` folded into (−90°, 90°]; 0 when either beam has no linear polarization |
//! | `polarization_contrast` | `sqrt((S1_t − S1_b)² + (S2_t − S2_b)²) / ((S0_t + S0_b)/2)` |
//!
//! The polarization contrast is the amplitude of the part of the target–background radiance
//! difference that a rotating linear analyzer modulates, relative to the mean radiance: through
//! an analyzer at angle ψ a camera sees `I(ψ) = ½(S0 + S1 cos2ψ + S2 sin2ψ)`, so the difference
//! `I_t(ψ) − I_b(ψ)` swings by `½·|ΔS_lin|` around `½ΔS0`. It equals `|ΔDoLP|` when the two
//! intensities and AoLPs are equal, grows with an AoLP difference (`2·DoLP·|sin ΔAoLP|` at equal
//! DoLP and intensity), and weighs each DoLP by its intensity: a dark target's polarization
//! counts for less. It lies in `[0, 2]`.
//!
//! [`Contrast::rank`] lists the best directions ([`Ranking`]) with viewing zenith angle up to
//! [`RankOptions::max_zenith`] (80° by default): sorted by score, each one at least
//! [`RankOptions::min_separation`] (great-circle angle between viewing directions) from every
//! better one (greedy non-maximum suppression), then optionally refined by brute force around
//! its grid node.
//!
//! By aspect: the illumination (`illumination`), the viewing grid (`grid`), one material's
//! hemisphere (`hemisphere`), the contrast quantities of one direction (`sample`), the ranking
//! (`rank`) and refinement (`refine`) of the best directions, the null loci (`null`); this file
//! holds the comparison itself, [`Contrast`], and its maps.

use crate::analysis::scene::Observer;
use crate::analysis::sky::Quality;
use crate::engine::{Engine, Kernel};
use crate::geometry::Geometry;
use crate::model::Material;
use crate::optics::stokes::Stokes;

mod grid;
mod hemisphere;
mod illumination;
mod null;
mod rank;
mod refine;
mod sample;

pub use grid::{ViewGrid, MAX_GRID_DIRECTIONS};
pub use hemisphere::{hemisphere, hemisphere_mean, ViewSample};
pub use illumination::Illumination;
pub use null::polarization_null;
pub use rank::{separation, RankOptions, Ranking};
pub use sample::ContrastSample;

/// Target and background compared at every view direction: either under one collimated
/// source, per unit irradiance, at one wavelength or over a band — the reflected Stokes vectors
/// are the weighted sums over spectral nodes `S = Σ w_j·F_j·S_in` (one node of weight 1 for a
/// single wavelength; a band's normalized quadrature weights otherwise,
/// `crate::analysis::spectral`) — or in a scene ([`Contrast::scene`]: each surface's observed
/// Stokes radiance, emission and sky included, docs/model.md §17). Every derived quantity
/// comes from (band-integrated) Stokes vectors.
#[derive(Debug, Clone)]
pub struct Contrast {
    source: Source,
}

#[derive(Debug, Clone)]
enum Source {
    /// `(weight, target, background)` per spectral node, under one collimated source.
    Collimated {
        nodes: Vec<(f64, Material, Material)>,
        light: Illumination,
    },
    /// Each surface in its scene.
    Scene {
        target: Box<Observer>,
        background: Box<Observer>,
    },
}

/// [`ContrastSample`]s at every node of a [`ViewGrid`], zenith-major.
#[derive(Debug, Clone, PartialEq)]
pub struct ContrastMap {
    /// The grid.
    pub grid: ViewGrid,
    /// One sample per node, `samples[k·n_phi + j]`.
    pub samples: Vec<ContrastSample>,
}

impl Contrast {
    /// Target, background and illumination, at one wavelength (the materials as given).
    pub fn new(target: &Material, background: &Material, light: Illumination) -> Self {
        Self {
            source: Source::Collimated {
                nodes: vec![(1.0, target.clone(), background.clone())],
                light,
            },
        }
    }

    /// Over spectral nodes `(weight, target, background)` (the weights of a mean, summing to
    /// 1: `Spectrum::mean_nodes`).
    ///
    /// # Panics
    /// When `nodes` is empty.
    pub fn spectral(nodes: Vec<(f64, Material, Material)>, light: Illumination) -> Self {
        assert!(!nodes.is_empty(), "at least one spectral node");
        Self {
            source: Source::Collimated { nodes, light },
        }
    }

    /// Target and background each observed in its scene (typically the same sky, band and
    /// atmosphere with each surface's own temperature): their observed Stokes radiances.
    pub fn scene(target: Observer, background: Observer) -> Self {
        Self {
            source: Source::Scene {
                target: Box::new(target),
                background: Box::new(background),
            },
        }
    }

    /// The collimated illumination, `None` in a scene without one.
    pub fn light(&self) -> Option<Illumination> {
        match &self.source {
            Source::Collimated { light, .. } => Some(*light),
            Source::Scene { target, .. } => target
                .scene()
                .sun
                .and_then(|sun| Illumination::new(sun.zenith, sun.azimuth, sun.stokes).ok()),
        }
    }

    /// The target and background observers of a scene contrast.
    pub fn observers(&self) -> Option<(&Observer, &Observer)> {
        match &self.source {
            Source::Scene {
                target, background, ..
            } => Some((target, background)),
            Source::Collimated { .. } => None,
        }
    }

    /// The spectral nodes `(weight, target, background)` of a collimated contrast (empty in a
    /// scene).
    pub fn nodes(&self) -> &[(f64, Material, Material)] {
        match &self.source {
            Source::Collimated { nodes, .. } => nodes,
            Source::Scene { .. } => &[],
        }
    }

    /// Both materials seen from `(theta_r, phi_r)` (rad; θr clamped into `[0, π/2]`), by the
    /// engine's single-element path.
    pub fn at(&self, theta_r: f64, phi_r: f64) -> ContrastSample {
        let Source::Collimated { nodes, light } = &self.source else {
            return self.at_all(&[(theta_r, phi_r)])[0];
        };
        let g = light.geometry(theta_r, phi_r);
        let s = light.stokes();
        let (mut t, mut b) = (Stokes([0.0; 4]), Stokes([0.0; 4]));
        for (w, target, background) in nodes {
            t = t.combine(1.0, &Kernel::new(target).pbrdf(&g).apply(&s), *w);
            b = b.combine(1.0, &Kernel::new(background).pbrdf(&g).apply(&s), *w);
        }
        ContrastSample {
            theta_r: g.theta_r(),
            phi_r,
            target: t,
            background: b,
        }
    }

    /// Both materials seen from each direction `(θr, φr)` (rad; θr clamped into `[0, π/2]`),
    /// through the engine.
    pub fn at_all(&self, dirs: &[(f64, f64)]) -> Vec<ContrastSample> {
        self.at_all_with(dirs, Quality::Full)
    }

    /// As [`Contrast::at_all`], a scene's azimuth-dependent sky integrated at `quality`.
    pub fn at_all_with(&self, dirs: &[(f64, f64)], quality: Quality) -> Vec<ContrastSample> {
        let (nodes, light) = match &self.source {
            Source::Collimated { nodes, light } => (nodes, light),
            Source::Scene { target, background } => {
                let (t, b) = rayon::join(
                    || target.observe_with(dirs, quality),
                    || background.observe_with(dirs, quality),
                );
                return t
                    .iter()
                    .zip(&b)
                    .map(|(t, b)| ContrastSample {
                        theta_r: t.theta_r,
                        phi_r: t.phi_r,
                        target: t.stokes,
                        background: b.stokes,
                    })
                    .collect();
            }
        };
        let geoms: Vec<Geometry> = dirs.iter().map(|&(t, p)| light.geometry(t, p)).collect();
        let s = light.stokes();
        let zero = Stokes([0.0; 4]);
        let (mut t, mut b) = (vec![zero; dirs.len()], vec![zero; dirs.len()]);
        for (w, target, background) in nodes {
            let ft = Engine::new(target).pbrdf_of(&geoms).expect("no index");
            let fb = Engine::new(background).pbrdf_of(&geoms).expect("no index");
            for k in 0..dirs.len() {
                t[k] = t[k].combine(1.0, &ft[k].apply(&s), *w);
                b[k] = b[k].combine(1.0, &fb[k].apply(&s), *w);
            }
        }
        (0..dirs.len())
            .map(|k| ContrastSample {
                theta_r: geoms[k].theta_r(),
                phi_r: dirs[k].1,
                target: t[k],
                background: b[k],
            })
            .collect()
    }

    /// Whether every result is the same at all view azimuths: a scene contrast without a sun
    /// and with an azimuth-independent sky (the model is isotropic). The best directions are
    /// then rings about the normal, and [`Contrast::rank`] ranks view zeniths (at the grid's
    /// first azimuth) instead of listing one ring's azimuths.
    pub fn is_azimuth_independent(&self) -> bool {
        match &self.source {
            Source::Scene { target, background } => {
                target.is_azimuth_independent() && background.is_azimuth_independent()
            }
            Source::Collimated { .. } => false,
        }
    }

    /// Both materials over the whole grid, through the engine (a scene's azimuth-dependent sky
    /// on the map rule, [`Quality::Map`]; the ranked directions are evaluated again on the
    /// full one).
    pub fn map(&self, grid: &ViewGrid) -> ContrastMap {
        let dirs: Vec<(f64, f64)> = (0..grid.len()).map(|i| grid.direction(i)).collect();
        ContrastMap {
            grid: grid.clone(),
            samples: self.at_all_with(&dirs, Quality::Map),
        }
    }
}
