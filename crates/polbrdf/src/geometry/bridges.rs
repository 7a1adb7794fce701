//! Bridges to the conventions of other tools (docs/bridges.md): one function per conversion,
//! each stating its convention and its source, so that a polbrdf result can be compared with, or
//! handed to, a polarization camera pipeline (polanalyser), NIST SCATMECH (pySCATMECH) and
//! Mitsuba 3.
//!
//! **polbrdf's own conventions** (docs/model.md §1–2): directions point away from the surface,
//! `w = (sinθ cosφ, sinθ sinφ, cosθ)`; Stokes vectors are in each beam's psps frame
//! `(s, p, k)` with `k` the propagation direction, `s = unit(z × k)`, `p = k × s`; the incident
//! beam travels along `−w_i` (`s_in = (sinφi, −cosφi, 0)`), the reflected one along `w_r`
//! (`s_out = (−sinφr, cosφr, 0)`); the AoLP is `½·atan2(S2, S1)` in (−π/2, π/2], from s toward
//! p; `S3 = −2Im(E_s E_p*)`.
//!
//! **Angles between frames.** [`frame_angle`] measures the angle from one reference axis to
//! another about the beam, positive from `x` toward `k × x` (counterclockwise for a receiver
//! looking back toward the source). A Stokes vector given in the frame `(s, p)` is, in the frame
//! turned by `a`, `Mueller::rotator(−a)·S` (its AoLP smaller by `a`).

use crate::error::{Error, Result};
use crate::geometry::direction::Geometry;
use crate::geometry::rusinkiewicz::MITSUBA_S3;
use crate::optics::mueller::Mueller;
use crate::optics::stokes::Stokes;
use std::f64::consts::PI;

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The angle (rad, in (−π, π]) about the beam direction `k` from the reference axis `from` to the
/// reference axis `to`, positive from `from` toward `k × from`: `atan2((k × from)·to, from·to)`.
/// Both axes are taken perpendicular to `k` (any component along `k` is ignored); neither needs
/// to be normalized. Used for every change of Stokes frame below.
pub fn frame_angle(k: [f64; 3], from: [f64; 3], to: [f64; 3]) -> f64 {
    dot(cross(k, from), to).atan2(dot(from, to))
}

/// The psps frame `(s, p, k)` of the incident beam of `g` (travelling along `−w_i`):
/// `s_in = (sinφi, −cosφi, 0)`, `p_in = k × s_in` (docs/model.md §2).
pub fn incident_frame(g: &Geometry) -> [[f64; 3]; 3] {
    let wi = g.w_i();
    let k = [-wi[0], -wi[1], -wi[2]];
    let (sp, cp) = g.phi_i().sin_cos();
    let s = [sp, -cp, 0.0];
    [s, cross(k, s), k]
}

/// The psps frame `(s, p, k)` of the reflected beam of `g` (travelling along `w_r`):
/// `s_out = (−sinφr, cosφr, 0)`, `p_out = k × s_out` (docs/model.md §2). For θr < 90°, `p_out`
/// is the projection of the zenith `z` on the plane across the beam.
pub fn reflected_frame(g: &Geometry) -> [[f64; 3]; 3] {
    let k = g.w_r();
    let (sp, cp) = g.phi_r().sin_cos();
    let s = [-sp, cp, 0.0];
    [s, cross(k, s), k]
}

// --- Polarization cameras --------------------------------------------------------------------

/// The roll (rad) of a camera that looks back along the reflected beam of `g` (from the detector
/// toward the surface) with image-up vector `up` (world coordinates; the part along the beam is
/// ignored): the angle from `s_out` to the camera's image x axis (image right,
/// `x = unit(up × k)`), from s toward p.
///
/// A camera with no roll (`up` = the zenith `z`, a level camera) has image right = `s_out` and
/// image up = `p_out`: polbrdf's AoLP is then the camera's AoLP measured from image right toward
/// image up (counterclockwise as the image is displayed).
///
/// # Errors
/// [`Error::InvalidParameter`] (`up`) when `up` is not finite or is parallel to the beam.
pub fn camera_roll(g: &Geometry, up: [f64; 3]) -> Result<f64> {
    let [s, _, k] = reflected_frame(g);
    let x = cross(up, k);
    let norm = dot(x, x).sqrt();
    let scale = dot(up, up).sqrt();
    if !(norm.is_finite() && norm > 1e-12 * scale) {
        return Err(Error::InvalidParameter {
            name: "up",
            value: norm,
            reason: "must be finite and not parallel to the view direction",
        });
    }
    Ok(frame_angle(k, s, x))
}

