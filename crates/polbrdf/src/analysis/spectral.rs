//! Spectra and bands (docs/model.md §15): a band's relative spectral response R(λ), and the
//! quadrature that integrates a spectral quantity over it.
//!
//! A band is a relative spectral response `R(λ)` tabulated at strictly increasing wavelengths,
//! linear between them and zero outside. Stokes vectors add incoherently, so a band result is
//! the band integral of the **Stokes vector**, `S_band = ∫ R(λ)·S(λ) dλ`, and its DoLP is that
//! of `S_band` — never an average of DoLPs. Reflectance-like results (per unit irradiance, sr⁻¹)
//! use the response-weighted mean `∫ R·S dλ / ∫ R dλ` (a flat source spectrum); radiances the
//! integral itself.
//!
//! **Quadrature.** The integrand is smooth between the response's nodes and the nodes of the
//! materials' tabulated indices (both piecewise linear in λ): every such node is a panel edge,
//! each panel is split into pieces of at most `step`, and each piece takes the 3-point
//! Gauss–Legendre rule — exact for `R·S` polynomial of degree 5 on the piece. With the default
//! step (1/16 of the band's width) a band integral of the model agrees with one on a step 8
//! times finer to better than 1e-9 relative (`tests/spectral.rs`).

use crate::error::{Error, Result};
use crate::model::{Material, MaterialSpec};
use crate::optics::dispersion::Dispersion;

/// The most rows of a band's response: each row is a panel edge of the band quadrature, and
/// every panel takes at least three evaluations of the model at every view (a 1.9 MB band file
/// of 10⁵ rows ran for minutes: issue 35). 10⁴ rows hold a response at 1 nm from 0.3 µm to
/// 10 µm; a finer measured response is resampled before use.
pub const MAX_BAND_ROWS: usize = 10_000;

/// A relative spectral response (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    name: String,
    wavelengths: Vec<f64>,
    response: Vec<f64>,
}

impl Band {
    /// A band from its response `response[i]` at `wavelengths[i]` (µm, strictly increasing,
    /// > 0); `name` for messages.
    ///
    /// # Errors
    /// [`Error::InvalidParameterAt`] naming `wavelength_um` or `response` and the element for a
    /// value that is not finite, a wavelength ≤ 0 or not above the previous one, or a negative
    /// response, and for a row beyond the [`MAX_BAND_ROWS`]th; [`Error::InconsistentParameters`] for fewer than two points or a response that
    /// is zero everywhere.
    pub fn new(name: &str, wavelengths: Vec<f64>, response: Vec<f64>) -> Result<Self> {
        let at = |name: &'static str, value: f64, index: usize, reason: &'static str| {
            Err(Error::InvalidParameterAt {
                name,
                value,
                index,
                reason,
            })
        };
        if wavelengths.len() != response.len() {
            return Err(Error::LengthMismatch {
                name: "response",
                got: response.len(),
                expected: wavelengths.len(),
            });
        }
        if wavelengths.len() < 2 {
            return Err(Error::InconsistentParameters(format!(
                "band `{name}`: a response needs at least two wavelengths"
            )));
        }
        if let Some(&l) = wavelengths.get(MAX_BAND_ROWS) {
            return at(
                "wavelength_um",
                l,
                MAX_BAND_ROWS,
                "a band response has at most 10⁴ rows (polbrdf::analysis::spectral::\
                 MAX_BAND_ROWS): each row is a panel edge of the band quadrature, three model \
                 evaluations per view; resample a finer response",
            );
        }
        for (i, (&l, &r)) in wavelengths.iter().zip(&response).enumerate() {
            if !(l.is_finite() && l > 0.0) {
                return at("wavelength_um", l, i, "must be finite and > 0");
            }
            if i > 0 && l <= wavelengths[i - 1] {
                return at(
                    "wavelength_um",
                    l,
                    i,
                    "wavelengths must increase strictly from row to row",
                );
            }
            if !(r.is_finite() && r >= 0.0) {
                return at("response", r, i, "must be finite and >= 0");
            }
        }
        if response.iter().all(|r| *r == 0.0) {
            return Err(Error::InconsistentParameters(format!(
                "band `{name}`: the response is zero everywhere"
            )));
        }
        Ok(Self {
            name: name.to_string(),
            wavelengths,
            response,
        })
    }

    /// The band's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The wavelengths (µm) and the response at them.
    pub fn table(&self) -> (&[f64], &[f64]) {
        (&self.wavelengths, &self.response)
    }

    /// The range (µm) where the response can be non-zero: from the last zero before the first
    /// non-zero value to the first zero after the last one.
    pub fn range(&self) -> (f64, f64) {
        let first = self.response.iter().position(|r| *r > 0.0).unwrap_or(0);
        let last = self.response.iter().rposition(|r| *r > 0.0).unwrap_or(0);
        let lo = self.wavelengths[first.saturating_sub(1)];
        let hi = self.wavelengths[(last + 1).min(self.wavelengths.len() - 1)];
        (lo, hi)
    }

    /// `R(λ)`: linear between the nodes, 0 outside.
    pub fn response(&self, lambda_um: f64) -> f64 {
        let (x, y) = (&self.wavelengths, &self.response);
        if !(lambda_um >= x[0] && lambda_um <= x[x.len() - 1]) {
            return 0.0;
        }
        let i = x.partition_point(|&v| v <= lambda_um).clamp(1, x.len() - 1);
        let t = (lambda_um - x[i - 1]) / (x[i] - x[i - 1]);
        y[i - 1] + (y[i] - y[i - 1]) * t
    }

