//! What the camera sees (detection.md §6): a simulated raw frame of a division-of-focal-plane
//! (DoFP) camera — the target as a square of super-pixels on its background — and the Stokes
//! images reconstructed from it, one estimate per 2×2 super-pixel (no interpolation).
//!
//! **Layout.** Each 2×2 super-pixel carries the analyzers `[[90°, 45°], [135°, 0°]]` (row 0 then
//! row 1, left to right): raw pixel `(2i, 2j)` is the 90° analyzer, `(2i, 2j+1)` the 45°,
//! `(2i+1, 2j)` the 135° and `(2i+1, 2j+1)` the 0°.
//!
//! **One raw pixel, one frame.** Its electrons are Poisson with mean `N_k + N_dark` (signal and
//! dark, §3), clipped at the full well `N_sat` (flagged); Gaussian read noise of standard
//! deviation `σ_read` is added; the ADC gives `round(e/g)` counts, at least 0 and at most
//! `2^bits − 1` (the top count is flagged as saturated too). With `M` frames averaged the raw
//! value is the mean of the `M` frames' counts (flagged when any frame saturated).
//!
//! **Reconstruction.** Per super-pixel the channel estimates are `I_k = g·counts_k − N_dark`
//! (the mean dark level, known from calibration, is subtracted), and `Ŝ = W₃⁺ I` with the
//! camera's reconstruction matrix (§4). Ŝ is in electrons per frame (the analysis vectors' scale:
//! for an ideal analyzer, `Ŝ0` is what the pixel would collect without it). DoLP and AoLP use
//! the crate's one definition ([`crate::optics::stokes`]). A super-pixel with a saturated raw
//! pixel has no estimate: its S0, DoLP and AoLP are NaN and it is left out of the statistics.
//!
//! **Randomness.** One [`SplitMix64`] stream seeded by the caller, drawn in raw-pixel row-major
//! order (for each pixel: for each frame, the Poisson count then the read noise): the same seed
//! gives the same frame on every platform for a given build (the Poisson sampler is
//! `rand_distr`'s, pinned by `Cargo.lock`).

use super::{NoiseModel, Sensor};
use crate::error::{Error, Result};
use crate::numeric::sample::SplitMix64;
use crate::optics::stokes::Stokes;
use rand_distr::{Distribution, Poisson};

/// The analyzer angle (degrees) of each raw pixel of a super-pixel, `[row][column]`.
pub const LAYOUT_DEG: [[f64; 2]; 2] = [[90.0, 45.0], [135.0, 0.0]];

/// The largest frame side, in super-pixels (a 2048 × 2048 raw frame, 32 MiB of counts).
pub const MAX_SIDE: usize = 1024;

/// The most random draws one frame may take (raw pixels × frames averaged), about 30 s of
/// simulation on one core.
pub const MAX_DRAWS: u64 = 1 << 28;

/// How the camera turns electrons into counts (detection.md §3; per frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Readout {
    /// Mean dark electrons per pixel per frame (dark current × integration time), ≥ 0.
    pub dark_e: f64,
    /// Read noise, electrons RMS, ≥ 0.
    pub read_noise_e: f64,
    /// ADC gain `g`, electrons per count, > 0.
    pub gain_e_per_count: f64,
    /// ADC bits, 1 to 32.
    pub adc_bits: u32,
    /// Full well `N_sat`, electrons, > 0.
    pub full_well_e: f64,
    /// Frames averaged `M`, ≥ 1.
    pub frames: u32,
}

/// What to simulate: the scene as electrons per channel, the camera's readout and
/// reconstruction, the frame's size and the seed.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameSpec {
    /// Frame side, super-pixels (1 to [`MAX_SIDE`]); the raw frame is twice as wide.
    pub side: usize,
    /// The target square's side, super-pixels (0 to `side`), centred.
    pub target_side: usize,
    /// Analyzer angle of each channel, degrees: 0, 45, 90 and 135 in any order (mod 180).
    pub angles_deg: [f64; 4],
    /// Mean signal electrons per frame of each channel on the target (`N_k`, §3).
    pub target_e: [f64; 4],
    /// Mean signal electrons per frame of each channel on the background.
    pub background_e: [f64; 4],
    /// The reconstruction matrix `W₃⁺` by columns: channel `k`'s column `c_k`, so that
    /// `Ŝ = Σ_k I_k·c_k` (as [`super::Analyzer::pseudo_inverse`] gives it).
    pub reconstruction: [[f64; 3]; 4],
    /// The readout.
    pub readout: Readout,
    /// The seed of the random stream.
    pub seed: u64,
}

