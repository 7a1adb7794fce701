//! The simulated camera frame of a detection (`polbrdf detect --frame`, Python
//! `polbrdf.detect_frame`; detection.md §6, docs/detection-frame.md): what a photon-counting DoFP
//! camera sees of the target on its background at one view and range — the raw frame and the
//! reconstructed S0, DoLP and AoLP images — with the `.npy` files both adapters write (so the
//! CLI's files and Python's arrays are the same bytes).

use crate::detect::DetectStudy;
use crate::error::{TaskError, TaskResult};
use polbrdf::analysis::detection::frame::{simulate, Frame, FrameSpec, MAX_SIDE};
use polbrdf::analysis::detection::statistics::pixels_on_target;
use polbrdf::analysis::detection::{Detection, Detector};
use polbrdf::analysis::detection::{Layout, NoiseSpec};
use polbrdf::Stokes;

/// The smallest frame side, super-pixels: room for background statistics around a small target.
pub const MIN_SIDE: usize = 64;

/// What to simulate.
#[derive(Debug, Clone)]
pub struct FrameRequest {
    /// The sensor, path, target area and criteria (a photon-counting DoFP camera).
    pub detector: Detector,
    /// The Stokes radiance leaving the target toward the view (before the path).
    pub target: Stokes,
    /// The Stokes radiance leaving the background toward the view.
    pub background: Stokes,
    /// The view's zenith angle θr (degrees, in [0, 90)).
    pub theta_r_deg: f64,
    /// The range (m, > 0).
    pub range_m: f64,
    /// The camera's ADC bits (1 to 32).
    pub adc_bits: u32,
    /// The frame side in super-pixels; `None`: twice the target's, at least [`MIN_SIDE`], at
    /// most [`MAX_SIDE`].
    pub side: Option<usize>,
    /// The seed of the random stream.
    pub seed: u64,
}

/// A simulated frame with the detection it illustrates.
#[derive(Debug, Clone)]
pub struct FrameOutput {
    /// The frame and its reconstruction (its measured target and background statistics).
    pub frame: Frame,
    /// Stokes pixels on target at this range (§5, a real number); the target square's side is
    /// its square root rounded to the nearest whole super-pixel.
    pub pixels_on_target: f64,
    /// The analytic detection at this view and range (§1–5), to compare with the frame.
    pub detection: Detection,
}

/// The target square's side for `pixels` Stokes pixels, and the frame's side.
pub fn frame_sides(pixels: f64, side: Option<usize>) -> (usize, usize) {
    let n = pixels.max(0.0).sqrt().round().min(MAX_SIDE as f64) as usize;
    let side = side.unwrap_or_else(|| (2 * n).clamp(MIN_SIDE, MAX_SIDE));
    (n.min(side), side)
}

/// Simulates the frame of `req`.
///
/// # Errors
/// [`TaskError::Invalid`] naming `theta_r_deg`, `range_m`, `adc_bits` or `side`; the core's
/// refusals ([`FrameSpec::for_sensor`]: a NEL sensor, not four channels; the path beyond its
/// table) as [`TaskError::Model`].
pub fn run(req: &FrameRequest) -> TaskResult<FrameOutput> {
    if !(req.theta_r_deg.is_finite() && (0.0..90.0).contains(&req.theta_r_deg)) {
        return Err(TaskError::invalid(
            "theta_r_deg",
            "must lie in [0, 90) degrees",
        ));
    }
    if !(req.range_m.is_finite() && req.range_m > 0.0) {
        return Err(TaskError::invalid("range_m", "must be finite and > 0 m"));
    }
    if !(1..=32).contains(&req.adc_bits) {
        return Err(TaskError::invalid("adc_bits", "must be 1 to 32"));
    }
    if req.side.is_some_and(|s| !(1..=MAX_SIDE).contains(&s)) {
        return Err(TaskError::invalid(
            "side",
            format!("the frame side must be 1 to {MAX_SIDE} super-pixels"),
        ));
    }
    let d = &req.detector;
    let theta = req.theta_r_deg.to_radians();
    let detection = d.detect(&req.target, &req.background, theta, req.range_m)?;
    let pixels = pixels_on_target(d.area_m2, theta, req.range_m, d.sensor.ifov_rad);
    let (target_side, side) = frame_sides(pixels, req.side);
    let t = d.path.apply(&req.target, req.range_m)?;
    let b = d.path.apply(&req.background, req.range_m)?;
    let spec = FrameSpec::for_sensor(
        &d.sensor,
        &t,
        &b,
        req.adc_bits,
        (side, target_side),
        req.seed,
    )?;
    Ok(FrameOutput {
        frame: simulate(&spec)?,
        pixels_on_target: pixels,
        detection,
    })
}

/// The frame of a detection study (`polbrdf detect --frame`): at its best-ranked view (by
/// detection range; the first view without a range search) and its first range, with the sensor
/// file's ADC.
///
/// # Errors
/// [`TaskError::Invalid`] naming `frame` for a sensor that is not a photon-counting DoFP
/// camera; as [`run`].
pub fn of_study(study: &DetectStudy, side: Option<usize>, seed: u64) -> TaskResult<FrameOutput> {
    let spec = &study.sensor.spec;
    let NoiseSpec::PhotonCounting { adc_bits, .. } = spec.noise else {
        return Err(TaskError::invalid(
            "frame",
            "a simulated frame needs a photon-counting camera; the sensor gives a NEL or NETD \
             (thermal), which has no electrons to draw",
        ));
    };
    if spec.layout != Layout::Dofp {
        return Err(TaskError::invalid(
            "frame",
            "a simulated frame needs a division-of-focal-plane sensor (layout = \"dofp\")",
        ));
    }
    let view = study.ranked()[0];
    run(&FrameRequest {
        detector: study.detector.clone(),
        target: view.target,
        background: view.background,
        theta_r_deg: view.theta_r.to_degrees(),
        range_m: study.ranges_m[0],
        adc_bits,
        side,
        seed,
    })
}

/// The frame's arrays as `.npy` files, in this order: `frame_raw_counts.npy` (`2·side × 2·side`
/// float64 counts), `frame_saturated.npy` (bool, same shape), `frame_s0.npy` (electrons),
/// `frame_dolp.npy`, `frame_aolp_deg.npy` (`side × side` float64).
///
/// # Errors
/// None in practice (the shapes match by construction); an encoding error as
/// [`TaskError::Invalid`].
pub fn npy_files(frame: &Frame) -> TaskResult<Vec<(String, Vec<u8>)>> {
    use polbrdf_io::npy::{array_bool, array_f64};
    let (raw, side) = ([2 * frame.side, 2 * frame.side], [frame.side, frame.side]);
    let err = |e: std::io::Error| TaskError::invalid("frame", e.to_string());
    Ok(vec![
        (
            "frame_raw_counts.npy".into(),
            array_f64(&raw, &frame.raw_counts).map_err(err)?,
        ),
        (
            "frame_saturated.npy".into(),
            array_bool(&raw, &frame.raw_saturated).map_err(err)?,
        ),
        (
            "frame_s0.npy".into(),
            array_f64(&side, &frame.s0).map_err(err)?,
        ),
        (
            "frame_dolp.npy".into(),
            array_f64(&side, &frame.dolp).map_err(err)?,
        ),
        (
            "frame_aolp_deg.npy".into(),
            array_f64(&side, &frame.aolp_deg).map_err(err)?,
        ),
    ])
}
