//! Tests of the bridges: each convention checked by an independent construction (the electric
//! field as a 3-D vector and Malus's law, the model's isotropy), not by re-deriving the formula.
use super::*;
use crate::MaterialSpec;

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = dot(v, v).sqrt();
    v.map(|x| x / n)
}

fn add(a: [f64; 3], b: [f64; 3], ca: f64, cb: f64) -> [f64; 3] {
    std::array::from_fn(|i| ca * a[i] + cb * b[i])
}

fn geometries() -> Vec<Geometry> {
    let mut out = Vec::new();
    for &(ti, pi, tr, pr) in &[
        (30.0, 0.0, 30.0, 180.0),
        (55.0, 20.0, 40.0, -100.0),
        (10.0, -150.0, 75.0, 60.0),
        (80.0, 90.0, 5.0, 300.0),
        (45.0, 33.0, 0.0, 10.0),
    ] {
        out.push(Geometry::from_degrees(ti, pi, tr, pr).unwrap());
    }
    out
}

/// Malus's law on the 3-D field: the Stokes vector a pipeline computes from four polarizer
/// pixels at 0°, 45°, 90°, 135° measured from `x` toward `y` (`S1 = I0 − I90`,
/// `S2 = I45 − I135`), for a fully linearly polarized beam with field direction `e`.
fn measured(e: [f64; 3], x: [f64; 3], y: [f64; 3]) -> [f64; 3] {
    let i = |deg: f64| {
        let (s, c) = deg.to_radians().sin_cos();
        dot(e, add(x, y, c, s)).powi(2)
    };
    [i(0.0) + i(90.0), i(0.0) - i(90.0), i(45.0) - i(135.0)]
}

#[test]
fn a_level_camera_has_no_roll_and_its_x_axis_is_s_out() {
    for g in geometries().into_iter().filter(|g| g.theta_r() > 0.0) {
        let roll = camera_roll(&g, [0.0, 0.0, 1.0]).unwrap();
        assert!(roll.abs() < 1e-12, "{roll}");
        // Image right of a level camera looking along −w_r: forward × world up.
        let [s, p, k] = reflected_frame(&g);
        let right = unit(cross([-k[0], -k[1], -k[2]], [0.0, 0.0, 1.0]));
        assert!((dot(right, s) - 1.0).abs() < 1e-12);
        assert!(p[2] > 0.0, "p_out is image up");
    }
}

#[test]
fn camera_stokes_follow_malus_law_for_any_roll_and_image_axes() {
    for g in geometries() {
        let [s, p, k] = reflected_frame(&g);
        for roll_deg in [0.0_f64, 17.0, -65.0, 120.0] {
            // The camera's own axes, turned by the roll from (s, p) about k.
            let (sr, cr) = roll_deg.to_radians().sin_cos();
            let x = add(s, p, cr, sr);
            let up = add(s, p, -sr, cr);
            let roll = camera_roll(&g, add(up, k, 1.0, 0.3)).unwrap();
            assert!((roll - roll_deg.to_radians()).abs() < 1e-12, "{roll}");
            for psi_deg in [-73.15_f64, 0.0, 12.0, 89.0] {
                let psi = psi_deg.to_radians();
                let e = add(s, p, psi.cos(), psi.sin());
                let sto = Stokes::linear(psi);
                for (y, yaxis) in [(ImageY::Up, up), (ImageY::Down, up.map(|v| -v))] {
                    let want = measured(e, x, yaxis);
                    let got = stokes_to_polanalyser(&sto, roll, y);
                    for c in 0..3 {
                        assert!((got[c] - want[c]).abs() < 1e-12, "{got:?} {want:?}");
                    }
                    let aolp = aolp_to_polanalyser(psi, roll, y);
                    assert!((0.0..PI).contains(&aolp));
                    assert!((aolp - polanalyser_aolp(&got)).abs() < 1e-12);
                }
            }
        }
    }
}

#[test]
fn the_issue_example_is_the_range_alone_for_a_level_camera() {
    // The same Stokes vector: −73.15° here, 106.85° in polanalyser (camera angles growing
    // toward image up); 73.15° if the camera's angles grow toward image down (y down).
    let psi = (-73.15_f64).to_radians();
    let up = aolp_to_polanalyser(psi, 0.0, ImageY::Up).to_degrees();
    assert!((up - 106.85).abs() < 1e-9, "{up}");
    let down = aolp_to_polanalyser(psi, 0.0, ImageY::Down).to_degrees();
    assert!((down - 73.15).abs() < 1e-9, "{down}");
    // A camera rolled by +30° sees the same field 30° less far from its x axis.
    let rolled = aolp_to_polanalyser(psi, 30_f64.to_radians(), ImageY::Up).to_degrees();
    assert!((rolled - 76.85).abs() < 1e-9, "{rolled}");
    // S0 and S3 are the same in the camera frame; the inverse returns the vector.
    let sto = Stokes::new(1.0, 0.3, -0.5, 0.2);
    let c = stokes_to_camera(&sto, 0.7);
    assert_eq!((c[0], c[3]), (sto[0], sto[3]));
    let back = stokes_from_camera(&c, 0.7);
    assert!((0..4).all(|i| (back[i] - sto[i]).abs() < 1e-15));
}