impl FrameSpec {
    /// The frame of a photon-counting DoFP `sensor` whose pixels see `target` and `background`
    /// (Stokes radiance at the sensor, after the path, in the units its channels weigh —
    /// [`super::Path::apply`]): channel means `N_k = gain·a_k·S'` ([`super::Analyzer::measure`],
    /// [`NoiseModel::gain`]), the reconstruction `W₃⁺` of its analyzer, dark electrons
    /// `dark current × integration time`, its read noise, gain, full well and frames averaged,
    /// and an ADC of `adc_bits`.
    ///
    /// # Errors
    /// [`Error::InconsistentParameters`] for a NEL (thermal) sensor, which has no electrons to
    /// draw, or one without exactly four channels; then as [`simulate`] (checked there).
    pub fn for_sensor(
        sensor: &Sensor,
        target: &Stokes,
        background: &Stokes,
        adc_bits: u32,
        (side, target_side): (usize, usize),
        seed: u64,
    ) -> Result<FrameSpec> {
        let NoiseModel::PhotonCounting(p) = &sensor.noise else {
            return Err(Error::InconsistentParameters(
                "a simulated frame needs a photon-counting camera: a noise-equivalent-radiance \
                 (thermal) sensor has no electrons to draw"
                    .into(),
            ));
        };
        let analyzer = &sensor.analyzer;
        if analyzer.channels() != 4 {
            return Err(Error::InconsistentParameters(format!(
                "a simulated DoFP frame needs 4 analyzer channels (0°, 45°, 90°, 135°), the sensor \
                 has {}",
                analyzer.channels()
            )));
        }
        let gain = sensor.noise.gain();
        let electrons = |s: &Stokes| -> [f64; 4] {
            let i = analyzer.measure(s);
            std::array::from_fn(|k| gain * i[k])
        };
        Ok(FrameSpec {
            side,
            target_side,
            angles_deg: std::array::from_fn(|k| analyzer.angles()[k].to_degrees()),
            target_e: electrons(target),
            background_e: electrons(background),
            reconstruction: std::array::from_fn(|k| analyzer.pseudo_inverse()[k]),
            readout: Readout {
                dark_e: p.dark_current_e_per_s * p.integration_time_s,
                read_noise_e: p.read_noise_e,
                gain_e_per_count: p.gain_e_per_count,
                adc_bits,
                full_well_e: p.full_well_e,
                frames: sensor.frames,
            },
            seed,
        })
    }
}

/// Sample mean and variance of a set of values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleMoments {
    /// Number of values.
    pub n: usize,
    /// Their mean (NaN when `n = 0`).
    pub mean: f64,
    /// Their unbiased sample variance (divisor `n − 1`; NaN when `n < 2`).
    pub variance: f64,
}

impl SampleMoments {
    /// The moments of the finite values among `values` where `keep` is true.
    pub fn of(values: &[f64], keep: impl Fn(usize) -> bool) -> SampleMoments {
        let (mut n, mut mean, mut m2) = (0usize, 0.0, 0.0);
        for (i, &v) in values.iter().enumerate() {
            if keep(i) && v.is_finite() {
                // Welford's update: stable for many values of similar size.
                n += 1;
                let d = v - mean;
                mean += d / n as f64;
                m2 += d * (v - mean);
            }
        }
        SampleMoments {
            n,
            mean: if n > 0 { mean } else { f64::NAN },
            variance: if n > 1 { m2 / (n - 1) as f64 } else { f64::NAN },
        }
    }
}

/// Measured statistics of one region (target or background) over its unsaturated
/// super-pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegionStats {
    /// `Ŝ0`, electrons.
    pub s0: SampleMoments,
    /// `Ŝ1`, electrons.
    pub s1: SampleMoments,
    /// `Ŝ2`, electrons.
    pub s2: SampleMoments,
    /// Estimated DoLP.
    pub dolp: SampleMoments,
}

/// A simulated frame and its reconstruction.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Side, super-pixels (the raw frame is `2·side` wide and high).
    pub side: usize,
    /// The target square's side, super-pixels.
    pub target_side: usize,
    /// Raw counts, `(2·side)²` values row-major (the mean over the frames averaged).
    pub raw_counts: Vec<f64>,
    /// Raw pixels that saturated (full well or ADC top) in at least one frame, row-major.
    pub raw_saturated: Vec<bool>,
    /// `Ŝ0` per super-pixel, electrons, `side²` values row-major (NaN where saturated).
    pub s0: Vec<f64>,
    /// `Ŝ1` per super-pixel, electrons.
    pub s1: Vec<f64>,
    /// `Ŝ2` per super-pixel, electrons.
    pub s2: Vec<f64>,
    /// Estimated DoLP per super-pixel.
    pub dolp: Vec<f64>,
    /// Estimated AoLP per super-pixel, degrees in (−90°, 90°], from s toward p in the beam's
    /// psps basis (`W₃⁺` undoes the camera roll, detection.md §2).
    pub aolp_deg: Vec<f64>,
    /// Measured statistics on the target.
    pub target: RegionStats,
    /// Measured statistics on the background.
    pub background: RegionStats,
}

