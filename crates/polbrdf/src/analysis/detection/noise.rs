//! Signal and noise of one channel (detection.md §3): photon counting for a visible/NIR camera
//! (signal electrons, shot + dark + read + quantization noise, the full well), or a
//! noise-equivalent radiance for a thermal camera (given, or from a NETD); `M` frames averaged.

use crate::analysis::spectral::Band;
use crate::analysis::thermal::{planck, C2};
use crate::error::{non_negative, positive, Error, Result};
use std::f64::consts::PI;

/// Planck's constant (J·s, CODATA 2018, exact).
pub const H: f64 = 6.626_070_15e-34;
/// The speed of light in vacuum (m/s, CODATA 2018, exact).
pub const C: f64 = 299_792_458.0;

/// The most frames averaged.
pub const MAX_FRAMES: u32 = 1_000_000;

/// The projected solid angle of the optics' cone seen from a pixel, `Ω = π/(4F² + 1)`
/// (detection.md §3), for f-number `F`.
pub fn solid_angle(f_number: f64) -> f64 {
    PI / (4.0 * f_number * f_number + 1.0)
}

/// Photons per joule at wavelength `lambda_um` (µm): `λ/(h c)` (detection.md §3).
pub fn photons_per_joule(lambda_um: f64) -> f64 {
    lambda_um * 1e-6 / (H * C)
}

/// A photon-counting camera's channel (detection.md §3). Its channel values `I_k` are
/// band-integrated radiances weighted by the photon response of [`photon_band`]
/// (W·m⁻²·sr⁻¹), turned into electrons by `N = t·A_pix·Ω·τ_o·(λ_ref/hc)·I`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhotonCounting {
    /// Integration time (s, > 0).
    pub integration_time_s: f64,
    /// Pixel pitch (m, > 0): `A_pix = pitch²`.
    pub pixel_pitch_m: f64,
    /// f-number `F` (> 0).
    pub f_number: f64,
    /// Optics transmittance `τ_o` in (0, 1].
    pub optics_transmittance: f64,
    /// `λ_ref/(h c)` (J⁻¹) of the photon response the channel values are weighted with.
    pub photons_per_joule: f64,
    /// Dark current (e⁻/s, ≥ 0).
    pub dark_current_e_per_s: f64,
    /// Read noise (e⁻ rms, ≥ 0).
    pub read_noise_e: f64,
    /// ADC gain `g` (e⁻ per count, > 0).
    pub gain_e_per_count: f64,
    /// Full well `N_sat` (e⁻, > 0).
    pub full_well_e: f64,
}

/// The noise model of a sensor file (detection.md §3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NoiseModel {
    /// A photon-counting camera.
    PhotonCounting(PhotonCounting),
    /// A noise-equivalent radiance per channel per frame (> 0, in the units of the channel
    /// values `I_k`: band-integrated radiance, W·m⁻²·sr⁻¹).
    Nel {
        /// The NEL.
        nel: f64,
    },
}

impl PhotonCounting {
    /// Checks every field.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the field.
    pub fn validate(&self) -> Result<()> {
        positive("integration_time_s", self.integration_time_s)?;
        positive("pixel_pitch_m", self.pixel_pitch_m)?;
        positive("f_number", self.f_number)?;
        positive("optics_transmittance", self.optics_transmittance)?;
        if self.optics_transmittance > 1.0 {
            return Err(Error::InvalidParameter {
                name: "optics_transmittance",
                value: self.optics_transmittance,
                reason: "must lie in (0, 1]",
            });
        }
        positive("photons_per_joule", self.photons_per_joule)?;
        non_negative("dark_current_e_per_s", self.dark_current_e_per_s)?;
        non_negative("read_noise_e", self.read_noise_e)?;
        positive("gain_e_per_count", self.gain_e_per_count)?;
        positive("full_well_e", self.full_well_e)?;
        Ok(())
    }

    /// Electrons per unit channel value: `t·A_pix·Ω·τ_o·λ_ref/(h c)` (detection.md §3).
    pub fn electrons_per_radiance(&self) -> f64 {
        self.integration_time_s
            * self.pixel_pitch_m
            * self.pixel_pitch_m
            * solid_angle(self.f_number)
            * self.optics_transmittance
            * self.photons_per_joule
    }
}

impl NoiseModel {
    /// Checks the model.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the field (`nel`: finite and > 0).
    pub fn validate(&self) -> Result<()> {
        match self {
            NoiseModel::PhotonCounting(p) => p.validate(),
            NoiseModel::Nel { nel } => positive("nel", *nel).map(|_| ()),
        }
    }

    /// The factor from a channel value `I_k` to the channel's signal: electrons
    /// ([`PhotonCounting::electrons_per_radiance`]) or 1 (NEL).
    pub fn gain(&self) -> f64 {
        match self {
            NoiseModel::PhotonCounting(p) => p.electrons_per_radiance(),
            NoiseModel::Nel { .. } => 1.0,
        }
    }

    /// The variance of one frame of a channel whose signal is `signal` (detection.md §3):
    /// `N + N_dark + σ_read² + g²/12` electrons², or `NEL²`. A negative signal (impossible
    /// for a physical radiance) counts no shot noise.
    pub fn variance(&self, signal: f64) -> f64 {
        match self {
            NoiseModel::PhotonCounting(p) => {
                signal.max(0.0)
                    + p.dark_current_e_per_s * p.integration_time_s
                    + p.read_noise_e * p.read_noise_e
                    + p.gain_e_per_count * p.gain_e_per_count / 12.0
            }
            NoiseModel::Nel { nel } => nel * nel,
        }
    }

