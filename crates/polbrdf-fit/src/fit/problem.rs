//! The problem of one fit: the measurements grouped by geometry, the geometry stages prepared
//! once, and the weighted residuals `(model − data)/σ` at any parameter values — each one call of
//! the batch engine over the measured geometries (docs/model.md §7a, "Residuals").

use super::{Evaluator, Measurement, Observable};
use crate::error::FitError;
use crate::params::Param;
use polbrdf::engine::Prepared;
use polbrdf::{
    AngleVariables, Engine, Geometry, GeometryBatch, IndexColumns, Material, MaterialSpec, Mueller,
};
use rayon::prelude::*;

/// One measurement's row: (geometry index, observable, value, weight 1/σ).
pub(super) type Row = (usize, Observable, f64, f64);

/// A spectral index fixed per element: `n` and `k` of every element at its wavelength, and the
/// wavelength the material is built at.
type ElementIndex = (Vec<f64>, Vec<f64>, f64);

/// The prepared problem: the unique geometries (consecutive measurements at the same geometry
/// share one), and per measurement its geometry, observable, value and weight.
pub(super) struct Problem<'a> {
    base: MaterialSpec,
    /// The free parameters, in the order of the parameter vectors.
    pub(super) free: &'a [Param],
    /// The number of unique geometries (elements of the batch).
    elements: usize,
    /// The geometry stages of the batch, computed once for every evaluation.
    prepared: Prepared,
    /// Angle variables of each geometry (the one-geometry evaluator).
    angles: Vec<Option<AngleVariables>>,
    /// Per measurement: (geometry index, observable, value, weight 1/σ).
    pub(super) rows: Vec<Row>,
    /// Some measurement is a Mueller entry (the full matrix is needed, not BRDF and DoLP only).
    full: bool,
    evaluator: Evaluator,
    /// Per geometry: `∂f_v/∂ρ_V = 2/(cosθi + cosθr)`, and 0 at or below the horizon (where the
    /// model is 0 whatever ρ is) — the volume term's exact derivatives (`∂f_v/∂ρ_D` is 1
    /// above the horizon).
    dfv_drho_v: Vec<f64>,
    /// For a material with a spectral index: `(n, k)` of every element at its wavelength, fixed
    /// during the fit, and the wavelength the material is built at.
    spectral: Option<ElementIndex>,
}

impl<'a> Problem<'a> {
    /// The problem of fitting the `free` parameters of `base` to `data`: the measurements
    /// grouped by geometry, the spectral index fixed per element, the geometry stages prepared
    /// for `evaluator`, and the volume term's derivatives.
    ///
    /// # Errors
    /// [`FitError::BadParameterList`] for n or k free with a spectral index, or a spectral
    /// index without wavelengths; [`FitError::Model`] if the index or the material cannot be
    /// evaluated.
    pub(super) fn new(
        base: &MaterialSpec,
        free: &'a [Param],
        data: &[Measurement],
        evaluator: Evaluator,
    ) -> Result<Self, FitError> {
        let (geoms, element_wl, rows) = group_by_geometry(data);
        let spectral = spectral_index(base, free, &element_wl)?;
        let cols: [Vec<f64>; 4] = [
            geoms.iter().map(Geometry::theta_i).collect(),
            geoms.iter().map(Geometry::phi_i).collect(),
            geoms.iter().map(Geometry::theta_r).collect(),
            geoms.iter().map(Geometry::phi_r).collect(),
        ];
        let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3])?;
        let base_material = match &spectral {
            Some((_, _, l)) => base.build_at(*l)?,
            None => base.build()?,
        };
        Ok(Problem {
            base: base.clone(),
            free,
            elements: batch.len(),
            prepared: Engine::new(&base_material).prepare(&batch),
            spectral,
            angles: match evaluator {
                Evaluator::OneGeometry => geoms.iter().map(Geometry::angle_variables).collect(),
                Evaluator::Engine => Vec::new(),
            },
            full: rows.iter().any(|r| r.1.needs_matrix()),
            dfv_drho_v: volume_derivatives(&geoms),
            rows,
            evaluator,
        })
    }
}

