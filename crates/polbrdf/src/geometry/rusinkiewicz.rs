//! The Rusinkiewicz parametrization of Mitsuba 3's `measured_polarized` tables and the frame of
//! their Mueller matrices (docs/model.md §20).
//!
//! A table cell `(φ_d, θ_d, θ_h)` is an isotropic pair of directions: the half vector
//! `h = (sinθ_h, 0, cosθ_h)` (azimuth φ_h = 0; the model is isotropic), the Rusinkiewicz frame
//! `b = unit(z × h) = (0, 1, 0)`, `t = b × h = (cosθ_h, 0, −sinθ_h)`, the light direction
//! `w_i = cosθ_d·h + sinθ_d·(cosφ_d·t + sinφ_d·b)` and the view direction
//! `w_r = 2cosθ_d·h − w_i` (the mirror image of `w_i` about `h`).
//!
//! The table's Mueller matrices are expressed in the **plane-of-reflection frame**: for both
//! beams the Stokes reference axis is `unit(w_i × w_r)`, which is the facet's s axis `s_l` of
//! docs/model.md §4, and with Mitsuba's sign of S3, opposite to psps's (Mitsuba's Fresnel
//! amplitudes are the complex conjugates of polbrdf's: it takes `N = n − ik`). The psps pBRDF
//! `F` and the table matrix `T` are therefore related by the Priest–Meier angles of the
//! geometry and `P = diag(1, 1, 1, −1)`: `T = P·R(−η_r)·F·R(η_i)·P`,
//! `F = R(η_r)·P·T·P·R(−η_i)` with `R = Mueller::rotator` (P commutes with R).

use crate::error::Result;
use crate::geometry::angles::AngleVariables;
use crate::geometry::direction::Geometry;
use crate::optics::mueller::Mueller;

/// `|w_z|` below this is the horizon. A table's nodes are float32 (the plugin's type) and the
/// cells are evaluated at those values: two nodes whose in-plane sum `θ_h + θ_d` is 90° round
/// to a sum up to ~1.3e-7 rad off it (82° + 8° is 89.99999°, `w_z` ≈ 4e-8), where the standard
/// form's `1/(cosθi cosθr)` made the cell 1e8–1e9 sr⁻¹ and the plugin's interpolation spread
/// that over the neighbouring cells: the fireflies of issue 36. 1e-6 (0.2″) covers that rounding
/// with margin; a direction that close to the horizon is no measurement anyway.
pub const HORIZON_ROUNDING: f64 = 1e-6;

/// The geometry of the table cell `(φ_d, θ_d, θ_h)` (radians): light toward `w_i`, view toward
/// `w_r`, both from the construction in the module documentation. A direction below the horizon
/// (`θ_h + θ_d > 90°` in plane) gives a valid geometry whose pBRDF is zero (docs/model.md §1).
///
/// # Errors
/// [`crate::Error::InvalidAngle`] when an angle is not finite.
pub fn cell_geometry(phi_d: f64, theta_d: f64, theta_h: f64) -> Result<Geometry> {
    let (sh, ch) = theta_h.sin_cos();
    let (sd, cd) = theta_d.sin_cos();
    let (sp, cp) = phi_d.sin_cos();
    let h = [sh, 0.0, ch];
    let t = [ch, 0.0, -sh];
    let b = [0.0, 1.0, 0.0];
    let wi: [f64; 3] = std::array::from_fn(|k| cd * h[k] + sd * (cp * t[k] + sp * b[k]));
    let wr: [f64; 3] = std::array::from_fn(|k| 2.0 * cd * h[k] - wi[k]);
    let angles = |mut w: [f64; 3]| {
        // A node exactly on the horizon (θ_h + θ_d = 90° in plane) computes w_z ≈ 1e-17, not 0:
        // it is the horizon (zero pBRDF), not a direction 1e-17 rad above it where the standard
        // form's 1/(cosθi cosθr) is 1e16.
        if w[2].abs() < HORIZON_ROUNDING {
            w[2] = 0.0;
        }
        let rho = w[0].hypot(w[1]);
        let theta = rho.atan2(w[2]);
        let phi = if rho == 0.0 { 0.0 } else { w[1].atan2(w[0]) };
        (theta, phi)
    };
    let (ti, pi) = angles(wi);
    let (tr, pr) = angles(wr);
    Geometry::new(ti, pi, tr, pr)
}

/// Mitsuba's sign of S3 against psps's: `P = diag(1, 1, 1, −1)`.
pub const MITSUBA_S3: Mueller = Mueller([
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, -1.0],
]);

/// The psps pBRDF `F` (docs/model.md §2) as a matrix of Mitsuba's `measured_polarized` tables:
/// plane-of-reflection frame, Mitsuba's S3, `T = P·R(−η_r)·F·R(η_i)·P`.
pub fn to_reflection_frame(f: &Mueller, v: &AngleVariables) -> Mueller {
    MITSUBA_S3 * Mueller::rotator(-v.eta_r) * *f * Mueller::rotator(v.eta_i) * MITSUBA_S3
}