#[test]
fn a_camera_up_along_the_beam_is_refused() {
    let g = Geometry::from_degrees(30.0, 0.0, 0.0, 0.0).unwrap();
    let e = camera_roll(&g, [0.0, 0.0, 2.0]).unwrap_err();
    assert!(e.to_string().contains("up"), "{e}");
    assert!(camera_roll(&g, [f64::NAN, 0.0, 1.0]).is_err());
}

#[test]
fn scatmech_angles_put_specular_at_phi_s_zero_and_round_trip() {
    let g = Geometry::from_degrees(40.0, 75.0, 40.0, 255.0).unwrap();
    let a = to_scatmech(&g);
    assert!(a.phi_s.abs() < 1e-12 && (a.theta_s - a.theta_i).abs() < 1e-15);
    let back = Geometry::from_degrees(40.0, 75.0, 40.0, 75.0).unwrap();
    assert!(
        (to_scatmech(&back).phi_s - PI).abs() < 1e-12,
        "backscatter at φs = 180°"
    );
    let spec = MaterialSpec::new(1.6, 20.0).build().unwrap();
    for g in geometries() {
        let a = to_scatmech(&g);
        assert!(a.phi_s > -PI && a.phi_s <= PI);
        let h = from_scatmech(a.theta_i, a.theta_s, a.phi_s).unwrap();
        assert!((h.phi_i() - PI).abs() < 1e-15);
        let b = to_scatmech(&h);
        assert!((b.phi_s - a.phi_s).abs() < 1e-12);
        // The model is isotropic: SCATMECH's azimuths give the same pBRDF.
        let (f, fh) = (spec.pbrdf(&g), spec.pbrdf(&h));
        for i in 0..4 {
            for j in 0..4 {
                assert!((f[(i, j)] - fh[(i, j)]).abs() < 1e-12 * f.m00().max(1e-300));
            }
        }
    }
    assert!(from_scatmech(f64::NAN, 0.0, 0.0).is_err());
}

#[test]
fn mitsuba_basis_is_an_orthonormal_axis_across_the_beam() {
    for k in [
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        unit([0.3, -0.4, 0.5]),
        unit([-0.2, 0.9, -0.1]),
    ] {
        let x = mitsuba_stokes_basis(k);
        assert!(dot(x, k).abs() < 1e-15 && (dot(x, x) - 1.0).abs() < 1e-15);
    }
    // Up the z axis Mitsuba's x axis is the world x axis.
    assert_eq!(mitsuba_stokes_basis([0.0, 0.0, 1.0]), [1.0, 0.0, 0.0]);
}

#[test]
fn mitsuba_frames_turn_the_field_as_the_3d_vectors_say() {
    let spec = MaterialSpec::new(1.6, 20.0);
    let mut spec = spec;
    spec.k = 0.4;
    let m = spec.build().unwrap();
    for g in geometries() {
        let [s, p, k] = reflected_frame(&g);
        let x = mitsuba_stokes_basis(k);
        let y = cross(k, x);
        for psi in [-1.2, 0.0, 0.4, 1.5] {
            let e = add(s, p, f64::cos(psi), f64::sin(psi));
            let got = stokes_to_mitsuba(&Stokes::linear(psi), &g);
            let want = dot(e, y).atan2(dot(e, x));
            let d = (got.aolp() - want).rem_euclid(PI);
            assert!(d.min(PI - d) < 1e-12, "{} vs {want}", got.aolp());
        }
        // Circular light: Mitsuba's S3 is minus psps's.
        let c = stokes_to_mitsuba(&Stokes::new(1.0, 0.0, 0.0, 1.0), &g);
        assert!((c[3] + 1.0).abs() < 1e-15);
        // The matrix: round trip, and the DoLP of unpolarized light is frame-free.
        let f = m.pbrdf(&g);
        let t = mueller_to_mitsuba(&f, &g);
        let back = mueller_from_mitsuba(&t, &g);
        for i in 0..4 {
            for j in 0..4 {
                assert!((back[(i, j)] - f[(i, j)]).abs() < 1e-13 * f.m00());
            }
        }
        let dolp = |a: &Mueller| a[(1, 0)].hypot(a[(2, 0)]) / a.m00();
        assert!((dolp(&t) - dolp(&f)).abs() < 1e-13);
        // Mitsuba's Stokes vector out equals its matrix applied to its Stokes vector in.
        let s_in = Stokes::linear(0.3);
        let in_mitsuba = {
            let [si, _, ki] = incident_frame(&g);
            let a = frame_angle(ki, si, mitsuba_stokes_basis(ki));
            MITSUBA_S3 * (Mueller::rotator(-a) * s_in)
        };
        let via_mitsuba = t * in_mitsuba;
        let direct = stokes_to_mitsuba(&(f * s_in), &g);
        for i in 0..4 {
            assert!((via_mitsuba[i] - direct[i]).abs() < 1e-13 * f.m00());
        }
    }
}