    /// Whether a channel of signal `signal` (plus its dark electrons) is above the full well
    /// (detection.md §3: flagged, never clipped); never for a NEL model.
    pub fn saturated(&self, signal: f64) -> bool {
        match self {
            NoiseModel::PhotonCounting(p) => {
                signal + p.dark_current_e_per_s * p.integration_time_s > p.full_well_e
            }
            NoiseModel::Nel { .. } => false,
        }
    }
}

/// A quantum efficiency: constant or tabulated (linear between rows).
#[derive(Debug, Clone, PartialEq)]
pub enum QuantumEfficiency {
    /// The same at every wavelength, in (0, 1].
    Constant(f64),
    /// `(λ µm, η)` rows, λ strictly increasing, η in [0, 1].
    Table(Vec<(f64, f64)>),
}

impl QuantumEfficiency {
    /// η at `lambda_um`: linear between rows; `None` outside the table (never extrapolated).
    pub fn at(&self, lambda_um: f64) -> Option<f64> {
        match self {
            QuantumEfficiency::Constant(q) => Some(*q),
            QuantumEfficiency::Table(rows) => {
                let (first, last) = (rows.first()?, rows.last()?);
                if !(first.0..=last.0).contains(&lambda_um) {
                    return None;
                }
                let i = rows.partition_point(|r| r.0 < lambda_um);
                if i == 0 {
                    return Some(first.1);
                }
                let (a, b) = (rows[i - 1], rows[i]);
                Some(a.1 + (lambda_um - a.0) / (b.0 - a.0) * (b.1 - a.1))
            }
        }
    }

    /// The tabulated wavelengths (none for a constant).
    fn nodes(&self) -> Vec<f64> {
        match self {
            QuantumEfficiency::Constant(_) => Vec::new(),
            QuantumEfficiency::Table(rows) => rows.iter().map(|r| r.0).collect(),
        }
    }
}

/// The photon response `P(λ) = R(λ)·η(λ)·λ/λ_ref` of a band `R` and a quantum efficiency `η`,
/// as a band tabulated at the nodes of both, each interval cut into pieces of at most 1/16 of
/// the band's width (linear interpolation of the piecewise-quadratic product: relative error
/// below ~1e-3, docs/detection.md), with `λ_ref` the band's centre; and `λ_ref/(h c)` (J⁻¹).
/// `∫ P(λ)·S(λ) dλ · λ_ref/(h c)` is then the photo-electron rate per unit étendue of
/// detection.md §3.
///
/// # Errors
/// [`Error::InconsistentParameters`] when the band reaches outside a QE table's wavelengths;
/// as [`Band::new`].
pub fn photon_band(band: &Band, qe: &QuantumEfficiency) -> Result<(Band, f64)> {
    let (lo, hi) = band.range();
    let mut nodes: Vec<f64> = band.table().0.to_vec();
    nodes.extend(qe.nodes().into_iter().filter(|l| (lo..=hi).contains(l)));
    nodes.sort_by(f64::total_cmp);
    nodes.dedup();
    let max_piece = (hi - lo) / 16.0;
    let mut fine = vec![nodes[0]];
    for w in nodes.windows(2) {
        let n = ((w[1] - w[0]) / max_piece).ceil().max(1.0) as usize;
        fine.extend((1..=n).map(|j| w[0] + (w[1] - w[0]) * j as f64 / n as f64));
    }
    let lambda_ref = 0.5 * (lo + hi);
    let mut response = Vec::with_capacity(fine.len());
    for &l in &fine {
        let eta = qe.at(l).ok_or_else(|| {
            Error::InconsistentParameters(format!(
                "the quantum efficiency table does not cover the band: no value at {l} µm \
                 (the band spans {lo}–{hi} µm)"
            ))
        })?;
        response.push(band.response(l) * eta * l / lambda_ref);
    }
    let name = format!("{} × QE × λ/λref", band.name());
    Ok((
        Band::new(&name, fine, response)?,
        photons_per_joule(lambda_ref),
    ))
}

/// `∂B_λ/∂T` (W·m⁻²·sr⁻¹·µm⁻¹·K⁻¹) at `lambda_um`, `temperature_k`: `B·x·eˣ/((eˣ − 1)·T)` with
/// `x = c2/(λT)`.
pub fn planck_derivative(lambda_um: f64, temperature_k: f64) -> f64 {
    let x = C2 / (lambda_um * temperature_k);
    if x > 700.0 {
        return 0.0;
    }
    // x·eˣ/(eˣ − 1) = x/(1 − e⁻ˣ)
    planck(lambda_um, temperature_k) * x / (-(-x).exp_m1()) / temperature_k
}

/// `∫ R(λ)·B_λ(λ, T) dλ` (W·m⁻²·sr⁻¹) on the quadrature `nodes` `(λ, weight)` of a band
/// integral ([`crate::Spectrum::integral_nodes`]).
pub fn band_planck(nodes: &[(f64, f64)], temperature_k: f64) -> f64 {
    nodes
        .iter()
        .map(|(l, w)| w * planck(*l, temperature_k))
        .sum()
}

/// `NEL = NETD · ∂/∂T ∫ R(λ)·B(λ, T) dλ |_{T_ref}` (detection.md §3) on the quadrature
/// `nodes` of the band.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `netd_k` or `reference_temperature_k` when not finite
/// and > 0, or `nel` when the band has no thermal signal at `T_ref` (NEL not > 0).
pub fn nel_from_netd(
    netd_k: f64,
    reference_temperature_k: f64,
    nodes: &[(f64, f64)],
) -> Result<f64> {
    positive("netd_k", netd_k)?;
    positive("reference_temperature_k", reference_temperature_k)?;
    let d: f64 = nodes
        .iter()
        .map(|(l, w)| w * planck_derivative(*l, reference_temperature_k))
        .sum();
    positive("nel", netd_k * d)
}
