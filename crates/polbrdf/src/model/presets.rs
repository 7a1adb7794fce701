//! Built-in materials (`polbrdf materials` lists them).
//!
//! Metals' indices are for λ = 632.8 nm (He–Ne), from Rakić et al., Appl. Opt. 37, 5271 (1998)
//! for Al and from Johnson & Christy, Phys. Rev. B 6, 4370 (1972) for Au, Ag and Cu; iron from
//! Johnson & Christy, Phys. Rev. B 9, 5056 (1974). Values rounded to three significant figures.

use crate::error::{Error, Result};
use crate::model::spec::MaterialSpec;

/// One preset: its name, a one-line description and its spec.
#[derive(Debug, Clone)]
pub struct Preset {
    /// Name accepted by `--material` and [`preset`].
    pub name: &'static str,
    /// What it models and where the numbers come from.
    pub description: &'static str,
    /// The material.
    pub spec: MaterialSpec,
}

fn spec(name: &str, n: f64, k: f64, sigma_deg: f64, rho_d: f64, rho_v: f64) -> MaterialSpec {
    MaterialSpec {
        name: Some(name.to_string()),
        k,
        rho_d,
        rho_v,
        ..MaterialSpec::new(n, sigma_deg)
    }
}

/// Every preset, in listing order.
pub fn all() -> Vec<Preset> {
    vec![
        Preset {
            name: "paint",
            description: "the paper's coating: n = 1.65, τ = 15°, Ω = 40° (Maxwell & Beard); \
                          σ = 15° (a semi-gloss surface; the paper gives none), \
                          ρ_D = 0.03 sr⁻¹ (diffuse albedo πρ_D ≈ 9 %, a dark matte camouflage \
                          paint), ρ_V = 0.01 sr⁻¹",
            spec: spec("paint", 1.65, 0.0, 15.0, 0.03, 0.01),
        },
        Preset {
            name: "paint-smooth",
            description: "the paper's coating with no volume term and σ = 5°: the smooth-surface \
                          case of the paper's Fig. 3",
            spec: spec("paint-smooth", 1.65, 0.0, 5.0, 0.0, 0.0),
        },
        Preset {
            name: "glass",
            description: "crown glass, n = 1.52, σ = 5°, no volume term",
            spec: spec("glass", 1.52, 0.0, 5.0, 0.0, 0.0),
        },
        Preset {
            name: "aluminium",
            description:
                "aluminium at 632.8 nm: N = 1.340 + 7.300i (Rakić et al. 1998, Lorentz–Drude; \
                          library:Al/Rakic-LD), σ = 10°",
            spec: spec("aluminium", 1.340, 7.300, 10.0, 0.0, 0.0),
        },
        Preset {
            name: "gold",
            description:
                "gold at 632.8 nm: N = 0.1838 + 3.431i (Johnson & Christy 1972, interpolated; \
                          library:Au/Johnson), σ = 10°",
            spec: spec("gold", 0.1838, 3.431, 10.0, 0.0, 0.0),
        },
        Preset {
            name: "silver",
            description:
                "silver at 632.8 nm: N = 0.05625 + 4.276i (Johnson & Christy 1972, interpolated; \
                          library:Ag/Johnson), σ = 10°",
            spec: spec("silver", 0.05625, 4.276, 10.0, 0.0, 0.0),
        },
        Preset {
            name: "copper",
            description:
                "copper at 632.8 nm: N = 0.2700 + 3.408i (Johnson & Christy 1972, interpolated; \
                          library:Cu/Johnson), σ = 10°",
            spec: spec("copper", 0.2700, 3.408, 10.0, 0.0, 0.0),
        },
        Preset {
            name: "iron",
            description:
                "iron / bare steel at 632.8 nm: N = 2.895 + 3.069i (Johnson & Christy 1974, \
                          interpolated; library:Fe/Johnson), σ = 10°",
            spec: spec("iron", 2.895, 3.069, 10.0, 0.0, 0.0),
        },
    ]
}

/// Names of all presets.
pub fn names() -> Vec<&'static str> {
    all().into_iter().map(|p| p.name).collect()
}

/// The spec of the preset called `name`.
///
/// # Errors
/// [`Error::UnknownPreset`] listing the known names.
pub fn preset(name: &str) -> Result<MaterialSpec> {
    all()
        .into_iter()
        .find(|p| p.name == name)
        .map(|p| p.spec)
        .ok_or_else(|| Error::UnknownPreset {
            name: name.to_string(),
            known: names().join(", "),
        })
}
