//! The simulated DoFP frame (detection.md §6) and the Rician DoLP bias: layout, saturation,
//! reproducibility, refusals; the Rice mean against quadrature.

use polbrdf::analysis::detection::dolp_bias::{expected_dolp, rice_mean};
use polbrdf::analysis::detection::frame::{simulate, FrameSpec, Readout, LAYOUT_DEG};
use polbrdf::Error;

/// §4's reconstruction of the ideal four-angle camera, channels in the order 0°, 45°, 90°, 135°:
/// `S0 = (I0 + I45 + I90 + I135)/2`, `S1 = I0 − I90`, `S2 = I45 − I135`.
/// By columns, one per channel.
const IDEAL: [[f64; 3]; 4] = [
    [0.5, 1.0, 0.0],
    [0.5, 0.0, 1.0],
    [0.5, -1.0, 0.0],
    [0.5, 0.0, -1.0],
];

fn readout() -> Readout {
    Readout {
        dark_e: 0.0,
        read_noise_e: 0.0,
        gain_e_per_count: 1.0,
        adc_bits: 16,
        full_well_e: 60_000.0,
        frames: 1,
    }
}

fn spec(target_e: [f64; 4], background_e: [f64; 4]) -> FrameSpec {
    FrameSpec {
        side: 16,
        target_side: 6,
        angles_deg: [0.0, 45.0, 90.0, 135.0],
        target_e,
        background_e,
        reconstruction: IDEAL,
        readout: readout(),
        seed: 7,
    }
}

#[test]
fn each_raw_pixel_carries_its_analyzer_of_the_layout() {
    // Only one channel has light, no read noise, no dark: every other raw pixel reads 0 counts.
    for (k, angle) in [0.0, 45.0, 90.0, 135.0].into_iter().enumerate() {
        let mut e = [0.0; 4];
        e[k] = 500.0;
        let f = simulate(&spec(e, e)).unwrap();
        let w = 2 * f.side;
        for y in 0..w {
            for x in 0..w {
                let lit = LAYOUT_DEG[y % 2][x % 2] == angle;
                let c = f.raw_counts[y * w + x];
                assert_eq!(c > 0.0, lit, "angle {angle}: pixel ({y}, {x}) = {c}");
            }
        }
    }
}

#[test]
fn stokes_per_super_pixel_is_the_reconstruction_of_its_four_counts() {
    let f = simulate(&spec([900.0, 500.0, 100.0, 500.0], [400.0; 4])).unwrap();
    let w = 2 * f.side;
    for row in 0..f.side {
        for col in 0..f.side {
            let at = |r: usize, c: usize| f.raw_counts[(2 * row + r) * w + 2 * col + c];
            let (i90, i45, i135, i0) = (at(0, 0), at(0, 1), at(1, 0), at(1, 1));
            let i = row * f.side + col;
            assert_eq!(f.s0[i], 0.5 * (i0 + i45 + i90 + i135));
            assert_eq!(f.s1[i], i0 - i90);
            assert_eq!(f.s2[i], i45 - i135);
            let dolp = (f.s1[i].hypot(f.s2[i])) / f.s0[i];
            assert!((f.dolp[i] - dolp).abs() <= 1e-15 * dolp.max(1.0));
            let aolp = 0.5 * f.s2[i].atan2(f.s1[i]).to_degrees();
            assert!((f.aolp_deg[i] - aolp).abs() < 1e-12);
        }
    }
    // The target (S1 = 800 electrons) stands out in S1; the background is unpolarized.
    assert!((f.target.s1.mean - 800.0).abs() < 5.0 * (1000.0 / 36.0f64).sqrt());
    assert_eq!(f.target.s0.n, 36);
    assert_eq!(f.background.s0.n, 16 * 16 - 36);
}

#[test]
fn same_seed_same_frame_other_seed_other_frame() {
    let mut s = spec([900.0, 500.0, 100.0, 500.0], [400.0; 4]);
    s.readout.read_noise_e = 3.0;
    s.readout.dark_e = 20.0;
    s.readout.gain_e_per_count = 2.5;
    let a = simulate(&s).unwrap();
    assert_eq!(a, simulate(&s).unwrap());
    s.seed = 8;
    assert_ne!(a.raw_counts, simulate(&s).unwrap().raw_counts);
}

#[test]
fn saturation_is_flagged_counted_and_leaves_no_estimate() {
    // Target 90° channel far above the full well; background well below it.
    let mut s = spec([1000.0, 1000.0, 90_000.0, 1000.0], [1000.0; 4]);
    s.side = 8;
    s.target_side = 2;
    let f = simulate(&s).unwrap();
    assert_eq!(
        f.saturated_pixels(),
        4,
        "one 90° pixel per target super-pixel"
    );
    for row in 0..8 {
        for col in 0..8 {
            let i = row * 8 + col;
            assert_eq!(f.s0[i].is_nan(), f.on_target(row, col));
            assert_eq!(f.dolp[i].is_nan(), f.on_target(row, col));
        }
    }
    assert_eq!(f.target.s0.n, 0);
    assert!(f.target.s0.mean.is_nan());
    // The clipped pixels read the full well, not more.
    let w = 16;
    let top = f
        .raw_counts
        .iter()
        .zip(&f.raw_saturated)
        .filter(|(_, &s)| s)
        .map(|(&c, _)| c)
        .fold(0.0, f64::max);
    assert_eq!(top, 60_000.0);
    assert_eq!(f.raw_counts.len(), w * w);

    // An 8-bit ADC at 1 e⁻/count tops out at 255 counts: flagged too.
    let mut s = spec([400.0; 4], [100.0; 4]);
    s.readout.adc_bits = 8;
    let f = simulate(&s).unwrap();
    assert_eq!(f.saturated_pixels(), 4 * 36);
    assert!(f.raw_counts.iter().all(|&c| c <= 255.0));
}

