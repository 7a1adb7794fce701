//! The simplified Maxwell–Beard pBRDF of one validated material at one geometry: the readable
//! one-geometry path (docs/model.md §6). Every number it returns traces to one equation, and the
//! batch engine (`crate::engine`) evaluates exactly the same functions, across blocks.
//!
//! The call path of [`Material::evaluate`], one function per equation:
//!
//! | step | function | equation |
//! |---|---|---|
//! | sines and cosines | [`Trig::new`] | — |
//! | θN, β, ΦN, cos β, sin²β | [`FacetAngles::from_trig`] | docs/model.md §1, §9.2 |
//! | signed η_i, η_r | [`angles::eta_pairs`], [`angles::rotations`] | eq. 11, §4 |
//! | `q`, `|rs|²`, `|rp|²`, rs, rp | [`fresnel::transmitted_q`], [`fresnel::reflectances`], [`fresnel::amplitudes`] | eqs. 10–11, §3 |
//! | D | [`Distribution::eval_with`] | eq. 4 |
//! | SO | [`Shadowing::ratio`] | eq. 3 |
//! | g = f_s/R_F, f_v | [`terms::surface_and_volume`] | eqs. 1, 6 |
//! | A, B, C, S of `diag(rs, rp)` | [`mueller::diagonal_coefficients`] | Bohren & Huffman |
//! | F | [`mueller::facet_pbrdf`] | eq. 9 corrected, §6 |

use crate::geometry::angles::{self, AngleVariables, FacetAngles, Trig};
use crate::geometry::direction::Geometry;
use crate::model::distribution::Distribution;
use crate::model::shadowing::Shadowing;
use crate::model::spec::MaterialSpec;
use crate::model::terms::{self, Form};
use crate::numeric::math::{Math, Std};
use crate::optics::fresnel::{self, RefractiveIndex};
use crate::optics::mueller::{self, Mueller};
use crate::optics::stokes::Stokes;
use std::f64::consts::FRAC_PI_2;

/// The model's parameters of a validated material, apart from its index: what the surface and
/// volume terms need (both paths read them from here).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModelParams {
    /// The facet distribution D (eq. 4).
    pub distribution: Distribution,
    /// SO (eq. 3), `None` when switched off.
    pub shadowing: Option<Shadowing>,
    /// The surface-term form.
    pub form: Form,
    /// ρ_D (sr⁻¹).
    pub rho_d: f64,
    /// ρ_V (sr⁻¹).
    pub rho_v: f64,
}

impl ModelParams {
    /// Whether SO includes the `eq3` azimuth factor (the only term that needs ΦN).
    pub fn uses_phi_n(&self) -> bool {
        self.shadowing
            .is_some_and(|s| s.azimuth_term() == crate::model::shadowing::AzimuthTerm::Eq3)
    }

    /// `(g, f_v)` and the factors D and SO (as numerator and denominator) at `a`: eqs. 4, 3, 1/6.
    #[inline(always)]
    pub fn scalar_terms<M: Math<F = f64>>(&self, a: &FacetAngles) -> (f64, f64, f64, (f64, f64)) {
        let d = self.distribution.eval_with::<M>(a.theta_n);
        let so = self.shadowing.map_or((1.0, 1.0), |s| {
            s.ratio::<M>(a.theta_n, a.beta, a.phi_n, a.theta_i)
        });
        let (g, fv) = terms::surface_and_volume::<M>(self.form, d, so, a, self.rho_d, self.rho_v);
        (g, fv, d, so)
    }
}

/// A validated material: everything the model needs to evaluate the pBRDF.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    spec: MaterialSpec,
    index: RefractiveIndex,
    params: ModelParams,
    /// For a material built from a spectral spec at a wavelength: the wavelength (µm).
    wavelength_um: Option<f64>,
}

/// The terms of one surface evaluation, for tracing a number back to its equation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceTerms {
    /// The angle variables used.
    pub angles: AngleVariables,
    /// `D(θN)` (eq. 4), sr⁻¹.
    pub d: f64,
    /// `R_F(β)` (eq. 1).
    pub r_f: f64,
    /// `SO` (eq. 3); 1 when shadowing is off.
    pub so: f64,
}

/// One evaluation of the model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Evaluation {
    /// The 4×4 pBRDF `F` (sr⁻¹, psps basis): `f_s·M/M00 + f_v·diag(1,0,0,0)` (eq. 9 corrected).
    pub pbrdf: Mueller,
    /// Surface term `f_s` (eq. 1 or eq. 6), sr⁻¹.
    pub surface: f64,
    /// Volume term `f_v = ρ_D + 2ρ_V/(cosθi + cosθr)` (eq. 1), sr⁻¹.
    pub volume: f64,
    /// The intermediate quantities; `None` at or below the horizon.
    pub terms: Option<SurfaceTerms>,
}