impl Frame {
    /// Number of raw pixels that saturated.
    pub fn saturated_pixels(&self) -> usize {
        self.raw_saturated.iter().filter(|&&s| s).count()
    }

    /// Whether super-pixel `(row, col)` lies on the target.
    pub fn on_target(&self, row: usize, col: usize) -> bool {
        on_target(self.side, self.target_side, row, col)
    }
}

fn on_target(side: usize, target_side: usize, row: usize, col: usize) -> bool {
    let lo = (side - target_side) / 2;
    (lo..lo + target_side).contains(&row) && (lo..lo + target_side).contains(&col)
}

fn invalid(name: &'static str, value: f64, reason: &'static str) -> Error {
    Error::InvalidParameter {
        name,
        value,
        reason,
    }
}

/// The channel of each layout position, `[row][column]`, from the channels' angles.
fn layout_channels(angles_deg: &[f64; 4]) -> Result<[[usize; 2]; 2]> {
    let mut out = [[usize::MAX; 2]; 2];
    for (k, &a) in angles_deg.iter().enumerate() {
        let reason = "a DoFP frame needs one analyzer at each of 0°, 45°, 90° and 135°";
        let bad = || Error::InvalidParameterAt {
            name: "analyzer_angle_deg",
            value: a,
            index: k,
            reason,
        };
        let wrapped = a.rem_euclid(180.0);
        let (r, c) = [(0, 0), (0, 1), (1, 0), (1, 1)]
            .into_iter()
            .find(|&(r, c)| {
                let d = (wrapped - LAYOUT_DEG[r][c]).abs();
                d.min(180.0 - d) < 1e-9
            })
            .ok_or_else(bad)?;
        if out[r][c] != usize::MAX {
            return Err(bad());
        }
        out[r][c] = k;
    }
    Ok(out)
}

fn check(spec: &FrameSpec) -> Result<()> {
    let r = &spec.readout;
    if spec.side == 0 || spec.side > MAX_SIDE {
        return Err(invalid(
            "side",
            spec.side as f64,
            "the frame side must be 1 to 1024 super-pixels",
        ));
    }
    if spec.target_side > spec.side {
        return Err(invalid(
            "target_side",
            spec.target_side as f64,
            "the target must fit in the frame",
        ));
    }
    let draws = 4 * (spec.side as u64).pow(2) * u64::from(r.frames);
    if r.frames == 0 || draws > MAX_DRAWS {
        return Err(invalid(
            "frames",
            f64::from(r.frames),
            "frames averaged must be ≥ 1, and raw pixels × frames at most 2^28",
        ));
    }
    let nonneg = [("dark_e", r.dark_e), ("read_noise_e", r.read_noise_e)];
    for (name, v) in nonneg {
        if !(v.is_finite() && v >= 0.0) {
            return Err(invalid(name, v, "must be finite and ≥ 0"));
        }
    }
    let positive = [
        ("gain_e_per_count", r.gain_e_per_count),
        ("full_well_e", r.full_well_e),
    ];
    for (name, v) in positive {
        if !(v.is_finite() && v > 0.0) {
            return Err(invalid(name, v, "must be finite and > 0"));
        }
    }
    if !(1..=32).contains(&r.adc_bits) {
        return Err(invalid(
            "adc_bits",
            f64::from(r.adc_bits),
            "must be 1 to 32",
        ));
    }
    for (name, e) in [
        ("target_e", spec.target_e),
        ("background_e", spec.background_e),
    ] {
        for (k, &v) in e.iter().enumerate() {
            // The Poisson sampler's limit is far above any full well; the mean must stay
            // below it so that every draw is defined.
            if !(v.is_finite() && v >= 0.0 && v + r.dark_e < Poisson::<f64>::MAX_LAMBDA) {
                return Err(Error::InvalidParameterAt {
                    name,
                    value: v,
                    index: k,
                    reason: "mean electrons must be finite, ≥ 0 and below 1.8e19",
                });
            }
        }
    }
    if spec.reconstruction.iter().flatten().any(|v| !v.is_finite()) {
        return Err(invalid(
            "reconstruction",
            f64::NAN,
            "the reconstruction matrix must be finite",
        ));
    }
    Ok(())
}

/// Draws one raw pixel: the mean counts over the frames and whether any frame saturated.
struct PixelSampler {
    poisson: Option<Poisson<f64>>,
    readout: Readout,
    top: f64,
}

impl PixelSampler {
    fn new(mean_e: f64, readout: Readout) -> Self {
        Self {
            // Poisson(0) is 0 (rand_distr refuses λ = 0).
            poisson: Poisson::new(mean_e).ok(),
            readout,
            top: 2f64.powi(readout.adc_bits as i32) - 1.0,
        }
    }

