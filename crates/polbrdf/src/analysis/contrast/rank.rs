//! The ranking of a contrast map's best directions: the score, the options, greedy
//! non-maximum suppression by great-circle separation.

use super::{Contrast, ContrastMap, ContrastSample};
use rayon::prelude::*;

/// What the best directions are ranked by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Ranking {
    /// `|ΔDoLP|` (default).
    #[default]
    DeltaDolp,
    /// The polarization contrast `|ΔS_lin|/S̄0`, which also weighs intensity.
    PolarizationContrast,
}

impl Ranking {
    /// Every score, in the order the command line lists them.
    pub const ALL: [Ranking; 2] = [Ranking::DeltaDolp, Ranking::PolarizationContrast];

    /// The name used on the command line and in files.
    pub fn as_str(&self) -> &'static str {
        match self {
            Ranking::DeltaDolp => "delta-dolp",
            Ranking::PolarizationContrast => "polarization-contrast",
        }
    }
}

impl ContrastSample {
    /// The ranking score: `|ΔDoLP|` or the polarization contrast.
    pub fn score(&self, by: Ranking) -> f64 {
        match by {
            Ranking::DeltaDolp => self.delta_dolp().abs(),
            Ranking::PolarizationContrast => self.polarization_contrast(),
        }
    }
}

impl std::str::FromStr for Ranking {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        crate::names::parse(&Self::ALL, |r| r.as_str(), s)
    }
}

/// How [`Contrast::rank`] lists the best directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RankOptions {
    /// The score (default `|ΔDoLP|`).
    pub by: Ranking,
    /// How many directions to list (default 10).
    pub count: usize,
    /// Minimum great-circle angle between two listed directions (rad; default 10°).
    pub min_separation: f64,
    /// Largest viewing zenith angle considered (rad; default 80°). Toward grazing view the
    /// target's projected area vanishes and the facet model (with its `1/cosθr`) is least
    /// reliable, while the contrast often keeps growing up to the horizon: without this limit
    /// the "best" direction would sit at whatever zenith angle the grid happens to reach.
    pub max_zenith: f64,
    /// Refine each listed direction by brute force around its grid node (default true): the
    /// cell of ±1 grid step in θ and φ is searched on a grid 8 times finer, twice (final
    /// resolution 1/64 of the grid step), and the list is sorted again. A refined direction
    /// stays within one grid step of its node, so two listed directions may end up slightly
    /// closer than `min_separation`.
    pub refine: bool,
}

impl Default for RankOptions {
    fn default() -> Self {
        Self {
            by: Ranking::DeltaDolp,
            count: 10,
            min_separation: 10f64.to_radians(),
            max_zenith: 80f64.to_radians(),
            refine: true,
        }
    }
}

impl Contrast {
    /// The best directions of `map`, best first ([`crate::analysis::contrast`]): sorted by
    /// `opts.by` (ties by grid index), each at least `opts.min_separation` from every better one,
    /// at most `opts.count`, refined by brute force when `opts.refine`. Nodes whose score is not
    /// a number are skipped.
    pub fn rank(&self, map: &ContrastMap, opts: &RankOptions) -> Vec<ContrastSample> {
        let ring = self.is_azimuth_independent();
        let first_phi = map.grid.phis().first().copied().unwrap_or(0.0);
        let mut order: Vec<(usize, f64)> = map
            .samples
            .iter()
            .enumerate()
            .filter(|(_, s)| s.theta_r <= opts.max_zenith * (1.0 + 1e-12))
            .filter(|(_, s)| !ring || s.phi_r == first_phi)
            .map(|(i, s)| (i, s.score(opts.by)))
            .filter(|(_, v)| !v.is_nan())
            .collect();
        order.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        let mut picked: Vec<ContrastSample> = Vec::new();
        for (i, _) in order {
            if picked.len() >= opts.count {
                break;
            }
            let s = map.samples[i];
            let w = s.direction();
            let far = picked
                .iter()
                .all(|p| separation(&w, &p.direction()) >= opts.min_separation);
            if far {
                picked.push(s);
            }
        }
        // The picked nodes at full accuracy (the map may have been taken on a coarser rule).
        let dirs: Vec<(f64, f64)> = picked.iter().map(|s| (s.theta_r, s.phi_r)).collect();
        let picked = self.at_all(&dirs);
        if opts.refine {
            let mut refined: Vec<ContrastSample> = picked
                .par_iter()
                .map(|s| self.refine(s, &map.grid, opts))
                .collect();
            // Refinement raises each score by a different amount: sort again (stable).
            refined.sort_by(|a, b| b.score(opts.by).total_cmp(&a.score(opts.by)));
            refined
        } else {
            picked
        }
    }
}

fn w_dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Great-circle angle between two unit vectors, accurate at small angles.
pub fn separation(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let cross = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let c = cross[0].hypot(cross[1]).hypot(cross[2]);
    c.atan2(w_dot(a, b))
}
