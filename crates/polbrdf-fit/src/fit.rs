//! The general fit: any subset of the material parameters against any mix of measured BRDF,
//! DoLP and Mueller entries, by Levenberg–Marquardt, with covariance and χ² (docs/model.md §7a).
//! Every residual vector is one call of the batch engine over the measured geometries.

use crate::error::FitError;
use crate::lm::{self, cholesky_solve, LmOptions};
use crate::params::Param;
use crate::zbs::{self, ZbsFit, ZbsPoint};
use polbrdf::engine::Prepared;
use polbrdf::sample::SplitMix64;
use polbrdf::{
    AngleVariables, Engine, Evaluation, Geometry, GeometryBatch, IndexColumns, Material,
    MaterialSpec, Mueller,
};
use rayon::prelude::*;

/// A measurable quantity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Observable {
    /// Scalar BRDF `f = F00` (sr⁻¹).
    Brdf,
    /// DoLP for unpolarized illumination (eq. 13).
    Dolp,
    /// BRDF for s-polarized incidence, no analyzer: `F·(1, 1, 0, 0)` → `F00 + F01` (sr⁻¹).
    BrdfS,
    /// BRDF for p-polarized incidence, no analyzer: `F·(1, −1, 0, 0)` → `F00 − F01` (sr⁻¹).
    BrdfP,
    /// Mueller-matrix BRDF entry `F_ij` (sr⁻¹, psps basis).
    Mueller(usize, usize),
}

impl Observable {
    /// Every quantity, in the order of [`Observable::parse`]'s list: `brdf`, `dolp`, `brdf_s`,
    /// `brdf_p`, `m00` … `m33` (row-major).
    pub fn all() -> Vec<Observable> {
        let mut all = vec![
            Observable::Brdf,
            Observable::Dolp,
            Observable::BrdfS,
            Observable::BrdfP,
        ];
        all.extend((0..16).map(|k| Observable::Mueller(k / 4, k % 4)));
        all
    }

    /// From a column name: `brdf`, `dolp`, `brdf_s`, `brdf_p`, `m00` … `m33`.
    pub fn parse(name: &str) -> Option<Self> {
        match name {
            "brdf" => Some(Observable::Brdf),
            "dolp" => Some(Observable::Dolp),
            "brdf_s" => Some(Observable::BrdfS),
            "brdf_p" => Some(Observable::BrdfP),
            _ => Mueller::entry_of(name).map(|(i, j)| Observable::Mueller(i, j)),
        }
    }

    /// The column name.
    pub fn name(&self) -> String {
        match self {
            Observable::Brdf => "brdf".into(),
            Observable::Dolp => "dolp".into(),
            Observable::BrdfS => "brdf_s".into(),
            Observable::BrdfP => "brdf_p".into(),
            // An entry outside the matrix (no quantity of a file) is named as it is.
            Observable::Mueller(i, j) if *i < 4 && *j < 4 => Mueller::COLUMNS[4 * i + j].into(),
            Observable::Mueller(i, j) => format!("entry ({i}, {j}) outside the 4×4 matrix"),
        }
    }

    /// Whether the quantity needs more of `F` than `F00` and the DoLP.
    pub fn needs_matrix(&self) -> bool {
        !matches!(self, Observable::Brdf | Observable::Dolp)
    }

    /// The model's value of this quantity.
    pub fn of(&self, e: &Evaluation) -> f64 {
        self.of_pbrdf(&e.pbrdf)
    }

    /// This quantity of a pBRDF `F`: `F00`, the DoLP of `F·(1, 0, 0, 0)`, `F00 ± F01` or `F_ij`
    /// (psps basis: `(1, 1, 0, 0)` is s-polarized, docs/model.md §2).
    pub fn of_pbrdf(&self, f: &Mueller) -> f64 {
        match *self {
            Observable::Brdf => f.m00(),
            Observable::Dolp => f.dolp_unpolarized(),
            Observable::BrdfS => f.m00() + f[(0, 1)],
            Observable::BrdfP => f.m00() - f[(0, 1)],
            Observable::Mueller(i, j) => f[(i, j)],
        }
    }
}

/// One measured value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measurement {
    /// Where it was measured.
    pub geometry: Geometry,
    /// What was measured.
    pub observable: Observable,
    /// The value.
    pub value: f64,
    /// Its 1-σ uncertainty, if known (> 0).
    pub sigma: Option<f64>,
    /// The vacuum wavelength (µm), when the data are spectral: a material with a spectral
    /// index is evaluated with its index there.
    pub wavelength_um: Option<f64>,
}

/// How the model is evaluated at the measured geometries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Evaluator {
    /// The batch engine, over all geometries at once (default).
    #[default]
    Engine,
    /// `Material::evaluate_angles` one geometry at a time, on angle variables computed once —
    /// how fits were evaluated before the engine; kept to verify the engine's results and to
    /// measure the difference side by side (`cargo bench -p polbrdf-fit`).
    OneGeometry,
}

/// Settings of [`fit`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitOptions {
    /// Extra starts, scattered around the initial values (factor up to 2 each way), besides the
    /// initial values and the zero-bistatic start. The best result is kept.
    pub extra_starts: usize,
    /// Seed of the scatter.
    pub seed: u64,
    /// Stopping rules.
    pub lm: LmOptions,
    /// How the model is evaluated.
    pub evaluator: Evaluator,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            extra_starts: 2,
            seed: 1,
            lm: LmOptions::default(),
            evaluator: Evaluator::Engine,
        }
    }
}