    fn draw(&self, rng: &mut SplitMix64) -> (f64, bool) {
        let r = &self.readout;
        let (mut sum, mut saturated) = (0.0, false);
        for _ in 0..r.frames {
            let mut e = self.poisson.as_ref().map_or(0.0, |p| p.sample(rng));
            if e > r.full_well_e {
                e = r.full_well_e;
                saturated = true;
            }
            let v = e + r.read_noise_e * rng.normal();
            let counts = (v / r.gain_e_per_count).round().max(0.0);
            if counts >= self.top {
                saturated = true;
            }
            sum += counts.min(self.top);
        }
        (sum / f64::from(r.frames), saturated)
    }
}

/// Simulates the raw frame of `spec` and reconstructs its Stokes images.
///
/// # Errors
/// [`Error::InvalidParameter`] naming the quantity for a frame side out of 1 to [`MAX_SIDE`],
/// a target larger than the frame, too many draws ([`MAX_DRAWS`]), a negative or non-finite
/// readout value, ADC bits outside 1 to 32, a non-finite reconstruction matrix;
/// [`Error::InvalidParameterAt`] for analyzers that are not the DoFP four or a negative or
/// non-finite mean.
pub fn simulate(spec: &FrameSpec) -> Result<Frame> {
    check(spec)?;
    let channel = layout_channels(&spec.angles_deg)?;
    let (side, raw_side) = (spec.side, 2 * spec.side);
    let dark = spec.readout.dark_e;
    let sampler = |e: &[f64; 4]| -> [PixelSampler; 4] {
        std::array::from_fn(|k| PixelSampler::new(e[k] + dark, spec.readout))
    };
    let (on, off) = (sampler(&spec.target_e), sampler(&spec.background_e));
    let mut rng = SplitMix64::new(spec.seed);
    let mut raw_counts = vec![0.0; raw_side * raw_side];
    let mut raw_saturated = vec![false; raw_side * raw_side];
    for y in 0..raw_side {
        for x in 0..raw_side {
            let k = channel[y % 2][x % 2];
            let s = if on_target(side, spec.target_side, y / 2, x / 2) {
                &on[k]
            } else {
                &off[k]
            };
            let (c, sat) = s.draw(&mut rng);
            raw_counts[y * raw_side + x] = c;
            raw_saturated[y * raw_side + x] = sat;
        }
    }
    Ok(reconstruct(spec, &channel, raw_counts, raw_saturated))
}

/// Stokes per super-pixel from the raw counts, and the regions' statistics.
fn reconstruct(
    spec: &FrameSpec,
    channel: &[[usize; 2]; 2],
    raw_counts: Vec<f64>,
    raw_saturated: Vec<bool>,
) -> Frame {
    let (side, raw_side) = (spec.side, 2 * spec.side);
    let (g, dark) = (spec.readout.gain_e_per_count, spec.readout.dark_e);
    let n = side * side;
    let (mut s0, mut s1, mut s2) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut dolp, mut aolp_deg) = (vec![0.0; n], vec![0.0; n]);
    for row in 0..side {
        for col in 0..side {
            let mut intensity = [0.0; 4];
            let mut saturated = false;
            for (r, c) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                let at = (2 * row + r) * raw_side + 2 * col + c;
                intensity[channel[r][c]] = g * raw_counts[at] - dark;
                saturated |= raw_saturated[at];
            }
            let mut s = [0.0; 3];
            for (c, i) in spec.reconstruction.iter().zip(&intensity) {
                for (s, c) in s.iter_mut().zip(c) {
                    *s += c * i;
                }
            }
            let i = row * side + col;
            if saturated {
                (s0[i], s1[i], s2[i], dolp[i], aolp_deg[i]) =
                    (f64::NAN, f64::NAN, f64::NAN, f64::NAN, f64::NAN);
            } else {
                let stokes = Stokes::new(s[0], s[1], s[2], 0.0);
                (s0[i], s1[i], s2[i]) = (s[0], s[1], s[2]);
                dolp[i] = stokes.dolp();
                aolp_deg[i] = stokes.aolp().to_degrees();
            }
        }
    }
    let region = |target: bool| {
        let keep = |i: usize| on_target(side, spec.target_side, i / side, i % side) == target;
        RegionStats {
            s0: SampleMoments::of(&s0, keep),
            s1: SampleMoments::of(&s1, keep),
            s2: SampleMoments::of(&s2, keep),
            dolp: SampleMoments::of(&dolp, keep),
        }
    };
    let (target, background) = (region(true), region(false));
    Frame {
        side,
        target_side: spec.target_side,
        raw_counts,
        raw_saturated,
        s0,
        s1,
        s2,
        dolp,
        aolp_deg,
        target,
        background,
    }
}
