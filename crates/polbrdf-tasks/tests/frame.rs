//! The simulated camera frame job: the target's size from §5's pixels on target, the frame
//! matching the detection it illustrates, the `.npy` files, the request's validation.

use polbrdf::analysis::detection::noise::photons_per_joule;
use polbrdf::analysis::detection::{
    Analyzer, Criteria, Detector, NoiseModel, Path, PhotonCounting, Sensor,
};
use polbrdf::Stokes;
use polbrdf_tasks::frame::{frame_sides, npy_files, run, FrameRequest, MIN_SIDE};
use polbrdf_tasks::TaskError;

fn detector(noise: NoiseModel) -> Detector {
    let sensor = Sensor {
        analyzer: Analyzer::ideal_dofp(),
        noise,
        frames: 1,
        ifov_rad: 2.0 * 3.45e-6 / 0.05,
    };
    let path = Path::from_visibility(20_000.0, 1.0).unwrap();
    Detector::new(sensor, path, 4.0, Criteria::default()).unwrap()
}

fn camera() -> NoiseModel {
    NoiseModel::PhotonCounting(PhotonCounting {
        integration_time_s: 0.002,
        pixel_pitch_m: 3.45e-6,
        f_number: 2.8,
        optics_transmittance: 0.9,
        photons_per_joule: photons_per_joule(0.55),
        dark_current_e_per_s: 3.0,
        read_noise_e: 2.3,
        gain_e_per_count: 10_500.0 / 4096.0,
        full_well_e: 10_500.0,
    })
}

fn request(range_m: f64) -> FrameRequest {
    FrameRequest {
        detector: detector(camera()),
        target: Stokes::new(1.0, 0.2, 0.08, 0.0),
        background: Stokes::new(1.2, 0.02, 0.0, 0.0),
        theta_r_deg: 40.0,
        range_m,
        adc_bits: 12,
        side: None,
        seed: 5,
    }
}

#[test]
fn the_target_square_has_the_pixels_on_target_of_the_detection() {
    assert_eq!(frame_sides(0.2, None), (0, MIN_SIDE));
    assert_eq!(frame_sides(100.0, None), (10, MIN_SIDE));
    assert_eq!(frame_sides(2500.0, None), (50, 100));
    assert_eq!(frame_sides(1e12, None), (1024, 1024));
    assert_eq!(frame_sides(2500.0, Some(30)), (30, 30));

    let out = run(&request(500.0)).unwrap();
    let f = &out.frame;
    assert_eq!(f.saturated_pixels(), 0);
    let n = out.pixels_on_target.sqrt().round() as usize;
    assert!(n > 5, "{}", out.pixels_on_target);
    assert_eq!(f.target_side, n);
    assert_eq!(f.target.s0.n, n * n);
    // The frame measures what the detection predicts: the target's mean S0 at the sensor
    // (after the path) within 5 standard errors.
    let want = out.detection.target.stokes[0];
    let se = (out.detection.target.covariance[0][0] / (n * n) as f64).sqrt();
    assert!(
        (f.target.s0.mean - want).abs() < 5.0 * se,
        "{} vs {want}",
        f.target.s0.mean
    );
    let want_b = out.detection.background.stokes[0];
    let se_b = (out.detection.background.covariance[0][0] / f.background.s0.n as f64).sqrt();
    assert!((f.background.s0.mean - want_b).abs() < 5.0 * se_b);
    // Farther away, the target covers fewer pixels.
    let far = run(&request(2000.0)).unwrap();
    assert!(far.frame.target_side < f.target_side);
}

#[test]
fn npy_files_hold_the_frames_arrays_bit_for_bit() {
    let out = run(&request(800.0)).unwrap();
    let f = &out.frame;
    let files = npy_files(f).unwrap();
    let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        [
            "frame_raw_counts.npy",
            "frame_saturated.npy",
            "frame_s0.npy",
            "frame_dolp.npy",
            "frame_aolp_deg.npy"
        ]
    );
    let tail = |bytes: &[u8], n: usize| bytes[bytes.len() - n..].to_vec();
    let le = |v: &[f64]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    assert_eq!(tail(&files[0].1, 8 * f.raw_counts.len()), le(&f.raw_counts));
    assert_eq!(tail(&files[4].1, 8 * f.aolp_deg.len()), le(&f.aolp_deg));
    let raw = 2 * f.side;
    assert!(String::from_utf8_lossy(&files[1].1).contains(&format!(
        "'descr': '|b1', 'fortran_order': False, 'shape': ({raw}, {raw})"
    )));
    // Seeded: the same request gives the same bytes.
    assert_eq!(
        files,
        npy_files(&run(&request(800.0)).unwrap().frame).unwrap()
    );
}

/// A change to a request.
type Change = fn(&mut FrameRequest);

#[test]
fn bad_requests_name_their_field() {
    let cases: [(&str, Change); 6] = [
        ("theta_r_deg", |r| r.theta_r_deg = 90.0),
        ("range_m", |r| r.range_m = 0.0),
        ("range_m", |r| r.range_m = f64::NAN),
        ("adc_bits", |r| r.adc_bits = 0),
        ("side", |r| r.side = Some(0)),
        ("side", |r| r.side = Some(1025)),
    ];
    for (field, change) in cases {
        let mut r = request(500.0);
        change(&mut r);
        match run(&r) {
            Err(TaskError::Invalid { field: f, .. }) => assert_eq!(f, field),
            other => panic!("{field}: {other:?}"),
        }
    }
    // A thermal (NEL) sensor has no electrons to draw.
    let mut r = request(500.0);
    r.detector = detector(NoiseModel::Nel { nel: 0.01 });
    let e = run(&r).unwrap_err().to_string();
    assert!(e.contains("needs a photon-counting camera"), "{e}");
}