impl Evaluation {
    /// The zero result (a direction at or below the horizon, docs/model.md §1).
    pub fn zero() -> Self {
        Self {
            pbrdf: Mueller::zero(),
            surface: 0.0,
            volume: 0.0,
            terms: None,
        }
    }

    /// The result where the material has no valid index (a spectral index whose data give
    /// none at the wavelength asked for): NaN everywhere.
    pub fn undefined() -> Self {
        Self {
            pbrdf: Mueller([[f64::NAN; 4]; 4]),
            surface: f64::NAN,
            volume: f64::NAN,
            terms: None,
        }
    }

    /// Scalar BRDF `f = F00 = f_s + f_v` (eqs. 1, 6), sr⁻¹.
    pub fn brdf(&self) -> f64 {
        self.pbrdf.m00()
    }

    /// DoLP of the reflected light for unpolarized input (eq. 13).
    pub fn dolp(&self) -> f64 {
        self.pbrdf.dolp_unpolarized()
    }

    /// Reflected Stokes radiance per unit irradiance for input `s` (eq. 12).
    pub fn reflect(&self, s: &Stokes) -> Stokes {
        self.pbrdf.apply(s)
    }
}

impl Material {
    pub(crate) fn from_parts(
        spec: MaterialSpec,
        index: RefractiveIndex,
        params: ModelParams,
    ) -> Self {
        Self {
            spec,
            index,
            params,
            wavelength_um: None,
        }
    }

    /// Records the spectral source and the wavelength a material was built at
    /// ([`MaterialSpec::build_at`]).
    pub(crate) fn set_origin(
        &mut self,
        spectral: Option<crate::model::spec::SpectralSource>,
        lambda_um: Option<f64>,
    ) {
        if spectral.is_some() {
            self.spec.spectral = spectral;
            self.wavelength_um = lambda_um;
        }
    }

    /// The wavelength (µm) this material was built at, for one with a spectral index
    /// ([`MaterialSpec::build_at`]); `None` for a constant index.
    pub fn wavelength_um(&self) -> Option<f64> {
        self.wavelength_um
    }

    /// The same material at another wavelength: its spectral index there (a constant index is
    /// unchanged).
    ///
    /// # Errors
    /// [`crate::Error::WavelengthOutOfRange`] outside the data.
    pub fn at_wavelength(&self, lambda_um: f64) -> crate::Result<Material> {
        let index = self.spec.index_at(lambda_um)?;
        let mut m = self.with_index(index);
        if self.spec.spectral.is_some() {
            m.wavelength_um = Some(lambda_um);
        }
        Ok(m)
    }

    /// The spec this material was built from.
    pub fn spec(&self) -> &MaterialSpec {
        &self.spec
    }
    /// Display name, if any.
    pub fn name(&self) -> Option<&str> {
        self.spec.name.as_deref()
    }
    /// Complex refractive index.
    pub fn index(&self) -> RefractiveIndex {
        self.index
    }
    /// The model's parameters apart from the index.
    pub fn params(&self) -> &ModelParams {
        &self.params
    }
    /// Facet distribution (eq. 4).
    pub fn distribution(&self) -> Distribution {
        self.params.distribution
    }
    /// Shadowing function (eq. 3), `None` when switched off.
    pub fn shadowing(&self) -> Option<Shadowing> {
        self.params.shadowing
    }
    /// Surface-term form.
    pub fn form(&self) -> Form {
        self.params.form
    }
    /// ρ_D (sr⁻¹).
    pub fn rho_d(&self) -> f64 {
        self.params.rho_d
    }
    /// ρ_V (sr⁻¹).
    pub fn rho_v(&self) -> f64 {
        self.params.rho_v
    }

    /// The same material with another complex index (its spec's `n`, `k` follow).
    pub fn with_index(&self, index: RefractiveIndex) -> Material {
        let mut m = self.clone();
        m.index = index;
        if m.spec.spectral.is_none() {
            m.spec.n = index.n();
            m.spec.k = index.k();
        }
        m
    }

    /// The same material without its volume term (`ρ_D = ρ_V = 0`): `F00` is then `f_s`.
    pub fn surface_only(&self) -> Material {
        let mut m = self.clone();
        m.params.rho_d = 0.0;
        m.params.rho_v = 0.0;
        m.spec.rho_d = 0.0;
        m.spec.rho_v = 0.0;
        m
    }

