//! The polarization-null loci on a contrast map: where S1 of the observed Stokes vector changes
//! sign between two grid zeniths.

use super::ContrastMap;

/// The locus of the polarization null of the target (`target = true`) or the background on a
/// map: for each azimuth of the grid, the view zenith angles where S1 of the observed Stokes
/// vector changes sign between two grid zeniths, interpolated linearly — where the emitted
/// (p-polarized, S1 < 0) and the reflected (s-polarized) polarizations cancel in a thermal
/// scene (docs/model.md §17). `(θr, φr)` in radians, azimuth-major. A null only where S2
/// vanishes identically — in scenes symmetric about the normal
/// ([`Contrast::is_azimuth_independent`](super::Contrast::is_azimuth_independent)); elsewhere an S1 sign change is the AoLP turning
/// through ±45°.
pub fn polarization_null(map: &ContrastMap, target: bool) -> Vec<(f64, f64)> {
    let grid = &map.grid;
    let (nt, np) = (grid.n_theta(), grid.n_phi());
    let s1 = |k: usize, j: usize| {
        let s = &map.samples[k * np + j];
        (
            s.theta_r,
            if target {
                s.target.0[1]
            } else {
                s.background.0[1]
            },
        )
    };
    let mut out = Vec::new();
    for j in 0..np {
        let phi = map.samples[j].phi_r;
        for k in 1..nt {
            let ((t0, a), (t1, b)) = (s1(k - 1, j), s1(k, j));
            if a != 0.0 && b != 0.0 && (a < 0.0) != (b < 0.0) {
                out.push((t0 + (t1 - t0) * a / (a - b), phi));
            } else if b == 0.0 && a != 0.0 {
                out.push((t1, phi));
            }
        }
    }
    out
}