/// A change to a frame's specification.
type Change = Box<dyn Fn(&mut FrameSpec)>;

#[test]
fn refusals_name_the_quantity() {
    let base = spec([100.0; 4], [100.0; 4]);
    let mut s = base.clone();
    s.angles_deg = [0.0, 45.0, 90.0, 90.0];
    match simulate(&s) {
        Err(Error::InvalidParameterAt { name, index, .. }) => {
            assert_eq!((name, index), ("analyzer_angle_deg", 3));
        }
        other => panic!("{other:?}"),
    }
    // Angles are taken mod 180°.
    s.angles_deg = [180.0, 45.0, -90.0, 135.0];
    assert!(simulate(&s).is_ok());
    let cases: Vec<(&str, Change)> = vec![
        ("side", Box::new(|s| s.side = 0)),
        ("side", Box::new(|s| s.side = 1025)),
        ("target_side", Box::new(|s| s.target_side = 17)),
        ("frames", Box::new(|s| s.readout.frames = 0)),
        ("frames", Box::new(|s| s.readout.frames = 300_000)),
        (
            "gain_e_per_count",
            Box::new(|s| s.readout.gain_e_per_count = 0.0),
        ),
        (
            "full_well_e",
            Box::new(|s| s.readout.full_well_e = f64::NAN),
        ),
        ("read_noise_e", Box::new(|s| s.readout.read_noise_e = -1.0)),
        ("dark_e", Box::new(|s| s.readout.dark_e = f64::INFINITY)),
        ("adc_bits", Box::new(|s| s.readout.adc_bits = 0)),
        ("adc_bits", Box::new(|s| s.readout.adc_bits = 33)),
        (
            "reconstruction",
            Box::new(|s| s.reconstruction[2][1] = f64::NAN),
        ),
    ];
    for (want, change) in cases {
        let mut s = base.clone();
        change(&mut s);
        match simulate(&s) {
            Err(Error::InvalidParameter { name, .. }) => assert_eq!(name, want),
            other => panic!("{want}: {other:?}"),
        }
    }
    let mut s = base;
    s.background_e[2] = -1.0;
    match simulate(&s) {
        Err(Error::InvalidParameterAt { name, index, .. }) => {
            assert_eq!((name, index), ("background_e", 2));
        }
        other => panic!("{other:?}"),
    }
}

/// `E|Z|` for a 2-D Gaussian of mean `(nu, 0)` and unit variance per component, by the
/// midpoint rule on a ±9σ square (an independent check of the Bessel-function closed form;
/// the cone of |z| at the origin limits it to about 1e-7).
fn rice_mean_by_quadrature(nu: f64) -> f64 {
    let (n, half) = (1200, 9.0);
    let h = 2.0 * half / f64::from(n);
    let mut sum = 0.0;
    for i in 0..n {
        let x = -half + (f64::from(i) + 0.5) * h;
        for j in 0..n {
            let y = -half + (f64::from(j) + 0.5) * h;
            let w = (-(x * x + y * y) / 2.0).exp();
            sum += (x + nu).hypot(y) * w;
        }
    }
    sum * h * h / (2.0 * std::f64::consts::PI)
}

#[test]
fn rice_mean_matches_quadrature_and_its_limits() {
    // ν = 0: the Rayleigh mean σ·√(π/2).
    assert!((rice_mean(0.0, 2.0) - 2.0 * (std::f64::consts::PI / 2.0).sqrt()).abs() < 1e-14);
    // Both branches of the Bessel functions (u = ν²/4σ² below and above 20) and the switch.
    for nu in [0.3, 1.0, 2.5, 5.0, 8.9, 8.95, 12.0] {
        let (closed, quad) = (rice_mean(nu, 1.0), rice_mean_by_quadrature(nu));
        assert!((closed - quad).abs() < 1e-6, "ν = {nu}: {closed} vs {quad}");
    }
    // Scale: E|Z| is homogeneous of degree 1 in (ν, σ).
    assert!((rice_mean(6.0, 3.0) - 3.0 * rice_mean(2.0, 1.0)).abs() < 1e-13);
    // Large ν/σ: E|Z| = ν + σ²/(2ν) + O(σ⁴/ν³).
    let nu = 200.0;
    assert!((rice_mean(nu, 1.0) - (nu + 0.5 / nu)).abs() < 1e-6);
    // The estimated DoLP is biased upward, by √(π/2)·σ/S0 at P = 0.
    let (s0, sigma) = (1000.0, 30.0);
    assert!((expected_dolp(0.0, s0, sigma) - 0.0376).abs() < 1e-4);
    for p in [0.0, 0.01, 0.05, 0.2, 0.9] {
        assert!(expected_dolp(p, s0, sigma) > p);
    }
}