/// Consecutive measurements at the same geometry (and wavelength) grouped into one element:
/// the elements' geometries and wavelengths, and every measurement's row.
fn group_by_geometry(data: &[Measurement]) -> (Vec<Geometry>, Vec<Option<f64>>, Vec<Row>) {
    let mut geoms: Vec<Geometry> = Vec::new();
    let mut element_wl: Vec<Option<f64>> = Vec::new();
    let mut rows = Vec::with_capacity(data.len());
    for d in data {
        if geoms.last() != Some(&d.geometry) || element_wl.last() != Some(&d.wavelength_um) {
            geoms.push(d.geometry);
            element_wl.push(d.wavelength_um);
        }
        rows.push((
            geoms.len() - 1,
            d.observable,
            d.value,
            d.sigma.map_or(1.0, |s| 1.0 / s),
        ));
    }
    (geoms, element_wl, rows)
}

/// For a material with a spectral index: `(n, k)` of every element at its wavelength (fixed
/// during the fit) and the first element's wavelength, at which the material is built; `None`
/// for a constant index.
///
/// # Errors
/// [`FitError::BadParameterList`] when n or k is free (they come from the index) or an element
/// has no wavelength; [`FitError::Model`] outside the index's range.
fn spectral_index(
    base: &MaterialSpec,
    free: &[Param],
    element_wl: &[Option<f64>],
) -> Result<Option<ElementIndex>, FitError> {
    let Some(src) = &base.spectral else {
        return Ok(None);
    };
    if let Some(p) = free.iter().find(|p| matches!(p, Param::N | Param::K)) {
        return Err(FitError::BadParameterList(format!(
            "`{}` comes from the spectral index `{}`: fit n and k per wavelength \
             (--per-wavelength), or use a constant-index material",
            p.name(),
            src.source
        )));
    }
    let (mut nn, mut kk) = (Vec::new(), Vec::new());
    for l in element_wl {
        let Some(l) = l else {
            return Err(FitError::BadParameterList(format!(
                "the material has a spectral index (`{}`): every measurement needs a \
                 wavelength (a `wavelength_um` column)",
                src.source
            )));
        };
        let index = base.index_at(*l)?;
        nn.push(index.n());
        kk.push(index.k());
    }
    let first = element_wl[0].expect("checked above");
    Ok(Some((nn, kk, first)))
}

/// Per geometry: `∂f_v/∂ρ_V = 2/(cosθi + cosθr)` above the horizon, 0 at or below it.
fn volume_derivatives(geoms: &[Geometry]) -> Vec<f64> {
    geoms
        .iter()
        .map(|g| {
            if g.is_above_horizon() {
                2.0 / (g.theta_i().cos() + g.theta_r().cos())
            } else {
                0.0
            }
        })
        .collect()
}

/// The model at every measured geometry: `F00` and the DoLP, or the whole matrix.
#[derive(Debug, Clone)]
pub(super) enum Values {
    BrdfDolp(Vec<f64>, Vec<f64>),
    Full(Vec<[f64; 16]>),
}

impl Values {
    /// `F00` and the DoLP of geometry `g`.
    fn f00_dolp(&self, g: usize) -> (f64, f64) {
        match self {
            Values::BrdfDolp(b, d) => (b[g], d[g]),
            Values::Full(f) => {
                let m = Mueller::from_row_major(&f[g]);
                (m.m00(), m.dolp_unpolarized())
            }
        }
    }

    fn of(&self, g: usize, obs: Observable) -> f64 {
        match (self, obs) {
            (Values::BrdfDolp(b, _), Observable::Brdf) => b[g],
            (Values::BrdfDolp(_, d), Observable::Dolp) => d[g],
            (Values::Full(f), obs) => obs.of_pbrdf(&Mueller::from_row_major(&f[g])),
            (Values::BrdfDolp(..), _) => {
                unreachable!("the full path for quantities that need the matrix")
            }
        }
    }
}