    /// Checks a quadrature step (µm): finite, > 0, and not so small that the band would be
    /// split into more than 10⁵ pieces (a step that small is a typo, and would exhaust memory).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `band_step_um`.
    pub fn check_step(&self, step: f64) -> Result<f64> {
        let (lo, hi) = self.range();
        if !(step.is_finite() && step > 0.0) {
            return Err(Error::InvalidParameter {
                name: "band_step_um",
                value: step,
                reason: "must be finite and > 0 (µm)",
            });
        }
        if (hi - lo) / step > 1e5 {
            return Err(Error::InvalidParameter {
                name: "band_step_um",
                value: step,
                reason: "splits the band into more than 10⁵ pieces: give a step of at least \
                         1e-5 of the band's width",
            });
        }
        Ok(step)
    }

    /// The default quadrature step: 1/16 of the band's width.
    pub fn default_step(&self) -> f64 {
        let (lo, hi) = self.range();
        (hi - lo) / 16.0
    }

    /// Quadrature nodes `(λ, w)` for `∫ R(λ)·g(λ) dλ ≈ Σ w·g(λ)` (module documentation): panel
    /// edges at the response's nodes and at `breaks` (e.g. the tabulated wavelengths of the
    /// materials' indices), pieces of at most `step` µm, 3-point Gauss–Legendre on each. Nodes
    /// where the response is 0 are left out.
    pub fn nodes(&self, step: f64, breaks: &[f64]) -> Vec<(f64, f64)> {
        let (lo, hi) = self.range();
        let mut edges: Vec<f64> = self
            .wavelengths
            .iter()
            .chain(breaks)
            .copied()
            .filter(|l| *l >= lo && *l <= hi)
            .chain([lo, hi])
            .collect();
        edges.sort_by(f64::total_cmp);
        edges.dedup();
        let step = if step.is_finite() && step > 0.0 {
            step
        } else {
            self.default_step()
        };
        let gl = [
            (-(0.6f64.sqrt()), 5.0 / 18.0),
            (0.0, 8.0 / 18.0),
            (0.6f64.sqrt(), 5.0 / 18.0),
        ];
        let mut out = Vec::new();
        for w in edges.windows(2) {
            let (a, b) = (w[0], w[1]);
            let pieces = ((b - a) / step).ceil().max(1.0) as usize;
            let h = (b - a) / pieces as f64;
            for p in 0..pieces {
                let mid = a + (p as f64 + 0.5) * h;
                for (x, wt) in gl {
                    let l = mid + 0.5 * h * x;
                    let r = self.response(l);
                    if r > 0.0 {
                        out.push((l, wt * h * r));
                    }
                }
            }
        }
        out
    }
}

/// At what spectrum an analysis runs: one wavelength, or the response-weighted mean over a band.
#[derive(Debug, Clone, PartialEq)]
pub enum Spectrum {
    /// One wavelength (µm).
    Wavelength(f64),
    /// A band, with the quadrature step (µm; `None` for the default).
    Band(Band, Option<f64>),
}

impl Spectrum {
    /// The wavelengths and weights of the response-weighted mean (weights summing to 1): one
    /// node of weight 1 for a wavelength; the band's quadrature nodes, normalized, with panel
    /// edges at the tabulated wavelengths of every spectral index among `specs`.
    pub fn mean_nodes(&self, specs: &[&MaterialSpec]) -> Vec<(f64, f64)> {
        let mut nodes = self.integral_nodes(specs);
        let total: f64 = nodes.iter().map(|n| n.1).sum();
        for n in &mut nodes {
            n.1 /= total;
        }
        nodes
    }

    /// The wavelengths and weights of the band integral `∫ R(λ)·g(λ) dλ` (µm): for one
    /// wavelength, the node itself with weight 1.
    pub fn integral_nodes(&self, specs: &[&MaterialSpec]) -> Vec<(f64, f64)> {
        match self {
            Spectrum::Wavelength(l) => vec![(*l, 1.0)],
            Spectrum::Band(band, step) => {
                let breaks: Vec<f64> = specs.iter().flat_map(|s| table_nodes(s)).collect();
                band.nodes(step.unwrap_or_else(|| band.default_step()), &breaks)
            }
        }
    }

    /// The materials of `spec` at each node of `nodes`.
    ///
    /// # Errors
    /// As [`MaterialSpec::build_at`]: a node outside a spectral index's data names the
    /// material and its range.
    pub fn materials(spec: &MaterialSpec, nodes: &[(f64, f64)]) -> Result<Vec<Material>> {
        let first = spec.build_at(nodes.first().map_or(1.0, |n| n.0))?;
        nodes.iter().map(|(l, _)| first.at_wavelength(*l)).collect()
    }
}

/// The tabulated wavelengths of a spectral index (where its n or k has a kink).
fn table_nodes(spec: &MaterialSpec) -> Vec<f64> {
    let Some(s) = &spec.spectral else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for d in std::iter::once(&s.index.n).chain(s.index.k.as_ref()) {
        if let Dispersion::Table { wavelengths, .. } = d {
            out.extend_from_slice(wavelengths);
        }
    }
    out
}
