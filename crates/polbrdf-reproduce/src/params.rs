//! Every number the reproduction uses: the paper's (with where it says so) and ours (with why).

/// Refractive index of the paint (paper §3: "n = 1.65", from Maxwell & Beard).
pub const N: f64 = 1.65;
/// Ω of eq. 3 in degrees (paper §3: "Ω = 40"; docs/model.md §5 reads it as degrees).
pub const OMEGA_DEG: f64 = 40.0;
/// τ of eq. 3 in degrees (paper §3: "τ = 15"; docs/model.md §5 reads it as degrees).
pub const TAU_DEG: f64 = 15.0;

/// Width of D for Fig. 2 (ours: the paper gives no a, b). σ = 15° (b = 1/σ² = 14.59 rad⁻²),
/// `a` from the hemispherical normalization; the same σ as the project's `paint` preset.
pub const FIG2_SIGMA_DEG: f64 = 15.0;
/// Incidence angles of the Fig. 2 curves, degrees ("from near 0° to near 90°").
pub const FIG2_THETAS_DEG: [f64; 7] = [1.0, 15.0, 30.0, 45.0, 60.0, 75.0, 89.0];
/// θN step of Fig. 2, degrees; θN runs over (0°, 60°] as in the paper.
pub const FIG2_THETA_N_STEP_DEG: f64 = 0.25;
/// Upper end of θN in Fig. 2, degrees (paper §3).
pub const FIG2_THETA_N_MAX_DEG: f64 = 60.0;

/// σ for the smooth-surface Fig. 3 (irrelevant to DoLP without a volume term; the project's
/// `paint-smooth` preset).
pub const SMOOTH_SIGMA_DEG: f64 = 5.0;

/// Lambertian volume constant ρ_D, sr⁻¹ (ours; the project's `paint` preset: diffuse albedo
/// πρ_D ≈ 9 %, a dark matte camouflage paint). Needed for any roughness dependence of DoLP.
pub const RHO_D: f64 = 0.03;
/// Non-Lambertian volume constant ρ_V, sr⁻¹ (ours; the project's `paint` preset).
pub const RHO_V: f64 = 0.01;

/// The roughness values of the paper's Table 1 rows (and of our Fig. 4 curves).
pub const ROUGHNESS: [f64; 6] = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5];
/// The incidence angles of the paper's Table 1 columns, degrees.
pub const TABLE_ANGLES_DEG: [f64; 5] = [20.0, 30.0, 45.0, 60.0, 80.0];

/// Table 1 as printed, first number of each cell: the paper's own model, DoLP in %.
pub const TABLE_PAPER_MODEL: [[f64; 5]; 6] = [
    [7.0, 15.0, 30.0, 58.0, 91.0],
    [7.0, 15.0, 30.0, 58.0, 88.0],
    [7.0, 15.0, 30.0, 56.0, 80.0],
    [7.0, 15.0, 30.0, 50.0, 69.0],
    [7.0, 15.0, 26.0, 42.0, 60.0],
    [6.0, 12.0, 20.0, 33.0, 50.0],
];
/// Table 1 as printed, second number of each cell: "Lawrence model" (L. B. Wolff, the
/// paper's ref. \[9\]), DoLP in %.
pub const TABLE_PAPER_LAWRENCE: [[f64; 5]; 6] = [
    [7.0, 15.0, 30.0, 58.0, 93.0],
    [7.0, 15.0, 29.0, 56.0, 88.0],
    [7.0, 14.0, 28.0, 53.0, 83.0],
    [7.0, 14.0, 27.0, 50.0, 79.0],
    [6.0, 13.0, 26.0, 47.0, 74.0],
    [2.0, 12.0, 22.0, 44.0, 69.0],
];
/// Table 1 as printed, third number of each cell: the paper's "error percentage".
pub const TABLE_PAPER_ERROR_PCT: [[f64; 5]; 6] = [
    [0.0, 0.0, 0.0, 0.0, 2.1],
    [0.0, 0.0, 3.3, 3.4, 0.0],
    [0.0, 6.7, 6.6, 5.4, 3.75],
    [0.0, 6.7, 9.9, 0.0, 14.5],
    [14.2, 13.3, 0.0, 11.9, 23.3],
    [66.7, 0.0, 10.0, 33.3, 38.0],
];

/// Angle step of the DoLP curves (Figs. 3–5), degrees.
pub const DOLP_STEP_DEG: f64 = 0.1;
/// Last angle of the DoLP curves, degrees (90° itself is grazing: nothing is reflected).
pub const DOLP_MAX_DEG: f64 = 89.9;
/// Angle step of the thermal-emission curves (each point is a 2-D integral), degrees.
pub const EMISSION_STEP_DEG: f64 = 1.0;

/// σ (degrees) at which interpretation (c)'s σ → 0 row (the Fresnel emission DoLP) is checked
/// against the model itself: the smallest σ at which the core's emissivity is stated to 1e-6
/// (`polbrdf::analysis::emission`); the check is repeated at twice this σ to show the rate.
pub const SMOOTH_CHECK_SIGMA_DEG: f64 = 0.05;

/// Range of the 1-D index scans (real n), log-spaced.
pub const SCAN_N_MIN: f64 = 1.01;
/// Upper end of the real-n scan.
pub const SCAN_N_MAX: f64 = 100.0;
