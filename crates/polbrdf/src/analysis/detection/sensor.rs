//! A sensor as a sensor file describes it ([`SensorSpec`]), and the [`Sensor`] and spectrum it
//! makes (detection.md §2–3, §5): the spectral weights the scene is integrated with (the band
//! response, times the quantum efficiency and `λ/λ_ref` for a photon-counting camera), the
//! noise model (a NETD turned into a NEL on that band), the ADC gain, and the IFOV of one Stokes
//! pixel (a 2×2 super-pixel for a division-of-focal-plane camera).

use super::noise::{nel_from_netd, photon_band, PhotonCounting, QuantumEfficiency};
use super::{Analyzer, NoiseModel, Sensor};
use crate::analysis::spectral::{Band, Spectrum};
use crate::error::{positive, Error, Result};

/// How the analyzer channels share the focal plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// Division of focal plane: one Stokes pixel is a 2×2 super-pixel (IFOV `2·pitch/f`).
    Dofp,
    /// Every channel sees the whole pixel (division of time or of amplitude): IFOV `pitch/f`.
    PerPixel,
}

impl Layout {
    /// Every layout, the default first.
    pub const ALL: [Layout; 2] = [Layout::Dofp, Layout::PerPixel];

    /// The layout named `name` ([`Layout::as_str`]).
    pub fn parse(name: &str) -> Option<Self> {
        crate::names::find(&Self::ALL, Self::as_str, name)
    }

    /// Its name in sensor files: `dofp`, `per-pixel`.
    pub fn as_str(self) -> &'static str {
        match self {
            Layout::Dofp => "dofp",
            Layout::PerPixel => "per-pixel",
        }
    }
}

/// The noise of a sensor file (detection.md §3).
#[derive(Debug, Clone, PartialEq)]
pub enum NoiseSpec {
    /// A photon-counting camera.
    PhotonCounting {
        /// Integration time (s).
        integration_time_s: f64,
        /// f-number.
        f_number: f64,
        /// Optics transmittance.
        optics_transmittance: f64,
        /// Quantum efficiency.
        quantum_efficiency: QuantumEfficiency,
        /// Dark current (e⁻/s).
        dark_current_e_per_s: f64,
        /// Read noise (e⁻ rms).
        read_noise_e: f64,
        /// ADC bits: the ADC spans the full well, `g = N_sat/2^bits` e⁻ per count.
        adc_bits: u32,
        /// Full well (e⁻).
        full_well_e: f64,
    },
    /// A noise-equivalent radiance per channel per frame (W·m⁻²·sr⁻¹, band-integrated).
    Nel(f64),
    /// A NETD (K) at a reference temperature (K): `NEL = NETD·∂/∂T ∫R·B dλ`.
    Netd {
        /// NETD (K).
        netd_k: f64,
        /// Reference temperature (K).
        reference_temperature_k: f64,
    },
}

/// A sensor file, read.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorSpec {
    /// A display name.
    pub name: String,
    /// The analyzers.
    pub analyzer: Analyzer,
    /// The layout.
    pub layout: Layout,
    /// Pixel pitch (m).
    pub pixel_pitch_m: f64,
    /// Focal length (m).
    pub focal_length_m: f64,
    /// Frames averaged.
    pub frames: u32,
    /// The band response.
    pub band: Band,
    /// The noise.
    pub noise: NoiseSpec,
}

impl SensorSpec {
    /// The IFOV of one Stokes pixel (rad): `pitch/f`, doubled for a DoFP super-pixel
    /// (detection.md §5).
    pub fn ifov_rad(&self) -> f64 {
        let pixel = self.pixel_pitch_m / self.focal_length_m;
        match self.layout {
            Layout::Dofp => 2.0 * pixel,
            Layout::PerPixel => pixel,
        }
    }

    /// The sensor and the spectrum a scene is observed over for it: the photon response
    /// ([`photon_band`]) of a photon-counting camera, else the band itself.
    ///
    /// # Errors
    /// As [`photon_band`], [`nel_from_netd`] and [`Sensor::validate`];
    /// [`Error::InvalidParameter`] naming `adc_bits` outside 1..=32, `pixel_pitch_m` or
    /// `focal_length_m` not finite and > 0.
    pub fn sensor(&self) -> Result<(Sensor, Spectrum)> {
        positive("pixel_pitch_m", self.pixel_pitch_m)?;
        positive("focal_length_m", self.focal_length_m)?;
        let (noise, spectrum) = match &self.noise {
            NoiseSpec::PhotonCounting {
                integration_time_s,
                f_number,
                optics_transmittance,
                quantum_efficiency,
                dark_current_e_per_s,
                read_noise_e,
                adc_bits,
                full_well_e,
            } => {
                if !(1..=32).contains(adc_bits) {
                    return Err(Error::InvalidParameter {
                        name: "adc_bits",
                        value: f64::from(*adc_bits),
                        reason: "must lie in 1..=32",
                    });
                }
                let (band, photons_per_joule) = photon_band(&self.band, quantum_efficiency)?;
                let noise = NoiseModel::PhotonCounting(PhotonCounting {
                    integration_time_s: *integration_time_s,
                    pixel_pitch_m: self.pixel_pitch_m,
                    f_number: *f_number,
                    optics_transmittance: *optics_transmittance,
                    photons_per_joule,
                    dark_current_e_per_s: *dark_current_e_per_s,
                    read_noise_e: *read_noise_e,
                    gain_e_per_count: full_well_e / 2f64.powi(*adc_bits as i32),
                    full_well_e: *full_well_e,
                });
                (noise, Spectrum::Band(band, None))
            }
            NoiseSpec::Nel(nel) => (
                NoiseModel::Nel { nel: *nel },
                Spectrum::Band(self.band.clone(), None),
            ),
            NoiseSpec::Netd {
                netd_k,
                reference_temperature_k,
            } => {
                let spectrum = Spectrum::Band(self.band.clone(), None);
                let nodes = spectrum.integral_nodes(&[]);
                let nel = nel_from_netd(*netd_k, *reference_temperature_k, &nodes)?;
                (NoiseModel::Nel { nel }, spectrum)
            }
        };
        let sensor = Sensor {
            analyzer: self.analyzer.clone(),
            noise,
            frames: self.frames,
            ifov_rad: self.ifov_rad(),
        };
        sensor.validate()?;
        Ok((sensor, spectrum))
    }
}