/// A Stokes vector of the reflected beam (psps, `s_out`) in the frame of a camera with roll
/// `roll` (rad, [`camera_roll`]): reference axis image right, second axis image up,
/// `Mueller::rotator(−roll)·S`. S0 and S3 are unchanged; the AoLP becomes `aolp − roll`.
pub fn stokes_to_camera(s: &Stokes, roll: f64) -> Stokes {
    Mueller::rotator(-roll) * *s
}

/// The inverse of [`stokes_to_camera`]: `Mueller::rotator(roll)·S`.
pub fn stokes_from_camera(s: &Stokes, roll: f64) -> Stokes {
    Mueller::rotator(roll) * *s
}

/// Which way a camera's second image axis points, for a pipeline that measures polarizer and
/// polarization angles from image right (`x`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageY {
    /// Angles grow from image right toward image **up** (counterclockwise as displayed; a
    /// right-handed frame with the propagation direction, as polbrdf's): no mirror.
    Up,
    /// Angles grow from image right toward image **down** (the pixel row index, y down, as in
    /// OpenCV's image coordinates): the frame is mirrored, S2 and S3 change sign.
    Down,
}

/// A Stokes vector of the reflected beam (psps) as a polarization-camera pipeline such as
/// polanalyser computes it from its polarizer pixels (`pa.calcStokes` with pixel angles measured
/// from image right, `pa.polarizer`'s Mueller matrix): [`stokes_to_camera`], then with
/// [`ImageY::Down`] S2 and S3 negated (a mirrored frame).
pub fn stokes_to_polanalyser(s: &Stokes, roll: f64, y: ImageY) -> Stokes {
    let c = stokes_to_camera(s, roll);
    match y {
        ImageY::Up => c,
        ImageY::Down => Stokes::new(c[0], c[1], -c[2], -c[3]),
    }
}

/// polanalyser's AoLP of a Stokes vector (`pa.cvtStokesToAoLP`): `½·atan2(S2, S1)` reduced to
/// `[0, π)` (radians). polbrdf's AoLP in (−π/2, π/2] and this one differ by π where polbrdf's is
/// negative: that alone is the difference for the same Stokes vector (−73.15° here is 106.85°
/// there).
pub fn polanalyser_aolp(s: &Stokes) -> f64 {
    let a = (0.5 * s[2].atan2(s[1])).rem_euclid(PI);
    // rem_euclid of a tiny negative number rounds to π itself; π is 0 on this circle.
    if a >= PI {
        0.0
    } else {
        a
    }
}

/// polbrdf's AoLP (rad, from `s_out` toward `p_out`) as polanalyser reports it for a camera with
/// roll `roll` (rad) and image axes `y`: `aolp − roll` (or `roll − aolp` with [`ImageY::Down`])
/// reduced to `[0, π)`.
pub fn aolp_to_polanalyser(aolp: f64, roll: f64, y: ImageY) -> f64 {
    let camera = aolp - roll;
    let signed = match y {
        ImageY::Up => camera,
        ImageY::Down => -camera,
    };
    polanalyser_aolp(&Stokes::linear(signed))
}

// --- NIST SCATMECH ---------------------------------------------------------------------------

/// A geometry in SCATMECH's angles (radians, as pySCATMECH's `BRDF_Model.MuellerBRDF` takes
/// them): the light arrives from azimuth 180° (travelling along `(sinθi, 0, −cosθi)`), the
/// viewer sits at zenith `theta_s` and azimuth `phi_s`, specular at `phi_s = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScatmechAngles {
    /// Incidence angle θi.
    pub theta_i: f64,
    /// Viewing (scattering) zenith angle θs.
    pub theta_s: f64,
    /// Viewing azimuth φs in (−π, π], 0 at specular.
    pub phi_s: f64,
}

/// polbrdf's geometry in SCATMECH's angles: `(θi, θs, φs) = (θi, θr, φr − φi − π)`, φs reduced to
/// (−π, π]. Both models are isotropic and both use the psps frames (SCATMECH's `coords="psps"`),
/// so with these angles the two Mueller matrices agree entry by entry
/// (python/tests/test_scatmech_oracle.py; docs/model.md §2).
pub fn to_scatmech(g: &Geometry) -> ScatmechAngles {
    ScatmechAngles {
        theta_i: g.theta_i(),
        theta_s: g.theta_r(),
        phi_s: scatmech_phi_s(g.phi_i(), g.phi_r(), PI),
    }
}

