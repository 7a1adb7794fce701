//! The refinement of a ranked direction around its grid node: brute force under a collimated
//! source, golden-section search in zenith for azimuth-independent results, compass search in a
//! scene whose results depend on azimuth.

use super::{Contrast, ContrastSample, RankOptions, Source, ViewGrid};
use crate::analysis::sky::Quality;
use std::f64::consts::PI;

impl Contrast {
    /// Brute-force search of the cell of ±1 grid step around `s` (clamped to the grid's zenith
    /// range and `opts.max_zenith`), on a grid 8 times finer, twice. For azimuth-independent
    /// results ([`Contrast::is_azimuth_independent`]) the search is over the zenith only: a
    /// golden-section search of the same interval down to 1/64 of the grid step, every
    /// evaluated zenith a candidate (about 12 evaluations instead of 34).
    pub(super) fn refine(
        &self,
        s: &ContrastSample,
        grid: &ViewGrid,
        opts: &RankOptions,
    ) -> ContrastSample {
        const SUB: i32 = 8;
        let by = opts.by;
        let t_max = grid.theta_max().min(opts.max_zenith * (1.0 + 1e-12));
        let mut best = *s;
        if self.is_azimuth_independent() {
            let dt = grid.theta_step();
            let (mut a, mut b) = ((s.theta_r - dt).max(0.0), (s.theta_r + dt).min(t_max));
            let g = 0.5 * (5f64.sqrt() - 1.0);
            let at = |t: f64| self.at_all(&[(t, s.phi_r)])[0];
            let consider = |c: ContrastSample, best: &mut ContrastSample| {
                if c.score(by) > best.score(by) {
                    *best = c;
                }
            };
            let (mut x1, mut x2) = (b - g * (b - a), a + g * (b - a));
            let (mut f1, mut f2) = (at(x1), at(x2));
            consider(f1, &mut best);
            consider(f2, &mut best);
            while b - a > dt / 64.0 {
                // Keep the better half; NaN scores count as worst.
                if f1.score(by) >= f2.score(by) || f2.score(by).is_nan() {
                    b = x2;
                    (x2, f2) = (x1, f1);
                    x1 = b - g * (b - a);
                    f1 = at(x1);
                    consider(f1, &mut best);
                } else {
                    a = x1;
                    (x1, f1) = (x2, f2);
                    x2 = a + g * (b - a);
                    f2 = at(x2);
                    consider(f2, &mut best);
                }
            }
            return best;
        }
        if matches!(self.source, Source::Scene { .. }) {
            return self.pattern_search(s, grid, opts, t_max);
        }
        let (mut dt, mut dp) = (grid.theta_step(), grid.phi_step());
        for _ in 0..2 {
            let (t0, p0) = (best.theta_r, best.phi_r);
            let mut cells = Vec::new();
            for a in -SUB..=SUB {
                let t = t0 + dt * f64::from(a) / f64::from(SUB);
                if t < 0.0 || t > t_max {
                    continue;
                }
                for b in -SUB..=SUB {
                    cells.push((t, p0 + dp * f64::from(b) / f64::from(SUB)));
                }
            }
            // The first strictly better candidate in scan order wins, as a serial search would.
            for c in self.at_all(&cells) {
                if c.score(by) > best.score(by) {
                    best = c;
                }
            }
            dt /= f64::from(SUB);
            dp /= f64::from(SUB);
        }
        best.phi_r = best.phi_r.rem_euclid(2.0 * PI);
        best
    }

    /// The refinement of a scene whose results depend on azimuth (a sun, a cie-clear or table
    /// sky), where every evaluation is a sky integral: a compass search on the map rule
    /// ([`Quality::Map`]) instead of the brute-force grid — the 8 neighbours at ±h in θ and
    /// φ (h = one grid step at first), moving to the best, halving h when the centre is best,
    /// until h is 1/64 of the step (about 60 evaluations instead of 578) — confined to the
    /// ±1-step cell; the result evaluated again on the full rule.
    fn pattern_search(
        &self,
        s: &ContrastSample,
        grid: &ViewGrid,
        opts: &RankOptions,
        t_max: f64,
    ) -> ContrastSample {
        let by = opts.by;
        let (t0, p0) = (s.theta_r, s.phi_r);
        let (dt0, dp0) = (grid.theta_step(), grid.phi_step());
        let inside = |t: f64, p: f64| {
            (0.0..=t_max).contains(&t)
                && (t - t0).abs() <= dt0 * (1.0 + 1e-12)
                && (p - p0).abs() <= dp0 * (1.0 + 1e-12)
        };
        let mut best = self.at_all_with(&[(t0, p0)], Quality::Map)[0];
        let mut h = 1.0;
        while h >= 1.0 / 64.0 {
            let (bt, bp) = (best.theta_r, best.phi_r);
            let cells: Vec<(f64, f64)> = [-1.0, 0.0, 1.0]
                .iter()
                .flat_map(|a| [-1.0, 0.0, 1.0].iter().map(move |b| (*a, *b)))
                .filter(|&(a, b)| a != 0.0 || b != 0.0)
                .map(|(a, b)| (bt + a * h * dt0, bp + b * h * dp0))
                .filter(|&(t, p)| inside(t, p))
                .collect();
            let mut moved = false;
            for c in self.at_all_with(&cells, Quality::Map) {
                if c.score(by) > best.score(by) {
                    best = c;
                    moved = true;
                }
            }
            if !moved {
                h /= 2.0;
            }
        }
        let mut out = self.at_all(&[(best.theta_r, best.phi_r)])[0];
        if out.score(by) < s.score(by) {
            out = *s;
        }
        out.phi_r = out.phi_r.rem_euclid(2.0 * PI);
        out
    }
}