/// Where a fitted parameter ended, relative to its domain.
#[derive(Debug, Clone, PartialEq)]
pub enum Bound {
    /// Inside its domain: the value and its standard error describe it.
    Interior,
    /// At the lower bound of its domain (0 for k, a, ρ_D, ρ_V): the data prefer a value at or
    /// below it. A standard error means nothing there (at k = 0 the model is even in k, so the
    /// derivative vanishes): the result is the bound with a one-sided upper limit, and the
    /// parameter's row of the covariance is NaN (the others' covariance is conditional on it).
    AtLowerBound {
        /// The one-sided 95 % upper limit from the profile of χ²: the value at which the best χ²
        /// over the other free parameters has risen by 2.706 (× χ²/dof when the uncertainties
        /// come from the residuals); `None` if χ² never rises that much (the data do not bound
        /// the parameter).
        upper_limit_95: Option<f64>,
        /// The parameter's correlation with every free parameter (in their order), at the
        /// upper limit (the other parameters at their best values there): what the parameter
        /// trades off against, e.g. k against n.
        correlation_at_limit: Option<Vec<f64>>,
    },
}

/// One measurement beside the fitted model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Residual {
    /// Index into the measurements given to [`fit`].
    pub index: usize,
    /// The model's value.
    pub model: f64,
    /// The measured value.
    pub data: f64,
    /// The uncertainty used (given, or estimated from the residuals).
    pub sigma: f64,
}

/// The outcome of a fit.
#[derive(Debug, Clone, PartialEq)]
pub struct FitResult {
    /// Warnings about the data (e.g. degenerate data whose uncertainties are not meaningful);
    /// empty for a well-posed fit.
    pub warnings: Vec<String>,
    /// Free parameters, in the order given.
    pub params: Vec<Param>,
    /// Their fitted values.
    pub values: Vec<f64>,
    /// Their standard errors, `sqrt(diag(covariance))`.
    pub stderr: Vec<f64>,
    /// Whether each parameter ended inside its domain or at its bound (with an upper limit).
    pub bounds: Vec<Bound>,
    /// Covariance matrix (row-major, in the order of `params`).
    pub covariance: Vec<Vec<f64>>,
    /// Correlation matrix.
    pub correlation: Vec<Vec<f64>>,
    /// χ² = Σ ((model − data)/σ)², with σ = 1 where no uncertainty was given.
    pub chi2: f64,
    /// Degrees of freedom: measurements − free parameters.
    pub dof: usize,
    /// χ²/dof.
    pub reduced_chi2: f64,
    /// True when the uncertainties were estimated from the scatter of the residuals (some
    /// measurement had no σ): covariance scaled by χ²/dof.
    pub scaled_by_residuals: bool,
    /// Whether the minimizer met a convergence test.
    pub converged: bool,
    /// Minimizer steps of the best start.
    pub iterations: usize,
    /// How it stopped, in words.
    pub message: String,
    /// Number of starts tried, and how many of them reached the best χ² (to 1e-6): fewer than
    /// all suggests several minima.
    pub starts: (usize, usize),
    /// The zero-bistatic inversion used for a start, when the data allowed one.
    pub zero_bistatic: Option<ZbsFit>,
    /// The fitted material.
    pub spec: MaterialSpec,
    /// Every measurement beside the model.
    pub residuals: Vec<Residual>,
}

/// The prepared problem: the unique geometries (consecutive measurements at the same geometry
/// share one), and per measurement its geometry, observable, value and weight.
struct Problem<'a> {
    base: MaterialSpec,
    free: &'a [Param],
    batch: GeometryBatch<'a>,
    /// The geometry stages of `batch`, computed once for every evaluation.
    prepared: Prepared,
    /// Angle variables of each geometry (the one-geometry evaluator).
    angles: Vec<Option<AngleVariables>>,
    /// Per measurement: (geometry index, observable, value, weight 1/σ).
    rows: Vec<(usize, Observable, f64, f64)>,
    /// Some measurement is a Mueller entry (the full matrix is needed, not BRDF and DoLP only).
    full: bool,
    evaluator: Evaluator,
    /// Per geometry: `∂f_v/∂ρ_V = 2/(cosθi + cosθr)`, and 0 at or below the horizon (where the
    /// model is 0 whatever ρ is) — the volume term's exact derivatives (`∂f_v/∂ρ_D` is 1
    /// above the horizon).
    dfv_drho_v: Vec<f64>,
    /// For a material with a spectral index: `(n, k)` of every element at its wavelength, fixed
    /// during the fit, and the wavelength the material is built at.
    spectral: Option<(Vec<f64>, Vec<f64>, f64)>,
}

/// The model at every measured geometry: `F00` and the DoLP, or the whole matrix.
#[derive(Debug, Clone)]
enum Values {
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
    fn spec_at(&self, x: &[f64]) -> MaterialSpec {
        let mut spec = self.base.clone();
        for (p, v) in self.free.iter().zip(x) {
            p.set(&mut spec, *v);
        }
        spec
    }

