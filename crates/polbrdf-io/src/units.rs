//! Suspicious units in valid inputs (docs/bridges.md, "Unit warnings"): values that are allowed
//! but more likely radians given where degrees are expected. The checks return warnings as
//! values; the CLI prints them as notes (`polbrdf: warning: …` on standard error) and Python
//! raises them as `UserWarning`. Nothing is changed or refused: a warning can be a false alarm
//! (a near-mirror really has σ < 1°).

use crate::csv_io::ANGLE_COLUMNS;
use polbrdf::{Geometry, MaterialSpec};
use std::f64::consts::{FRAC_PI_2, PI};

/// Below this (degrees) a roughness or a shadowing angle is taken to be radians by mistake: a
/// Gaussian slope distribution of σ < 1° is a polished mirror, while every plausible roughness
/// in radians (0.01…1.5 rad) is below it.
pub const SMALL_ANGLE_DEG: f64 = 1.0;

/// A valid input that is probably not what was meant.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnitWarning {
    /// The sentence, naming where the value came from, the key or column and the value.
    pub message: String,
}

impl std::fmt::Display for UnitWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// The warnings of a material's angle parameters (`sigma_deg`, and `tau_deg`/`omega_deg` when
/// shadowing is on): a value in (0, [`SMALL_ANGLE_DEG`]) degrees. `source` names the material
/// (its file or preset) in the message.
pub fn material_warnings(spec: &MaterialSpec, source: &str) -> Vec<UnitWarning> {
    let mut keys = vec![("sigma_deg", spec.sigma_deg)];
    if spec.shadowing {
        keys.push(("tau_deg", Some(spec.tau_deg)));
        keys.push(("omega_deg", Some(spec.omega_deg)));
    }
    keys.into_iter()
        .filter_map(|(key, v)| v.map(|v| (key, v)))
        .filter(|&(_, v)| v > 0.0 && v < SMALL_ANGLE_DEG)
        .map(|(key, v)| UnitWarning {
            message: format!(
                "{source}: {key} = {v} is below {SMALL_ANGLE_DEG}°, a near-mirror; if {v} is in \
                 radians, write {key} = {:.4}",
                v.to_degrees()
            ),
        })
        .collect()
}

/// The largest zenith and azimuth magnitudes of geometries read from degree columns, to tell
/// whether the columns hold radians: feed every row ([`AngleScan::add`]), then ask
/// [`AngleScan::warning`]. Memory: four numbers, whatever the number of rows.
#[derive(Debug, Clone, Copy, Default)]
pub struct AngleScan {
    rows: usize,
    max_zenith: f64,
    max_azimuth: f64,
}

impl AngleScan {
    /// Takes one geometry into account.
    pub fn add(&mut self, g: &Geometry) {
        self.rows += 1;
        self.max_zenith = self.max_zenith.max(g.theta_i()).max(g.theta_r());
        self.max_azimuth = self.max_azimuth.max(g.phi_i().abs()).max(g.phi_r().abs());
    }

    /// A warning when every zenith angle, read in degrees, is at most π/2 (i.e. at most
    /// 1.5708°) and some is not 0, and every azimuth is at most 2π (6.2832°) in magnitude: a
    /// file of radians in degree columns ([`ANGLE_COLUMNS`]). `source` names the file.
    pub fn warning(&self, source: &str) -> Option<UnitWarning> {
        // The geometries hold radians: the value read was θ.to_degrees().
        let zenith = self.max_zenith.to_degrees();
        let azimuth = self.max_azimuth.to_degrees();
        let suspicious =
            self.rows > 0 && zenith > 0.0 && zenith <= FRAC_PI_2 && azimuth <= 2.0 * PI;
        suspicious.then(|| UnitWarning {
            message: format!(
                "{source}: every angle in {} is small (zenith at most {zenith}°, azimuth \
                 at most {azimuth}° in magnitude over {} rows): these columns are in degrees; \
                 if the values are radians, convert them (× 180/π)",
                ANGLE_COLUMNS.join(", "),
                self.rows
            ),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_roughness_below_one_degree_warns_with_the_degrees_it_would_be() {
        let spec = MaterialSpec::new(1.5, 0.26);
        let w = material_warnings(&spec, "paint.toml");
        assert_eq!(w.len(), 1);
        assert_eq!(
            w[0].message,
            "paint.toml: sigma_deg = 0.26 is below 1°, a near-mirror; if 0.26 is in radians, \
             write sigma_deg = 14.8969"
        );
        assert!(material_warnings(&MaterialSpec::new(1.5, 1.0), "m").is_empty());
        assert!(material_warnings(&MaterialSpec::new(1.5, 12.0), "m").is_empty());
        let mut shadowed = MaterialSpec::new(1.5, 12.0);
        shadowed.shadowing = true;
        shadowed.tau_deg = 0.3;
        let w = material_warnings(&shadowed, "m");
        assert_eq!(w.len(), 1);
        assert!(
            w[0].message.starts_with("m: tau_deg = 0.3 is below 1°"),
            "{w:?}"
        );
        shadowed.shadowing = false;
        assert!(material_warnings(&shadowed, "m").is_empty());
    }

    #[test]
    fn radians_in_degree_columns_warn_and_degrees_do_not() {
        let scan = |rows: &[[f64; 4]]| {
            let mut s = AngleScan::default();
            for r in rows {
                s.add(&Geometry::from_degrees(r[0], r[1], r[2], r[3]).unwrap());
            }
            s.warning("data.csv")
        };
        // Radians: zeniths up to 1.4, azimuths up to π.
        let w = scan(&[[0.5, 0.0, 0.5, 3.1], [1.4, 0.0, 1.2, -1.0]]).unwrap();
        assert!(
            w.message.starts_with(
                "data.csv: every angle in theta_i_deg, phi_i_deg, theta_r_deg, phi_r_deg is \
                 small (zenith at most 1.4"
            ),
            "{w}"
        );
        assert!(w.message.contains("over 2 rows"), "{w}");
        // Degrees: a zenith of 30° is no radian.
        assert!(scan(&[[0.5, 0.0, 30.0, 180.0]]).is_none());
        // Normal incidence alone (every zenith 0) is no evidence either way.
        assert!(scan(&[[0.0, 0.0, 0.0, 180.0], [0.0, 0.0, 0.0, 0.0]]).is_none());
        // Small zeniths in degrees with real azimuths (180°) are degrees.
        assert!(scan(&[[1.0, 0.0, 1.0, 180.0]]).is_none());
        assert!(scan(&[]).is_none());
    }
}
