//! The minimizer's view of a fit: the free parameters in internal coordinates (`ln x`, `k²`, or
//! `x` bounded below), some held fixed, with the exact Jacobian columns of ρ_D and ρ_V
//! (docs/model.md §7a, "Coordinates and domains" and "Minimizer").

use super::problem::{Problem, Values};
use crate::lm::{self, LmOptions};
use crate::params::Param;
use std::cell::RefCell;

impl Problem<'_> {
    /// Minimizes χ² over the free parameters from natural values `x0`, with those of `hold`
    /// fixed at their values in `x0`.
    pub(super) fn minimize(
        &self,
        x0: &[f64],
        hold: &[usize],
        opts: &LmOptions,
    ) -> (Vec<f64>, lm::LmReport) {
        let moving = (0..self.free.len()).filter(|j| !hold.contains(j)).collect();
        let objective = FitObjective::new(self, x0, moving);
        let u0: Vec<f64> = objective
            .moving
            .iter()
            .map(|&j| self.free[j].to_internal(x0[j]))
            .collect();
        let lower: Vec<f64> = objective
            .moving
            .iter()
            .map(|&j| self.free[j].lower_bound())
            .collect();
        let report = lm::minimize(&objective, &u0, &lower, self.rows.len(), opts);
        (objective.to_x(&report.u), report)
    }
}

/// The objective of one minimization: the internal coordinates of the moving parameters, the
/// others at their values in `x0`. It keeps the model's values at the point evaluated last, so
/// that the Jacobian columns of ρ_D and ρ_V (which enter linearly) are exact and free.
pub(super) struct FitObjective<'p, 'x> {
    problem: &'p Problem<'p>,
    x0: &'x [f64],
    moving: Vec<usize>,
    last: RefCell<Option<(Vec<f64>, Values)>>,
}

impl<'p, 'x> FitObjective<'p, 'x> {
    /// The objective over the parameters `moving` (indices into the free parameters), the
    /// others at their values in `x0`.
    pub(super) fn new(problem: &'p Problem<'p>, x0: &'x [f64], moving: Vec<usize>) -> Self {
        FitObjective {
            problem,
            x0,
            moving,
            last: RefCell::new(None),
        }
    }

    /// The natural parameter values at internal coordinates `u` of the moving parameters.
    fn to_x(&self, u: &[f64]) -> Vec<f64> {
        let mut x = self.x0.to_vec();
        for (&j, u) in self.moving.iter().zip(u) {
            x[j] = self.problem.free[j].from_internal(*u);
        }
        x
    }
}

impl lm::Objective for FitObjective<'_, '_> {
    fn residuals(&self, u: &[f64], r: &mut [f64]) -> bool {
        let Ok(material) = self.problem.material_at(&self.to_x(u)) else {
            return false;
        };
        let v = self.problem.values(&material);
        self.problem.residuals_from(&v, r);
        *self.last.borrow_mut() = Some((u.to_vec(), v));
        r.iter().all(|x| x.is_finite())
    }

    fn jacobian(&self, u: &[f64], r: &[f64]) -> Option<Vec<Vec<f64>>> {
        let base = self
            .last
            .borrow_mut()
            .take()
            .filter(|(at, _)| at == u)
            .map(|x| x.1);
        let mut plus = vec![0.0; r.len()];
        let mut up = u.to_vec();
        let mut cols = Vec::with_capacity(u.len());
        for (k, &j) in self.moving.iter().enumerate() {
            let param = self.problem.free[j];
            if let (Some(v), Param::RhoD | Param::RhoV) = (&base, param) {
                cols.push(self.problem.volume_column(v, param));
                continue;
            }
            // Forward difference (as `lm::jacobian`).
            let h = f64::EPSILON.sqrt() * u[k].abs().max(1.0);
            up[k] = u[k] + h;
            let ok = self.residuals(&up, &mut plus);
            let step = up[k] - u[k];
            up[k] = u[k];
            if !ok {
                return None;
            }
            cols.push(plus.iter().zip(r).map(|(p, q)| (p - q) / step).collect());
        }
        Some(cols)
    }
}