    /// The material at natural parameter values `x` (built at the first element's wavelength
    /// for a spectral index, whose value per element [`Problem::values`] supplies).
    fn material_at(&self, x: &[f64]) -> polbrdf::Result<Material> {
        let spec = self.spec_at(x);
        match &self.spectral {
            Some((_, _, l)) => spec.build_at(*l),
            None => spec.build(),
        }
    }

    /// Weighted residuals `(model − data)/σ` at natural parameter values `x`.
    fn residuals(&self, x: &[f64], out: &mut [f64]) -> bool {
        let Ok(material) = self.material_at(x) else {
            return false;
        };
        self.residuals_of(&material, out);
        out.iter().all(|v| v.is_finite())
    }

    /// The model at every measured element (geometry, and wavelength for spectral data).
    fn values(&self, material: &Material) -> Values {
        let n = self.batch.len();
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
    fn model_values(&self, material: &Material, out: &mut [f64]) {
        let v = self.values(material);
        for (o, &(g, obs, _, _)) in out.iter_mut().zip(&self.rows) {
            *o = v.of(g, obs);
        }
    }

    /// The weighted residuals from the model's values.
    fn residuals_from(&self, v: &Values, out: &mut [f64]) {
        for (o, &(g, obs, value, w)) in out.iter_mut().zip(&self.rows) {
            *o = (v.of(g, obs) - value) * w;
        }
    }

    /// The exact column `∂r/∂ρ` of the volume constant `param` (ρ_D or ρ_V), from the model's
    /// values: `f_v = ρ_D + 2ρ_V/(cosθi + cosθr)` adds to F00 only, so
    /// `∂F00/∂ρ = ∂f_v/∂ρ`, `∂DoLP/∂ρ = −DoLP·(∂f_v/∂ρ)/F00`, and no other entry changes.
    fn volume_column(&self, v: &Values, param: Param) -> Vec<f64> {
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
    fn chi2(&self, x: &[f64]) -> f64 {
        let mut r = vec![0.0; self.rows.len()];
        if self.residuals(x, &mut r) {
            r.iter().map(|v| v * v).sum()
        } else {
            f64::INFINITY
        }
    }

    /// Minimizes χ² over the free parameters from natural values `x0`, with those of `hold`
    /// fixed at their values in `x0`.
    fn minimize(&self, x0: &[f64], hold: &[usize], opts: &LmOptions) -> (Vec<f64>, lm::LmReport) {
        let objective = FitObjective {
            problem: self,
            x0,
            moving: (0..self.free.len()).filter(|j| !hold.contains(j)).collect(),
            last: std::cell::RefCell::new(None),
        };
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
struct FitObjective<'p, 'x> {
    problem: &'p Problem<'p>,
    x0: &'x [f64],
    moving: Vec<usize>,
    last: std::cell::RefCell<Option<(Vec<f64>, Values)>>,
}

impl FitObjective<'_, '_> {
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

/// Fits the `free` parameters of `base` to `data`.
///
/// Strictly positive parameters are fitted as `ln x`; non-negative ones (k, a, ρ_D, ρ_V) as `x`
/// with the bound `x ≥ 0`, which the minimizer respects by projected steps — so a parameter
/// the data push to 0 ends there, is reported as [`Bound::AtLowerBound`] with a one-sided upper
/// limit, and does not make the fit fail. The covariance is computed in the natural parameters
/// from a central-difference Jacobian at the solution (forward differences at a bound).
///
/// # Errors
/// [`FitError::TooFewPoints`] unless there are more measurements than free parameters;
/// [`FitError::Unidentifiable`] when the data cannot determine some parameter;
/// [`FitError::Model`] if `base` is invalid.
pub fn fit(
    base: &MaterialSpec,
    free: &[Param],
    data: &[Measurement],
    opts: &FitOptions,
) -> Result<FitResult, FitError> {
    if !base.is_spectral() {
        base.build()?;
    }
    if free.is_empty() {
        return Err(FitError::BadParameterList("no free parameter".into()));
    }
    let p = free.len();
    let m = data.len();
    if m <= p {
        return Err(FitError::TooFewPoints {
            measurements: m,
            parameters: p,
        });
    }
    if opts.extra_starts > crate::MAX_EXTRA_STARTS {
        return Err(FitError::TooManyStarts(opts.extra_starts));
    }
    check_measurements(data)?;
    // Group consecutive measurements at the same geometry (and wavelength).
    let mut geoms: Vec<Geometry> = Vec::new();
    let mut element_wl: Vec<Option<f64>> = Vec::new();
    let mut rows = Vec::with_capacity(m);
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
    // A spectral index: fixed per element at its wavelength.
    let spectral = match &base.spectral {
        None => None,
        Some(src) => {
            if let Some(p) = free.iter().find(|p| matches!(p, Param::N | Param::K)) {
                return Err(FitError::BadParameterList(format!(
                    "`{}` comes from the spectral index `{}`: fit n and k per wavelength \
                     (--per-wavelength), or use a constant-index material",
                    p.name(),
                    src.source
                )));
            }
            let (mut nn, mut kk) = (Vec::new(), Vec::new());
            for l in &element_wl {
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
            Some((nn, kk, first))
        }
    };
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
    let problem = Problem {
        base: base.clone(),
        free,
        prepared: Engine::new(&base_material).prepare(&batch),
        batch,
        spectral,
        angles: match opts.evaluator {
            Evaluator::OneGeometry => geoms.iter().map(Geometry::angle_variables).collect(),
            Evaluator::Engine => Vec::new(),
        },
        full: rows.iter().any(|r| r.1.needs_matrix()),
        dfv_drho_v: geoms
            .iter()
            .map(|g| {
                if g.is_above_horizon() {
                    2.0 / (g.theta_i().cos() + g.theta_r().cos())
                } else {
                    0.0
                }
            })
            .collect(),
        rows,
        evaluator: opts.evaluator,
    };

    // Start values.
    let initial: Vec<f64> = free
        .iter()
        .map(|p| {
            let v = p.value(base)?;
            // At exactly 0 the gradient of a non-negative parameter can vanish (the model is
            // even in k): start at its typical magnitude instead.
            Ok(if !p.strictly_positive() && v == 0.0 {
                p.typical_scale()
            } else {
                v
            })
        })
        .collect::<Result<_, FitError>>()?;
    let mut starts = vec![initial.clone()];
    let zero_bistatic = zero_bistatic_start(base, free, data);
    if let Some(z) = &zero_bistatic {
        let mut s = initial.clone();
        for (k, param) in free.iter().enumerate() {
            match param {
                Param::B => s[k] = z.b,
                Param::SigmaDeg => s[k] = z.b.sqrt().recip().to_degrees(),
                Param::A => s[k] = z.a,
                _ => {}
            }
        }
        if s != initial {
            starts.push(s);
        }
    }
    let mut rng = SplitMix64::new(opts.seed);
    for _ in 0..opts.extra_starts {
        // A factor 2^(±1) on each value.
        starts.push(
            initial
                .iter()
                .map(|v| v * 2f64.powf(2.0 * rng.next_f64() - 1.0))
                .collect(),
        );
    }

    // Minimize from every start (in parallel).
    let reports: Vec<(Vec<f64>, lm::LmReport)> = starts
        .par_iter()
        .map(|s| problem.minimize(s, &[], &opts.lm))
        .collect();
    let (x, best) = reports
        .iter()
        .filter(|r| r.1.chi2.is_finite())
        .min_by(|a, b| a.1.chi2.total_cmp(&b.1.chi2))
        .cloned()
        .ok_or_else(|| {
            FitError::Model(polbrdf::Error::InconsistentParameters(
                "the model could not be evaluated from any start".into(),
            ))
        })?;
    let agreeing = reports
        .iter()
        .filter(|r| r.1.chi2 - best.chi2 <= 1e-6 * best.chi2.max(1.0))
        .count();

    // A parameter left at its bound: its profile χ² gives the upper limit — or a better
    // point inside the domain (the minimizer stopped where the gradient vanishes at the
    // bound), from which the fit is resumed.
    let (mut x, mut best) = (x, best);
    let mut limits: Vec<(usize, UpperLimit)> = Vec::new();
    let mut resumed = 0;
    loop {
        // The last digits: Gauss–Newton steps on the central-difference Jacobian (not needed
        // where the minimizer stopped on a vanishing gradient, within 1e-7 standard errors).
        if !best.message.starts_with("gradient") {
            x = polish(&problem, x, best.chi2);
        }
        best.chi2 = problem.chi2(&x);
        let scaled = data.iter().any(|d| d.sigma.is_none());
        let unit = if scaled {
            best.chi2 / (m - p) as f64
        } else {
            1.0
        };
        // A non-negative parameter the data cannot tell from its bound (χ² with it at the bound
        // within 1e-6·unit — a thousandth of a standard error — of the best, or of χ²'s
        // rounding) is at its bound: it approaches 0 only asymptotically where χ² is flat there
        // (e.g. data the model fits exactly).
        for j in 0..p {
            let bound = free[j].lower_bound();
            if bound.is_finite() && x[j] > bound {
                let mut at = x.clone();
                at[j] = bound;
                let c = problem.chi2(&at);
                if c <= best.chi2 + (1e-6 * unit).max(1e-9 * best.chi2) {
                    x = at;
                    best.chi2 = best.chi2.min(c);
                }
            }
        }
        limits.clear();
        let mut better = None;
        for j in (0..p).filter(|&j| x[j] <= free[j].lower_bound()) {
            match profile_upper_limit(&problem, &x, j, best.chi2, ONE_SIDED_95 * unit, &opts.lm) {
                Profile::Limit(l) => limits.push((j, l)),
                Profile::Better(x2) => {
                    better = Some(x2);
                    break;
                }
            }
        }
        match better {
            Some(x2) if resumed < 3 => {
                resumed += 1;
                let (x3, report) = problem.minimize(&x2, &[], &opts.lm);
                if report.chi2 < best.chi2 {
                    (x, best) = (x3, report);
                }
            }
            _ => break,
        }
    }
    // Covariance in the natural parameters, of those inside their domain.
    let interior: Vec<usize> = (0..p).filter(|&j| x[j] > free[j].lower_bound()).collect();
    let jac = natural_jacobian(&problem, &x, m);
    let scaled_by_residuals = data.iter().any(|d| d.sigma.is_none());
    let dof = m - p;
    let reduced_chi2 = best.chi2 / dof as f64;
    let scale = if scaled_by_residuals {
        reduced_chi2
    } else {
        1.0
    };
    let inner: Vec<Param> = interior.iter().map(|&j| free[j]).collect();
    let inner_x: Vec<f64> = interior.iter().map(|&j| x[j]).collect();
    let inner_cov = covariance_of(&problem, &inner, &inner_x, &interior, &jac, scale)?;
    let mut covariance = vec![vec![f64::NAN; p]; p];
    for (a, &i) in interior.iter().enumerate() {
        for (b, &j) in interior.iter().enumerate() {
            covariance[i][j] = inner_cov[a][b];
        }
    }
    let stderr: Vec<f64> = (0..p).map(|i| covariance[i][i].max(0.0).sqrt()).collect();
    let correlation = correlation_of(&covariance);
    let bounds = (0..p)
        .map(|j| match limits.iter().find(|l| l.0 == j) {
            None => Bound::Interior,
            Some((_, limit)) => Bound::AtLowerBound {
                upper_limit_95: limit.as_ref().map(|l| l.0),
                correlation_at_limit: limit.as_ref().and_then(|(_, xu)| {
                    let jac = natural_jacobian(&problem, xu, m);
                    let all: Vec<usize> = (0..p).collect();
                    let c = covariance_of(&problem, free, xu, &all, &jac, scale).ok()?;
                    Some(correlation_of(&c)[j].clone())
                }),
            },
        })
        .collect();
    let stderr = stderr
        .into_iter()
        .enumerate()
        .map(|(j, s)| if interior.contains(&j) { s } else { f64::NAN })
        .collect();

    let spec = problem.spec_at(&x);
    let material = problem.material_at(&x)?;
    let sigma_scale = scale.sqrt();
    let mut model = vec![0.0; m];
    problem.model_values(&material, &mut model);
    let residuals = data
        .iter()
        .zip(model)
        .enumerate()
        .map(|(index, (d, model))| Residual {
            index,
            model,
            data: d.value,
            sigma: d.sigma.unwrap_or(sigma_scale),
        })
        .collect();
    let warnings = degenerate_data_warnings(data, p);
    Ok(FitResult {
        warnings,
        params: free.to_vec(),
        values: x,
        stderr,
        bounds,
        covariance,
        correlation,
        chi2: best.chi2,
        dof,
        reduced_chi2,
        scaled_by_residuals,
        converged: best.converged,
        iterations: best.iterations,
        message: best.message,
        starts: (starts.len(), agreeing),
        zero_bistatic,
        spec,
        residuals,
    })
}

/// Refuses a measurement whose `|value/σ|` (σ = 1 when none is given) exceeds
/// [`crate::MAX_WEIGHTED_VALUE`], where its squared residual could overflow χ²: such a value
/// is an outlier or a unit error in the data (checked by [`fit`] before anything else).
///
/// # Errors
/// [`FitError::DataOutOfRange`] naming the first such measurement by its index in `data`.
pub fn check_measurements(data: &[Measurement]) -> Result<(), FitError> {
    for (index, d) in data.iter().enumerate() {
        let sigma = d.sigma.unwrap_or(1.0);
        let w = d.value / sigma;
        if !w.is_finite() || w.abs() > crate::MAX_WEIGHTED_VALUE {
            return Err(FitError::DataOutOfRange {
                index,
                observable: d.observable.name(),
                value: d.value,
                sigma,
            });
        }
    }
    Ok(())
}

/// Warnings about data that cannot give meaningful uncertainties: fewer distinct measurements
/// (geometry, wavelength and observable) than free parameters + 1 — e.g. one row repeated — so
/// that the fit is exactly determined and χ², the residual scaling and the covariance say
/// nothing about the parameters' uncertainty.
fn degenerate_data_warnings(data: &[Measurement], free: usize) -> Vec<String> {
    let key = |d: &Measurement| {
        let g = d.geometry;
        (
            [g.theta_i(), g.phi_i(), g.theta_r(), g.phi_r()].map(f64::to_bits),
            d.wavelength_um.map(f64::to_bits),
            d.observable.name(),
        )
    };
    let distinct: std::collections::HashSet<_> = data.iter().map(key).collect();
    let geometries: std::collections::HashSet<_> = data.iter().map(|d| key(d).0).collect();
    let mut w = Vec::new();
    if distinct.len() <= free {
        w.push(format!(
            "the {} measurement(s) hold only {} distinct one(s) (same geometry, wavelength and \
             quantity repeated) for {free} free parameter(s): the fit is exactly determined and \
             the uncertainties are not meaningful",
            data.len(),
            distinct.len()
        ));
    } else if geometries.len() == 1 && data.len() > 1 {
        w.push(
            "every measurement is at the same geometry: the parameters are determined by that \
             one geometry only, and their correlations and uncertainties may not be meaningful"
                .to_string(),
        );
    }
    w
}

/// One wavelength's fit of [`fit_per_wavelength`].
#[derive(Debug, Clone, PartialEq)]
pub struct WavelengthFit {
    /// The wavelength (µm).
    pub wavelength_um: f64,
    /// The measurements at it.
    pub measurements: usize,
    /// The fit there, or why it was refused.
    pub result: Result<FitResult, FitError>,
}

/// Fits the `free` parameters separately at each wavelength of the data (every measurement
/// needs one): e.g. an effective index `n(λ)`, `k(λ)` for a material no database has. With a
/// spectral `base`, its index at each wavelength is the start of n and k there. The wavelengths
/// are fitted in parallel and returned in increasing order; a refusal at one wavelength is
/// reported there and does not stop the others.
///
/// # Errors
/// [`FitError::BadParameterList`] when a measurement has no wavelength.
pub fn fit_per_wavelength(
    base: &MaterialSpec,
    free: &[Param],
    data: &[Measurement],
    opts: &FitOptions,
) -> Result<Vec<WavelengthFit>, FitError> {
    let mut wavelengths: Vec<f64> = Vec::new();
    for d in data {
        let Some(l) = d.wavelength_um else {
            return Err(FitError::BadParameterList(
                "a fit per wavelength needs the wavelength of every measurement (a \
                 `wavelength_um` column)"
                    .into(),
            ));
        };
        if !wavelengths.contains(&l) {
            wavelengths.push(l);
        }
    }
    wavelengths.sort_by(f64::total_cmp);
    Ok(wavelengths
        .par_iter()
        .map(|&l| {
            let subset: Vec<Measurement> = data
                .iter()
                .filter(|d| d.wavelength_um == Some(l))
                .copied()
                .collect();
            let result = (|| {
                let mut at = base.clone();
                if at.spectral.is_some() {
                    let index = at.index_at(l)?;
                    (at.n, at.k) = (index.n(), index.k());
                    at.spectral = None;
                }
                fit(&at, free, &subset, opts)
            })();
            WavelengthFit {
                wavelength_um: l,
                measurements: subset.len(),
                result,
            }
        })
        .collect())
}

/// `Δχ²` of a one-sided 95 % limit: `1.6449²`.
const ONE_SIDED_95: f64 = 2.705_543_454_095_404;

/// The covariance `(JᵀJ)⁻¹·scale` of the parameters `params` (columns `cols` of `jac`),
/// after the identifiability check.
fn covariance_of(
    problem: &Problem<'_>,
    params: &[Param],
    x: &[f64],
    cols: &[usize],
    jac: &[Vec<f64>],
    scale: f64,
) -> Result<Vec<Vec<f64>>, FitError> {
    let q = cols.len();
    let sub: Vec<Vec<f64>> = cols.iter().map(|&j| jac[j].clone()).collect();
    let (a, _) = lm::normal_equations(&sub, &vec![0.0; problem.rows.len()]);
    check_identifiable(params, &a, x, problem)?;
    // Columns of (JᵀJ)⁻¹; the matrix is symmetric, so they are also its rows.
    (0..q)
        .map(|j| {
            let e: Vec<f64> = (0..q).map(|i| f64::from(u8::from(i == j))).collect();
            cholesky_solve(&a, &e)
                .map(|col| col.into_iter().map(|v| v * scale).collect())
                .ok_or_else(|| unidentifiable_all(params))
        })
        .collect()
}

/// `C_ij/sqrt(C_ii C_jj)` (NaN where C is).
fn correlation_of(c: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let d: Vec<f64> = (0..c.len()).map(|i| c[i][i].max(0.0).sqrt()).collect();
    (0..c.len())
        .map(|i| {
            (0..c.len())
                .map(|j| c[i][j] / (d[i] * d[j]).max(f64::MIN_POSITIVE))
                .collect()
        })
        .collect()
}

/// A one-sided upper limit and the best parameters there (`None`: the data do not bound it).
type UpperLimit = Option<(f64, Vec<f64>)>;

/// What the profile of a parameter at its bound found.
enum Profile {
    /// The one-sided upper limit and the best parameters there.
    Limit(UpperLimit),
    /// A point inside the domain with a lower χ² than the fit's.
    Better(Vec<f64>),
}

/// A first guess of where the profile χ² of parameter `j` (at its bound in `x`) rises by
/// `delta`, from the quadratic model of χ² in the internal coordinates at `x`: with the
/// gradient `g` and the Schur complement `S` of `JᵀJ` for coordinate `j` (the others
/// re-optimized), `Δχ²(u) ≈ 2g·u + S·u²` from the bound; `None` where the model says nothing.
fn profile_guess(problem: &Problem<'_>, x: &[f64], j: usize, delta: f64) -> Option<f64> {
    use lm::Objective;
    let p = x.len();
    let objective = FitObjective {
        problem,
        x0: x,
        moving: (0..p).collect(),
        last: std::cell::RefCell::new(None),
    };
    let u: Vec<f64> = (0..p).map(|i| problem.free[i].to_internal(x[i])).collect();
    let mut r = vec![0.0; problem.rows.len()];
    if !objective.residuals(&u, &mut r) {
        return None;
    }
    let jac = objective.jacobian(&u, &r)?;
    let (a, g) = lm::normal_equations(&jac, &r);
    // S = A_jj − A_jo·A_oo⁻¹·A_oj.
    let others: Vec<usize> = (0..p).filter(|&i| i != j).collect();
    let q = others.len();
    let mut s = a[j * p + j];
    if q > 0 {
        let a_oo: Vec<f64> = others
            .iter()
            .flat_map(|&i| others.iter().map(move |&k| (i, k)))
            .map(|(i, k)| a[i * p + k])
            .collect();
        let a_oj: Vec<f64> = others.iter().map(|&i| a[i * p + j]).collect();
        let y = cholesky_solve(&a_oo, &a_oj)?;
        s -= a_oj.iter().zip(&y).map(|(a, b)| a * b).sum::<f64>();
    }
    let gj = g[j].max(0.0);
    if s.is_nan() || s <= 0.0 {
        return None;
    }
    let du = (-gj + (gj * gj + s * delta).sqrt()) / s;
    Some(problem.free[j].from_internal(u[j] + du))
}

/// The profile χ² of parameter `j` at value `t` — the best χ² over the other free parameters
/// with parameter `j` held at `t`, started from `x` — and the parameters there.
fn profile_at(
    problem: &Problem<'_>,
    x: &[f64],
    j: usize,
    t: f64,
    lm: &LmOptions,
) -> (f64, Vec<f64>) {
    let mut x0 = x.to_vec();
    x0[j] = t;
    if problem.free.len() == 1 {
        return (problem.chi2(&x0), x0);
    }
    let (xt, report) = problem.minimize(&x0, &[j], lm);
    (report.chi2, xt)
}

/// The value of parameter `j` (at its lower bound in `x`, with χ² `chi2`) where its profile χ²
/// has risen by `delta` — the one-sided 95 % upper limit — to 0.5 % of `delta`: a secant search
/// in `(ln t, ln Δχ²)` (exact for `Δχ² ∝ tᵖ`), bracketed, each profile fit started from the
/// previous one's parameters. Unbounded when χ² has not risen that much by 10⁶ times the
/// parameter's typical scale; [`Profile::Better`] if some point of the profile lies below `chi2`
/// (by more than its rounding).
fn profile_upper_limit(
    problem: &Problem<'_>,
    x: &[f64],
    j: usize,
    chi2: f64,
    delta: f64,
    lm: &LmOptions,
) -> Profile {
    let lm = LmOptions {
        ftol: 1e-10,
        xtol: 1e-7,
        ..*lm
    };
    let bound = x[j];
    let scale = problem.free[j].typical_scale();
    let rounding = 1e-9 * chi2.abs().max(1.0);
    let mut t = profile_guess(problem, x, j, delta)
        .filter(|t| *t > bound && t.is_finite())
        .unwrap_or(bound + scale);
    let mut warm = x.to_vec();
    // (distance from the bound, Δχ², parameters) on either side of the target.
    let mut below: Option<(f64, f64)> = None;
    let mut above: Option<(f64, f64, Vec<f64>)> = None;
    for _ in 0..40 {
        let (c, xt) = profile_at(problem, &warm, j, t, &lm);
        let d = c - chi2;
        if d < -rounding {
            return Profile::Better(xt);
        }
        let dist = t - bound;
        if (d - delta).abs() <= 5e-3 * delta {
            return Profile::Limit(Some((t, xt)));
        }
        if d < delta {
            below = Some((dist, d.max(rounding)));
        } else {
            above = Some((dist, d, xt.clone()));
        }
        warm = xt;
        let next = match (&below, &above) {
            (Some((t0, d0)), Some((t1, d1, _))) => {
                // Secant in (ln t, ln Δ), kept inside the bracket.
                let p = (d1 / d0).ln() / (t1 / t0).ln();
                let guess = t0 * (delta / d0).powf(1.0 / p.max(0.5));
                guess.clamp(t0 + 0.05 * (t1 - t0), t1 - 0.05 * (t1 - t0))
            }
            // One side only: as if Δ ∝ t³ (between the t² of a linear rise in k² and the t⁴
            // of a quadratic one), by at most ×10.
            (Some((t0, d0)), None) => t0 * (delta / d0).cbrt().clamp(1.0, 10.0),
            (None, Some((t1, d1, _))) => t1 * (delta / d1).cbrt().clamp(0.1, 1.0),
            (None, None) => unreachable!("one side is set"),
        };
        if next > 1e6 * scale {
            return Profile::Limit(None);
        }
        t = bound + next;
    }
    Profile::Limit(above.map(|(d, _, xt)| (bound + d, xt)))
}

/// Gauss–Newton steps from the minimizer's result `x` on the central-difference Jacobian in the
/// natural parameters, until the step is below 1e-8 standard errors (at most 8 steps), for the
/// parameters inside their domain.
///
/// Levenberg–Marquardt judges a step by the decrease of χ², which near the minimum is below
/// χ²'s own rounding (~1e-11 for 10⁴ values, a step of ~3e-6 standard errors), and its
/// forward-difference Jacobian is accurate to ~1e-8; so its result can sit 1e-5 standard
/// errors from the minimum. There the quadratic model is exact to second order, and the
/// central-difference gradient (accurate to ~1e-10) locates the minimum itself. Only a point
/// already within 1e-2 standard errors is polished; a step that fails to evaluate or leaves the
/// domain ends it.
fn polish(problem: &Problem<'_>, mut x: Vec<f64>, chi2: f64) -> Vec<f64> {
    let m = problem.rows.len();
    let p = x.len();
    let unit = (chi2 / m.saturating_sub(p).max(1) as f64).max(1.0);
    let mut r = vec![0.0; m];
    let mut last = f64::INFINITY;
    for _ in 0..8 {
        if !problem.residuals(&x, &mut r) {
            break;
        }
        let free: Vec<usize> = (0..p)
            .filter(|&j| x[j] > problem.free[j].lower_bound())
            .collect();
        if free.is_empty() {
            break;
        }
        let jac = natural_jacobian(problem, &x, m);
        let cols: Vec<Vec<f64>> = free.iter().map(|&j| jac[j].clone()).collect();
        let (a, g) = lm::normal_equations(&cols, &r);
        let Some(step) = cholesky_solve(&a, &g) else {
            break;
        };
        let decrement: f64 = step.iter().zip(&g).map(|(s, g)| s * g).sum();
        let near = decrement <= 1e-4 * unit; // false for NaN
                                             // Done at 1e-8 standard errors, or when a step no longer shortens the next (the noise
                                             // floor of the derivatives).
        if !near || decrement <= 1e-16 * unit || decrement > 0.25 * last {
            break;
        }
        last = decrement;
        let mut next = x.clone();
        for (k, &j) in free.iter().enumerate() {
            next[j] = x[j] - step[k];
        }
        let inside = free.iter().all(|&j| {
            let param = problem.free[j];
            if param.strictly_positive() {
                next[j] > 0.0
            } else {
                next[j] >= 0.0
            }
        });
        if !inside || !problem.residuals(&next, &mut r) {
            break;
        }
        x = next;
    }
    x
}

/// Jacobian of the weighted residuals with respect to the natural parameters: central
/// differences with steps `1e-6·max(|x|, step scale)` (forward where a non-negative parameter
/// sits at 0).
fn natural_jacobian(problem: &Problem<'_>, x: &[f64], m: usize) -> Vec<Vec<f64>> {
    let mut plus = vec![0.0; m];
    let mut minus = vec![0.0; m];
    let mut xp = x.to_vec();
    (0..x.len())
        .map(|j| {
            let h = problem.free[j].derivative_step(x[j]);
            xp[j] = x[j] + h;
            problem.residuals(&xp, &mut plus);
            let central = x[j] - h > 0.0;
            let step = if central {
                xp[j] = x[j] - h;
                problem.residuals(&xp, &mut minus);
                2.0 * h
            } else {
                problem.residuals(x, &mut minus);
                h
            };
            xp[j] = x[j];
            plus.iter()
                .zip(&minus)
                .map(|(a, b)| (a - b) / step)
                .collect()
        })
        .collect()
}

fn unidentifiable_all(free: &[Param]) -> FitError {
    FitError::Unidentifiable(
        free.iter()
            .map(|p| format!("`{}`", p.name()))
            .collect::<Vec<_>>()
            .join(", "),
    )
}

/// Refuses a fit whose normal matrix is (nearly) singular: a parameter without sensitivity, or
/// a combination of parameters the data cannot separate. Names the parameters involved.
fn check_identifiable(
    free: &[Param],
    a: &[f64],
    x: &[f64],
    problem: &Problem<'_>,
) -> Result<(), FitError> {
    let p = free.len();
    // Sensitivity of the residual vector to a change of each parameter by its own size (by its
    // typical scale where it is smaller, e.g. 0 at its bound), against the size of the weighted
    // data.
    let data_norm = problem
        .rows
        .iter()
        .map(|&(_, _, v, w)| (v * w) * (v * w))
        .sum::<f64>()
        .sqrt()
        .max(f64::MIN_POSITIVE);
    let dead: Vec<String> = (0..p)
        .filter(|&j| {
            let change = x[j].abs().max(free[j].typical_scale());
            a[j * p + j].sqrt() * change < 1e-9 * data_norm
        })
        .map(|j| format!("`{}`", free[j].name()))
        .collect();
    if !dead.is_empty() {
        return Err(FitError::Unidentifiable(dead.join(", ")));
    }
    // Equilibrated normal matrix: a correlation matrix of the linearized problem.
    let d: Vec<f64> = (0..p).map(|j| a[j * p + j].sqrt()).collect();
    let s: Vec<f64> = (0..p * p).map(|k| a[k] / (d[k / p] * d[k % p])).collect();
    let (values, vectors) = polbrdf::numeric::linalg::symmetric_eigen_dyn(&s, p);
    for (k, &lambda) in values.iter().enumerate() {
        if lambda < 1e-12 {
            let names: Vec<String> = (0..p)
                .filter(|&j| vectors[j * p + k].abs() > 0.2)
                .map(|j| format!("`{}`", free[j].name()))
                .collect();
            return Err(FitError::Unidentifiable(names.join(", ")));
        }
    }
    Ok(())
}

/// Runs the zero-bistatic inversion when the roughness is free and the data hold at least three
/// backscatter BRDF measurements.
fn zero_bistatic_start(
    base: &MaterialSpec,
    free: &[Param],
    data: &[Measurement],
) -> Option<ZbsFit> {
    if base.is_spectral() || !free.iter().any(|p| matches!(p, Param::B | Param::SigmaDeg)) {
        return None;
    }
    let points: Vec<ZbsPoint> = data
        .iter()
        .filter(|d| d.observable == Observable::Brdf)
        .filter_map(|d| {
            let v = d.geometry.angle_variables()?;
            (v.beta.abs() < 1e-6).then_some(ZbsPoint {
                theta: 0.5 * (v.theta_i + v.theta_r),
                f: d.value,
                sigma: d.sigma,
            })
        })
        .collect();
    let index = polbrdf::RefractiveIndex::new(base.n, base.k).ok()?;
    zbs::invert(&points, index, base.rho_d, base.rho_v).ok()
}