impl Problem<'_> {
    /// The material spec at natural parameter values `x`.
    pub(super) fn spec_at(&self, x: &[f64]) -> MaterialSpec {
        let mut spec = self.base.clone();
        for (p, v) in self.free.iter().zip(x) {
            p.set(&mut spec, *v);
        }
        spec
    }

    /// The material at natural parameter values `x` (built at the first element's wavelength
    /// for a spectral index, whose value per element [`Problem::values`] supplies).
    pub(super) fn material_at(&self, x: &[f64]) -> polbrdf::Result<Material> {
        let spec = self.spec_at(x);
        match &self.spectral {
            Some((_, _, l)) => spec.build_at(*l),
            None => spec.build(),
        }
    }

    /// Weighted residuals `(model − data)/σ` at natural parameter values `x`.
    pub(super) fn residuals(&self, x: &[f64], out: &mut [f64]) -> bool {
        let Ok(material) = self.material_at(x) else {
            return false;
        };
        self.residuals_of(&material, out);
        out.iter().all(|v| v.is_finite())
    }

    /// The model at every measured element (geometry, and wavelength for spectral data).
    pub(super) fn values(&self, material: &Material) -> Values {
        let n = self.elements;
        let engine = match &self.spectral {
            Some((nn, kk, _)) => Engine::new(material)
                .with_index(IndexColumns::new(nn, kk).expect("validated when prepared")),
            None => Engine::new(material),
        };
        match self.evaluator {
            Evaluator::Engine if self.full => {
                let mut f = vec![[0.0; 16]; n];
                engine
                    .mueller_prepared_into(&self.prepared, &mut f)
                    .expect("lengths match");
                Values::Full(f)
            }
            Evaluator::Engine => {
                let (mut brdf, mut dolp) = (vec![0.0; n], vec![0.0; n]);
                engine
                    .brdf_dolp_prepared_into(&self.prepared, &mut brdf, &mut dolp)
                    .expect("lengths match");
                Values::BrdfDolp(brdf, dolp)
            }
            Evaluator::OneGeometry => {
                let f: Vec<[f64; 16]> = self
                    .angles
                    .par_iter()
                    .enumerate()
                    .with_min_len(256)
                    .map(|(e, a)| match a {
                        Some(v) => {
                            let index = match &self.spectral {
                                Some((nn, kk, _)) => polbrdf::RefractiveIndex::new(nn[e], kk[e])
                                    .expect("validated when prepared"),
                                None => material.index(),
                            };
                            material
                                .evaluate_angles_with_index(v, index)
                                .pbrdf
                                .to_row_major()
                        }
                        None => [0.0; 16],
                    })
                    .collect();
                Values::Full(f)
            }
        }
    }

    /// The model's value of every measurement.
    pub(super) fn model_values(&self, material: &Material, out: &mut [f64]) {
        let v = self.values(material);
        for (o, &(g, obs, _, _)) in out.iter_mut().zip(&self.rows) {
            *o = v.of(g, obs);
        }
    }

    /// The weighted residuals from the model's values.
    pub(super) fn residuals_from(&self, v: &Values, out: &mut [f64]) {
        for (o, &(g, obs, value, w)) in out.iter_mut().zip(&self.rows) {
            *o = (v.of(g, obs) - value) * w;
        }
    }

    /// The exact column `∂r/∂ρ` of the volume constant `param` (ρ_D or ρ_V), from the model's
    /// values: `f_v = ρ_D + 2ρ_V/(cosθi + cosθr)` adds to F00 only, so
    /// `∂F00/∂ρ = ∂f_v/∂ρ`, `∂DoLP/∂ρ = −DoLP·(∂f_v/∂ρ)/F00`, and no other entry changes.
    pub(super) fn volume_column(&self, v: &Values, param: Param) -> Vec<f64> {
        self.rows
            .iter()
            .map(|&(g, obs, _, w)| {
                let dfv = match param {
                    Param::RhoD => f64::from(u8::from(self.dfv_drho_v[g] > 0.0)),
                    _ => self.dfv_drho_v[g],
                };
                let (f00, dolp) = v.f00_dolp(g);
                w * match obs {
                    // f_v adds to F00 only: F00 ± F01 moves with it, F01 does not.
                    Observable::Brdf
                    | Observable::BrdfS
                    | Observable::BrdfP
                    | Observable::Mueller(0, 0) => dfv,
                    Observable::Dolp if f00 > 0.0 => -dolp * dfv / f00,
                    _ => 0.0,
                }
            })
            .collect()
    }

    fn residuals_of(&self, material: &Material, out: &mut [f64]) {
        self.residuals_from(&self.values(material), out);
    }

    /// χ² at natural parameter values (∞ where the model cannot be evaluated).
    pub(super) fn chi2(&self, x: &[f64]) -> f64 {
        let mut r = vec![0.0; self.rows.len()];
        if self.residuals(x, &mut r) {
            r.iter().map(|v| v * v).sum()
        } else {
            f64::INFINITY
        }
    }
}