/// SCATMECH's viewing azimuth `φs = φr − φi − ½turn` reduced to (−½turn, ½turn], in any angle
/// unit: `half_turn` is π for radians, 180 for degrees (exact in degrees: 195 − 15 − 180 = 0).
pub fn scatmech_phi_s(phi_i: f64, phi_r: f64, half_turn: f64) -> f64 {
    let d = (phi_r - phi_i - half_turn).rem_euclid(2.0 * half_turn);
    if d > half_turn {
        d - 2.0 * half_turn
    } else {
        d
    }
}

/// SCATMECH's `(θi, θs, φs)` (radians) as polbrdf's geometry, with SCATMECH's source azimuth:
/// `(θi, φi, θr, φr) = (θi, π, θs, φs)`.
///
/// # Errors
/// [`Error::InvalidAngle`] as [`Geometry::new`] (NaN, ±∞, zenith outside `[0, π]`).
pub fn from_scatmech(theta_i: f64, theta_s: f64, phi_s: f64) -> Result<Geometry> {
    Geometry::new(theta_i, PI, theta_s, phi_s)
}

// --- Mitsuba 3 -------------------------------------------------------------------------------

/// Mitsuba 3's implicit Stokes reference axis of a beam travelling along the unit vector `k`:
/// `mi.mueller.stokes_basis(k)`, the first vector of `coordinate_system(k)` (Duff et al. 2017,
/// "Building an orthonormal basis, revisited", as in Mitsuba's `include/mitsuba/core/vector.h`;
/// `sign(0) = +1` as Dr.Jit's): with `σ = ±1` the sign of `k_z` and `a = −1/(σ + k_z)`,
/// `x = (1 + σ·k_x²·a, σ·k_x·k_y·a, −σ·k_x)`. The second axis is `k × x`, as psps's `p = k × s`.
pub fn mitsuba_stokes_basis(k: [f64; 3]) -> [f64; 3] {
    let sign = if k[2] >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + k[2]);
    let b = k[0] * k[1] * a;
    [1.0 + sign * k[0] * k[0] * a, sign * b, -sign * k[0]]
}

/// The angles from the psps s axes to Mitsuba's Stokes axes, incident and reflected beam.
fn mitsuba_angles(g: &Geometry) -> (f64, f64) {
    let [s_in, _, k_in] = incident_frame(g);
    let [s_out, _, k_out] = reflected_frame(g);
    (
        frame_angle(k_in, s_in, mitsuba_stokes_basis(k_in)),
        frame_angle(k_out, s_out, mitsuba_stokes_basis(k_out)),
    )
}

/// polbrdf's pBRDF `F` (psps) as the Mueller matrix Mitsuba 3's polarized BSDFs return from
/// `bsdf.eval` (divided by `cosθi`), in the local shading frame (z = the normal) in radiance
/// mode: polbrdf's `w_i` is Mitsuba's `wo` (toward the light) and `w_r` is `si.wi` (toward the
/// camera); the incident beam's reference axis is `stokes_basis(−w_i)`, the outgoing one's
/// `stokes_basis(w_r)` ([`mitsuba_stokes_basis`]); and Mitsuba's S3 is minus psps's (its Fresnel
/// amplitudes take `N = n − ik`; docs/model.md §20):
/// `M = P·R(−a_out)·F·R(a_in)·P`, `P = diag(1, 1, 1, −1)`, `R = Mueller::rotator`, `a` the
/// [`frame_angle`] from s to Mitsuba's axis. Same as Mitsuba's own
/// `mueller.rotate_mueller_basis` (python/tests/test_bridges_peers.py).
pub fn mueller_to_mitsuba(f: &Mueller, g: &Geometry) -> Mueller {
    let (a_in, a_out) = mitsuba_angles(g);
    MITSUBA_S3 * Mueller::rotator(-a_out) * *f * Mueller::rotator(a_in) * MITSUBA_S3
}

/// The inverse of [`mueller_to_mitsuba`]: `F = R(a_out)·P·M·P·R(−a_in)`.
pub fn mueller_from_mitsuba(m: &Mueller, g: &Geometry) -> Mueller {
    let (a_in, a_out) = mitsuba_angles(g);
    Mueller::rotator(a_out) * MITSUBA_S3 * *m * MITSUBA_S3 * Mueller::rotator(-a_in)
}

/// A Stokes vector of the reflected beam of `g` (psps) in Mitsuba's basis of that beam
/// (`stokes_basis(w_r)`, Mitsuba's sign of S3): `P·R(−a_out)·S`.
pub fn stokes_to_mitsuba(s: &Stokes, g: &Geometry) -> Stokes {
    let (_, a_out) = mitsuba_angles(g);
    MITSUBA_S3 * (Mueller::rotator(-a_out) * *s)
}

#[cfg(test)]
#[path = "bridges_tests.rs"]
mod tests;