/// The inverse of [`to_reflection_frame`]: `F = R(η_r)·P·T·P·R(−η_i)`.
pub fn from_reflection_frame(t: &Mueller, v: &AngleVariables) -> Mueller {
    Mueller::rotator(v.eta_r) * MITSUBA_S3 * *t * MITSUBA_S3 * Mueller::rotator(-v.eta_i)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::MaterialSpec;

    fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    #[test]
    fn cells_reproduce_their_rusinkiewicz_coordinates() {
        // Recompute (θ_h, θ_d, φ_d) from the directions as the plugin does.
        for &(pd, td, th) in &[
            (0.3, 0.4, 0.5),
            (-2.0, 1.1, 0.2),
            (3.0, 0.05, 1.2),
            (1.0, 0.7, 0.0),
        ] {
            let g = cell_geometry(pd, td, th).unwrap();
            let wi = g.w_i();
            let wr = g.w_r();
            let s: [f64; 3] = std::array::from_fn(|k| wi[k] + wr[k]);
            let n = dot(s, s).sqrt();
            let h = s.map(|x| x / n);
            assert!((h[2].acos() - th).abs() < 1e-12);
            assert!((dot(h, wi).acos() - td).abs() < 1e-12);
            if th > 0.0 {
                let b = [-h[1], h[0], 0.0];
                let bn = dot(b, b).sqrt();
                let b = b.map(|x| x / bn);
                let t = [
                    b[1] * h[2] - b[2] * h[1],
                    b[2] * h[0] - b[0] * h[2],
                    b[0] * h[1] - b[1] * h[0],
                ];
                let p: [f64; 3] = std::array::from_fn(|k| wi[k] - dot(wi, h) * h[k]);
                assert!((dot(b, p).atan2(dot(t, p)) - pd).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn horizon_nodes_at_their_float32_values_are_on_the_horizon() {
        // The export evaluates every cell at its nodes rounded to float32: every pair with
        // θ_h + θ_d = 90° of the default 2° × 1° grid (and of a 1° × 1° one) is on the horizon
        // there and has a zero pBRDF, not 1e8 sr⁻¹ (issue 36's fireflies).
        let m = MaterialSpec::new(1.65, 15.0).build().unwrap();
        let f32_node = |deg: f64| f64::from(deg.to_radians() as f32);
        for step in [1.0, 2.0] {
            let mut td = 0.0;
            while td <= 90.0 {
                let th = 90.0 - td;
                for pd in [0.0, std::f64::consts::PI, f64::from(std::f32::consts::PI)] {
                    let g = cell_geometry(pd, f32_node(td), f32_node(th)).unwrap();
                    assert!(
                        g.angle_variables().is_none(),
                        "θ_d = {td}°, θ_h = {th}°: {g:?}"
                    );
                    assert_eq!(m.pbrdf(&g), Mueller::zero());
                }
                td += step;
            }
        }
    }

    #[test]
    fn horizon_nodes_are_on_the_horizon() {
        let g = cell_geometry(0.0, 0.3, std::f64::consts::FRAC_PI_2 - 0.3).unwrap();
        assert!(g.angle_variables().is_none(), "{g:?}");
        let g =
            cell_geometry(std::f64::consts::PI, 0.3, std::f64::consts::FRAC_PI_2 - 0.3).unwrap();
        assert!(g.angle_variables().is_none(), "{g:?}");
        assert!(cell_geometry(0.0, 0.3, 1.2)
            .unwrap()
            .angle_variables()
            .is_some());
    }

    #[test]
    fn the_reflection_frame_is_the_facet_frame() {
        // In the plane-of-reflection frame the surface term is g·M_d/M00 with M_d the Mueller
        // matrix of diag(rs, rp): no linear–linear coupling between S1 and S2 (block diagonal).
        let mut spec = MaterialSpec::new(1.6, 20.0);
        spec.k = 0.3;
        let m = spec.build_at(0.55).unwrap();
        for &(pd, td, th) in &[(0.3, 0.4, 0.5), (-2.0, 1.1, 0.2), (2.5, 0.3, 0.9)] {
            let g = cell_geometry(pd, td, th).unwrap();
            let v = g.angle_variables().unwrap();
            let f = m.pbrdf(&g);
            let t = to_reflection_frame(&f, &v);
            let scale = t.m00();
            for (i, j) in [
                (0, 2),
                (0, 3),
                (1, 2),
                (1, 3),
                (2, 0),
                (2, 1),
                (3, 0),
                (3, 1),
            ] {
                assert!(t[(i, j)].abs() < 1e-12 * scale, "T{i}{j} = {}", t[(i, j)]);
            }
            let back = from_reflection_frame(&t, &v);
            for i in 0..4 {
                for j in 0..4 {
                    assert!((back[(i, j)] - f[(i, j)]).abs() < 1e-13 * scale);
                }
            }
            // The frame axis is unit(w_i × w_r) = s_l: check against the psps s_in (cos η_i).
            let (wi, wr) = (g.w_i(), g.w_r());
            let c = [
                wi[1] * wr[2] - wi[2] * wr[1],
                wi[2] * wr[0] - wi[0] * wr[2],
                wi[0] * wr[1] - wi[1] * wr[0],
            ];
            let cn = dot(c, c).sqrt();
            let phi_i = g.phi_i();
            let s_in = [phi_i.sin(), -phi_i.cos(), 0.0];
            assert!((dot(c, s_in) / cn - v.eta_i.cos()).abs() < 1e-12);
        }
    }
}