    /// The full evaluation at a geometry (docs/model.md §6; the call path in the module
    /// documentation). Zero at or below the horizon.
    pub fn evaluate(&self, g: &Geometry) -> Evaluation {
        self.evaluate_with_index(g, self.index)
    }

    /// As [`Material::evaluate`], with the complex index `index` instead of the material's own
    /// (the batch engine's per-element index uses it for the elements it does not vectorize).
    pub fn evaluate_with_index(&self, g: &Geometry, index: RefractiveIndex) -> Evaluation {
        if !g.is_above_horizon() {
            return Evaluation::zero();
        }
        let (ti, pi, tr, pr) = (g.theta_i(), g.phi_i(), g.theta_r(), g.phi_r());
        let t = Trig::new::<Std>(ti, pi, tr, pr);
        let a = FacetAngles::from_trig::<Std>(ti, &t, angles::phi_scale(pi, pr), true, true);
        let pairs = angles::eta_pairs::<Std>(&t);
        let [c_i, s_i, c_r, s_r] = pairs;
        let vars = AngleVariables {
            theta_i: ti,
            theta_r: tr,
            beta: a.beta,
            theta_n: a.theta_n,
            phi_n: a.phi_n,
            eta_i: s_i.atan2(c_i),
            eta_r: s_r.atan2(c_r),
        };
        self.evaluate_facet(&a, pairs, index, vars)
    }

    /// The pBRDF `F` at a geometry (eq. 9 corrected), sr⁻¹.
    pub fn pbrdf(&self, g: &Geometry) -> Mueller {
        self.evaluate(g).pbrdf
    }

    /// The scalar BRDF `f` at a geometry (eq. 1 / eq. 6), sr⁻¹.
    pub fn brdf(&self, g: &Geometry) -> f64 {
        self.evaluate(g).brdf()
    }

    /// DoLP for unpolarized input at a geometry (eq. 13).
    pub fn dolp(&self, g: &Geometry) -> f64 {
        self.evaluate(g).dolp()
    }

    /// The angle-variable entry point (docs/model.md §6): the full evaluation from explicit
    /// (θi, θr, β, θN, ΦN, η_i, η_r). Zero when θi or θr is at or beyond π/2 (or NaN).
    pub fn evaluate_angles(&self, v: &AngleVariables) -> Evaluation {
        self.evaluate_angles_with_index(v, self.index)
    }

    /// As [`Material::evaluate_angles`], with the complex index `index`.
    pub fn evaluate_angles_with_index(
        &self,
        v: &AngleVariables,
        index: RefractiveIndex,
    ) -> Evaluation {
        if !(v.theta_i < FRAC_PI_2 && v.theta_r < FRAC_PI_2) {
            return Evaluation::zero();
        }
        self.evaluate_facet(&FacetAngles::from_variables(v), v.eta_pairs(), index, *v)
    }

    /// Everything after the angles: Fresnel, D, SO, the surface and volume terms, F.
    fn evaluate_facet(
        &self,
        a: &FacetAngles,
        pairs: [f64; 4],
        index: RefractiveIndex,
        vars: AngleVariables,
    ) -> Evaluation {
        let (n2r, n2i) = index.squared();
        let (qr, qi) = fresnel::transmitted_q::<Std>(n2r, n2i, a.sin2_beta);
        let [rs2, rp2, inv_s, inv_p] = fresnel::reflectances::<Std>(n2r, n2i, a.cos_beta, qr, qi);
        let amp = fresnel::amplitudes::<Std>(n2r, n2i, a.cos_beta, qr, qi, inv_s, inv_p);
        let (g, fv, d, so) = self.params.scalar_terms::<Std>(a);
        let coef = mueller::diagonal_coefficients::<Std>(rs2, rp2, amp);
        let r_f = coef[0];
        let g = terms::flush_subnormal(g, r_f, d);
        let rot = angles::rotations::<Std>(pairs);
        let f = mueller::facet_pbrdf::<Std>(coef.map(|c| g * c), fv, rot);
        Evaluation {
            pbrdf: Mueller::from_row_major(&f),
            surface: g * r_f,
            volume: fv,
            terms: Some(SurfaceTerms {
                angles: vars,
                d,
                r_f,
                so: so.0 / so.1,
            }),
        }
    }

    /// The unpolarized volume term `f_v = ρ_D + 2ρ_V/(cosθi + cosθr)` (eq. 1), sr⁻¹.
    pub fn volume_term(&self, theta_i: f64, theta_r: f64) -> f64 {
        terms::volume::<Std>(
            self.params.rho_d,
            self.params.rho_v,
            1.0 / (theta_i.cos() + theta_r.cos()),
        )
    }
}
