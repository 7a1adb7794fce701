//! `polbrdf contrast`: target against background over the viewing hemisphere — polar maps of
//! DoLP, ΔDoLP, intensity ratio, AoLP difference and polarization contrast, `contrast.csv`, and
//! the best viewing directions in `best.json`.

use crate::error::CliError;
use crate::map::{
    angle_scale, csv, deg, dolp_scale, light_marks, polar_grid, render_all, short, single,
    write_all, Output, ViewArgs, PANEL,
};
use crate::spectrum::{describe, load_spec, materials_at};
use polbrdf::analysis::contrast::{
    polarization_null, Contrast, ContrastMap, ContrastSample, Illumination, RankOptions, Ranking,
};
use polbrdf::analysis::scene::Observer;
use polbrdf::Stokes;
use polbrdf_plot::{
    nice_ceil, ColorScale, Colormap, MarkShape, PolarFigure, PolarMark, PolarPanel,
};
use serde_json::{json, Value};
use std::path::PathBuf;

/// The polarization-null directions `(θ_r, φ_r)` in degrees of the target and of the background.
type NullLoci = (Vec<(f64, f64)>, Vec<(f64, f64)>);

/// `polbrdf contrast`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Target material: a TOML file, or a preset name (see `polbrdf materials`). With
    /// --scene, overrides the scene's `[target]` material.
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub target: Option<String>,
    /// Background material: a TOML file, or a preset name. With --scene, overrides the
    /// scene's `[background]` material.
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub background: Option<String>,
    /// A scene file (TOML: wavelength or band, sky, atmosphere, `[target]` and `[background]`
    /// materials and temperatures; see the README): target and background compared by their
    /// observed Stokes radiances — thermal emission and sky included — instead of under one
    /// collimated source.
    #[arg(long, value_name = "SCENE.toml",
          conflicts_with_all = ["sun_zenith_deg", "sun_azimuth_deg", "stokes", "wavelength_um", "band", "band_step_um"])]
    pub scene: Option<PathBuf>,
    #[command(flatten)]
    pub view: ViewArgs,
    /// What the best directions are ranked by: |ΔDoLP|, or the polarization contrast
    /// |ΔS_lin|/mean(S0), which also weighs intensity (docs/model.md §11).
    #[arg(long, value_name = "SCORE", default_value = "delta-dolp",
          value_parser = ["delta-dolp", "polarization-contrast"])]
    pub rank_by: String,
    /// Number of best directions listed in best.json.
    #[arg(long, value_name = "N", default_value_t = 10)]
    pub top: usize,
    /// Minimum angle between two listed directions, degrees.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 10.0,
        allow_negative_numbers = true
    )]
    pub min_separation_deg: f64,
    /// Largest viewing zenith angle the ranking considers, degrees (the maps cover the whole
    /// hemisphere).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 80.0,
        allow_negative_numbers = true
    )]
    pub max_zenith_deg: f64,
    /// Report the best grid nodes as they are, without the brute-force refinement around each.
    #[arg(long)]
    pub no_refine: bool,
    /// Output directory (created if missing).
    #[arg(long, value_name = "DIR", default_value = "contrast-out")]
    pub out: PathBuf,
}

impl Args {
    fn rank_options(&self) -> Result<RankOptions, CliError> {
        let by: Ranking = self.rank_by.parse().map_err(CliError::Invalid)?;
        if self.top == 0 {
            return Err(CliError::Invalid("--top must be at least 1".into()));
        }
        crate::limits::at_most("--top", self.top, crate::limits::TOP)?;
        if !(self.min_separation_deg.is_finite()
            && (0.0..=180.0).contains(&self.min_separation_deg))
        {
            return Err(CliError::Invalid(format!(
                "--min-separation-deg = {}: must lie in [0, 180]",
                self.min_separation_deg
            )));
        }
        if !(self.max_zenith_deg > 0.0 && self.max_zenith_deg < 90.0) {
            return Err(CliError::Invalid(format!(
                "--max-zenith-deg = {}: must lie in (0, 90)",
                self.max_zenith_deg
            )));
        }
        Ok(RankOptions {
            by,
            count: self.top,
            min_separation: self.min_separation_deg.to_radians(),
            max_zenith: self.max_zenith_deg.to_radians(),
            refine: !self.no_refine,
        })
    }
}

/// A material from the command line (`--target`) or else from the scene file's table.
fn material_of(
    arg: &Option<String>,
    option: &str,
    from_scene: Option<&polbrdf_io::SceneObject>,
) -> Result<(polbrdf::MaterialSpec, String, String), CliError> {
    if let Some(a) = arg {
        let (spec, name) = load_spec(a, option)?;
        return Ok((spec, name, a.clone()));
    }
    match from_scene.and_then(|o| o.material.clone()) {
        Some((spec, name)) => Ok((spec, name.clone(), name)),
        None => Err(CliError::Usage(format!(
            "{option} is required{}",
            if from_scene.is_some() {
                format!(
                    " (or a `material` in the scene's [{}] table)",
                    option.trim_start_matches("--")
                )
            } else {
                String::new()
            }
        ))),
    }
}

/// Runs `polbrdf contrast`.
pub fn run(args: &Args) -> Result<(), CliError> {
    // Everything is validated before anything is computed or written.
    let opts = args.rank_options()?;
    let started = std::time::Instant::now();
    let (problem, grid, setting, names, materials) = match &args.scene {
        Some(path) => {
            let grid = args.view.grid()?;
            let scene = polbrdf_io::read_scene(path)?;
            let (target, t_name, t_arg) =
                material_of(&args.target, "--target", Some(&scene.target))?;
            let (background, b_name, b_arg) =
                material_of(&args.background, "--background", Some(&scene.background))?;
            // Errors name the option, or the scene's table the material came from.
            let what = |arg: &Option<String>, option: &str, table: &str| match arg {
                Some(a) => format!("{option} {a}"),
                None => format!("{}: [{table}] material", path.display()),
            };
            let observer = |spec: &polbrdf::MaterialSpec, t: Option<f64>, what: String| {
                Observer::new(
                    spec,
                    &scene.thermal.with_surface_temperature(t),
                    &scene.spectrum,
                )
                .map_err(|e| crate::radiance::observer_error(&what, &e, &scene.spectrum))
            };
            // Valid but easy to get wrong: say so on standard error.
            for (table, t) in [
                ("target", scene.target.temperature_k),
                ("background", scene.background.temperature_k),
            ] {
                // Only where emission matters: from 3 µm on (at 300 K, B_λ at 3 µm is already
                // 1e-3 of its peak; in the visible it is below 1e-20).
                let longest = match &scene.spectrum {
                    polbrdf::Spectrum::Wavelength(l) => *l,
                    polbrdf::Spectrum::Band(b, _) => b.range().1,
                };
                if t.is_none() && longest >= 3.0 {
                    crate::note!(
                        "polbrdf contrast: note: {}: [{table}] has no temperature_k, so the \
                         {table} emits nothing (it only reflects the sky)",
                        path.display()
                    );
                }
            }
            if scene.thermal.surface_temperature_k.is_some() {
                crate::note!(
                    "polbrdf contrast: note: {}: [surface] is for `polbrdf radiance`; contrast \
                     uses the temperatures of [target] and [background]",
                    path.display()
                );
            }
            let problem = Contrast::scene(
                observer(
                    &target,
                    scene.target.temperature_k,
                    what(&args.target, "--target", "target"),
                )?,
                observer(
                    &background,
                    scene.background.temperature_k,
                    what(&args.background, "--background", "background"),
                )?,
            );
            let setting = Setting::Scene(Box::new(scene));
            (problem, grid, setting, (t_name, b_name), (t_arg, b_arg))
        }
        None => {
            let (light, grid) = args.view.build()?;
            let spectrum = args.view.spectral.spectrum()?;
            let (target, t_name, t_arg) = material_of(&args.target, "--target", None)?;
            let (background, b_name, b_arg) = material_of(&args.background, "--background", None)?;
            let nodes = materials_at(
                &[
                    (&target, "--target", &t_arg),
                    (&background, "--background", &b_arg),
                ],
                &spectrum,
            )?;
            let spectral_json = crate::spectrum::to_json(&spectrum, nodes.len());
            let problem = Contrast::spectral(
                nodes
                    .into_iter()
                    .map(|(w, mut ms)| {
                        let b = ms.remove(1);
                        (w, ms.remove(0), b)
                    })
                    .collect(),
                light,
            );
            let setting = Setting::Collimated {
                light,
                spectrum,
                spectral_json,
            };
            (problem, grid, setting, (t_name, b_name), (t_arg, b_arg))
        }
    };
    let map = problem.map(&grid);
    let top = problem.rank(&map, &opts);
    let elapsed = started.elapsed();
    let (t_name, b_name) = &names;
    let names = (t_name.as_str(), b_name.as_str());
    let scene = matches!(setting, Setting::Scene(_));
    // The null locus is where S1 changes sign while S2 vanishes identically: in scenes
    // symmetric about the normal. Under a sun or an azimuth-dependent sky an S1 sign change
    // is the AoLP turning through ±45°, no null: none is drawn or listed.
    let nulls = scene.then(|| {
        if problem.is_azimuth_independent() {
            (
                polarization_null(&map, true),
                polarization_null(&map, false),
            )
        } else {
            (Vec::new(), Vec::new())
        }
    });
    let mut files = vec![
        ("contrast.csv".to_string(), contrast_csv(&map, scene)),
        (
            "best.json".to_string(),
            best_json(
                args,
                &setting,
                &map,
                &top,
                &opts,
                names,
                &materials,
                nulls.as_ref(),
            ),
        ),
    ];
    figures(
        &mut files,
        &map,
        &top,
        &opts,
        &problem,
        names,
        nulls.as_ref(),
    )?;
    let paths = write_all(&args.out, &files)?;

    let score_name = match opts.by {
        Ranking::DeltaDolp => "|ΔDoLP|",
        Ranking::PolarizationContrast => "polarization contrast |ΔS_lin|/mean S0",
    };
    let lighting = match &setting {
        Setting::Collimated {
            light, spectrum, ..
        } => format!(
            "{}; sun at θi = {}°, φi = {}°",
            describe(&Some(spectrum.clone()).flatten()),
            short(light.theta_i().to_degrees()),
            short(light.phi_i().to_degrees())
        ),
        Setting::Scene(s) => format!("; scene {}", s.path.display()),
    };
    println!(
        "polbrdf contrast: target {t_name}, background {b_name}{lighting}; {} viewing directions \
         in {:.0} ms",
        grid.len(),
        elapsed.as_secs_f64() * 1e3
    );
    if let (Setting::Scene(s), Some((nt, nb)), true) =
        (&setting, &nulls, problem.is_azimuth_independent())
    {
        let t = polbrdf::analysis::scene::null_temperature(&s.thermal.sky, &s.spectrum);
        println!(
            "  polarization null: {} direction(s) on the target's map, {} on the background's{}",
            nt.len(),
            nb.len(),
            t.map_or(String::new(), |t| format!(
                "; under this uniform sky both lose their polarization everywhere at {t:.2} K"
            ))
        );
    }
    println!(
        "  best directions by {score_name} (θr ≤ {}°, at least {}° apart{}){}:",
        short(args.max_zenith_deg),
        short(args.min_separation_deg),
        if opts.refine { ", refined" } else { "" },
        if problem.is_azimuth_independent() {
            "; the scene is symmetric about the surface normal, so each is a ring of view \
             directions at every azimuth, listed at φr = 0"
        } else {
            ""
        }
    );
    println!(
        "  {:>3} {:>8} {:>8} {:>11} {:>11} {:>8} {:>9} {:>9}",
        "#", "θr (°)", "φr (°)", "DoLP targ.", "DoLP back.", "ΔDoLP", "I_t/I_b", "pol. con."
    );
    for (k, s) in top.iter().enumerate() {
        println!(
            "  {:>3} {:>8.2} {:>8.2} {:>11.4} {:>11.4} {:>+8.4} {:>9.3} {:>9.4}",
            k + 1,
            deg(s.theta_r),
            deg(s.phi_r),
            s.dolp_target(),
            s.dolp_background(),
            s.delta_dolp(),
            s.intensity_ratio(),
            s.polarization_contrast()
        );
    }
    println!("Wrote {} files to {}", paths.len(), args.out.display());
    Ok(())
}

/// Where target and background are compared: under one collimated source, or in a scene.
enum Setting {
    Collimated {
        light: Illumination,
        spectrum: Option<polbrdf::Spectrum>,
        spectral_json: Value,
    },
    Scene(Box<polbrdf_io::Scene>),
}

fn score_label(by: Ranking) -> &'static str {
    match by {
        Ranking::DeltaDolp => "|ΔDoLP|",
        Ranking::PolarizationContrast => "pol. contrast",
    }
}

const COLUMNS: [&str; 12] = [
    "theta_r_deg",
    "phi_r_deg",
    "dolp_target",
    "dolp_background",
    "delta_dolp",
    "intensity_target",
    "intensity_background",
    "intensity_ratio",
    "aolp_target_deg",
    "aolp_background_deg",
    "aolp_difference_deg",
    "polarization_contrast",
];

fn row(s: &ContrastSample) -> Vec<f64> {
    vec![
        deg(s.theta_r),
        deg(s.phi_r),
        s.dolp_target(),
        s.dolp_background(),
        s.delta_dolp(),
        s.target.0[0],
        s.background.0[0],
        s.intensity_ratio(),
        s.target.aolp().to_degrees(),
        s.background.aolp().to_degrees(),
        s.aolp_difference().to_degrees(),
        s.polarization_contrast(),
    ]
}

/// `contrast.csv`: the columns of [`COLUMNS`], and in a scene `radiance_difference`
/// (S0 of the target − S0 of the background) as well.
fn contrast_csv(map: &ContrastMap, scene: bool) -> Vec<u8> {
    if scene {
        let header: Vec<&str> = COLUMNS
            .iter()
            .copied()
            .chain(["radiance_difference"])
            .collect();
        csv(
            &header,
            map.samples.iter().map(|s| {
                let mut r = row(s);
                r.push(s.radiance_difference());
                r
            }),
        )
    } else {
        csv(&COLUMNS, map.samples.iter().map(row))
    }
}

/// A number for JSON: `null` when not finite (e.g. an infinite intensity ratio).
fn num(v: f64) -> Value {
    serde_json::Number::from_f64(v + 0.0).map_or(Value::Null, Value::Number)
}

fn entry(s: &ContrastSample) -> Value {
    let mut m = serde_json::Map::new();
    for (k, v) in COLUMNS.iter().zip(row(s)) {
        m.insert((*k).to_string(), num(v));
    }
    Value::Object(m)
}

#[allow(clippy::too_many_arguments)]
fn best_json(
    args: &Args,
    setting: &Setting,
    map: &ContrastMap,
    top: &[ContrastSample],
    opts: &RankOptions,
    (t_name, b_name): (&str, &str),
    (t_arg, b_arg): &(String, String),
    nulls: Option<&NullLoci>,
) -> Vec<u8> {
    // As `Contrast::is_azimuth_independent`: a scene without a sun, under a sky that is the
    // same at every azimuth.
    let azimuth_independent =
        matches!(setting, Setting::Scene(s) if s.thermal.is_azimuth_independent());
    let mut doc = json!({
        "best": top.first().map(entry),
        "top": top.iter().map(entry).collect::<Vec<_>>(),
        "ranking": {
            "by": opts.by.as_str(),
            "min_separation_deg": num(args.min_separation_deg),
            "max_zenith_deg": num(args.max_zenith_deg),
            "refined": opts.refine,
            "azimuth_independent": azimuth_independent,
        },
        "target": {"material": t_arg, "name": t_name},
        "background": {"material": b_arg, "name": b_name},
        "grid": {
            "theta_step_deg": num(deg(map.grid.theta_step())),
            "phi_step_deg": num(deg(map.grid.phi_step())),
            "directions": map.grid.len(),
        },
    });
    match setting {
        Setting::Collimated {
            light,
            spectral_json,
            ..
        } => {
            doc["illumination"] = json!({
                "sun_zenith_deg": num(light.theta_i().to_degrees()),
                "sun_azimuth_deg": num(light.phi_i().to_degrees()),
                "stokes_normalized": light.stokes().0.iter().map(|v| num(*v)).collect::<Vec<_>>(),
            });
            doc["spectrum"] = spectral_json.clone();
        }
        Setting::Scene(s) => {
            let nodes = s.spectrum.integral_nodes(&[]).len();
            let null_t = azimuth_independent
                .then(|| polbrdf::analysis::scene::null_temperature(&s.thermal.sky, &s.spectrum))
                .flatten();
            let locus = |v: &[(f64, f64)]| -> Vec<Value> {
                v.iter()
                    .map(|(t, p)| json!([num(deg(*t)), num(deg(*p))]))
                    .collect()
            };
            doc["scene"] = json!({
                "file": s.path.display().to_string(),
                "target_temperature_k": s.target.temperature_k,
                "background_temperature_k": s.background.temperature_k,
                "sky": sky_json(&s.thermal.sky),
                "transmittance": num(s.thermal.atmosphere.transmittance),
                "path_radiance": num(s.thermal.atmosphere.path_radiance),
                "units": match s.spectrum {
                    polbrdf::Spectrum::Wavelength(_) => "W·m⁻²·sr⁻¹·µm⁻¹ (spectral radiance)",
                    polbrdf::Spectrum::Band(..) => "W·m⁻²·sr⁻¹ (band-integrated radiance)",
                },
            });
            doc["spectrum"] = crate::spectrum::to_json(&Some(s.spectrum.clone()), nodes);
            if doc["spectrum"].get("integrated").is_some() {
                doc["spectrum"]["integrated"] =
                    json!("Stokes radiance, integral of response × radiance over the band");
            }
            if let Some((nt, nb)) = nulls {
                doc["polarization_null"] = json!({
                    "what": if azimuth_independent {
                        "view directions (theta_r_deg, phi_r_deg) where S1 changes sign: the emitted and reflected polarizations cancel"
                    } else {
                        "none computed: with a sun or an azimuth-dependent sky S2 does not vanish, and an S1 sign change is the AoLP turning through ±45°, not a null"
                    },
                    "target": locus(nt),
                    "background": locus(nb),
                    "uniform_sky_null_temperature_k": null_t.map(num),
                });
            }
        }
    }
    let mut text = serde_json::to_string_pretty(&doc).expect("JSON of numbers and strings");
    text.push('\n');
    text.into_bytes()
}

/// Marks for the ranked directions: the best one, then numbered rings.
fn ranked_marks(top: &[ContrastSample], by: Ranking) -> Vec<PolarMark> {
    top.iter()
        .enumerate()
        .map(|(k, s)| PolarMark {
            theta_deg: deg(s.theta_r),
            phi_deg: deg(s.phi_r),
            shape: if k == 0 {
                MarkShape::Best
            } else {
                MarkShape::Ring
            },
            label: if k == 0 { "1".into() } else { String::new() },
            legend: if k == 0 {
                format!("best {}", score_label(by))
            } else {
                format!("next {}", top.len() - 1)
            },
        })
        .collect()
}

fn figures(
    files: &mut Vec<Output>,
    map: &ContrastMap,
    top: &[ContrastSample],
    opts: &RankOptions,
    problem: &Contrast,
    (t_name, b_name): (&str, &str),
    nulls: Option<&NullLoci>,
) -> Result<(), CliError> {
    let grid = &map.grid;
    let values =
        |f: fn(&ContrastSample) -> f64| -> Vec<f64> { map.samples.iter().map(f).collect() };
    let light = problem.light().map_or_else(Vec::new, |l| light_marks(&l));
    let ranked: Vec<PolarMark> = light
        .iter()
        .cloned()
        .chain(ranked_marks(top, opts.by))
        .collect();
    let input = if problem
        .light()
        .is_none_or(|l| l.stokes() == Stokes::unpolarized())
    {
        String::new()
    } else {
        let s = problem.light().expect("collimated").stokes().0;
        format!(
            " (input S = {}, {}, {}, {})",
            short(s[0]),
            short(s[1]),
            short(s[2]),
            short(s[3])
        )
    };
    // Colour limits from the directions that are ranked (θr ≤ --max-zenith-deg): toward
    // grazing, values (and, for some parameter sets, unphysical ones) would set the scale of
    // the whole map; beyond, the colours saturate. `v` is aligned with the map's samples.
    let max_abs = |v: &[f64]| {
        v.iter()
            .zip(&map.samples)
            .filter(|(_, s)| s.theta_r <= opts.max_zenith * (1.0 + 1e-12))
            .map(|(x, _)| *x)
            .filter(|x| x.is_finite())
            .fold(0.0, |m: f64, x| m.max(x.abs()))
    };

    // The polarization null of each surface (in a scene): a dotted locus on its DoLP map.
    let null_marks = |v: &[(f64, f64)]| -> Vec<PolarMark> {
        v.iter()
            .enumerate()
            .map(|(k, (t, p))| PolarMark {
                theta_deg: deg(*t),
                phi_deg: deg(*p),
                shape: MarkShape::Dot,
                label: String::new(),
                legend: if k == 0 {
                    "polarization null".into()
                } else {
                    String::new()
                },
            })
            .collect()
    };
    let (null_t, null_b) = nulls.map_or((Vec::new(), Vec::new()), |(t, b)| {
        (null_marks(t), null_marks(b))
    });
    // In a scene (thermal emission: DoLP of a few per cent) both DoLP maps share a scale from
    // 0 to the larger of their maxima over the ranked directions, when that is below 0.5.
    let (dt_values, db_values) = (
        values(ContrastSample::dolp_target),
        values(ContrastSample::dolp_background),
    );
    let dolp_top = max_abs(&dt_values).max(max_abs(&db_values));
    let dolp_scale = || {
        if nulls.is_some() && dolp_top < 0.5 {
            ColorScale::linear(
                Colormap::Viridis,
                0.0,
                nice_ceil(dolp_top.max(1e-3)),
                "DoLP",
            )
        } else {
            dolp_scale()
        }
    };
    let dolp_t = PolarPanel {
        title: format!("DoLP — target: {t_name}{input}"),
        grid: polar_grid(grid, dt_values)?,
        scale: dolp_scale(),
        marks: light.iter().cloned().chain(null_t).collect(),
    };
    let dolp_b = PolarPanel {
        title: format!("DoLP — background: {b_name}"),
        grid: polar_grid(grid, db_values)?,
        scale: dolp_scale(),
        marks: light.iter().cloned().chain(null_b).collect(),
    };
    let delta = values(ContrastSample::delta_dolp);
    let lim = nice_ceil(max_abs(&delta).max(1e-3));
    let delta_dolp = PolarPanel {
        title: "ΔDoLP = DoLP(target) − DoLP(background)".into(),
        grid: polar_grid(grid, delta)?,
        scale: ColorScale::linear(Colormap::Diverging, -lim, lim, "ΔDoLP"),
        marks: if opts.by == Ranking::DeltaDolp {
            ranked.clone()
        } else {
            light.clone()
        },
    };
    let ratio = values(ContrastSample::intensity_ratio);
    let decades = (max_abs(&ratio.iter().map(|r| r.log10()).collect::<Vec<_>>()) * 2.0)
        .ceil()
        .clamp(1.0, 8.0)
        / 2.0;
    let ratio_panel = PolarPanel {
        title: "Intensity ratio S₀(target) / S₀(background)".into(),
        grid: polar_grid(grid, ratio)?,
        scale: ColorScale::log10(
            Colormap::Diverging,
            10f64.powf(-decades),
            10f64.powf(decades),
            "intensity ratio I_t / I_b",
        ),
        marks: light.clone(),
    };
    let d_aolp: Vec<f64> = map
        .samples
        .iter()
        .map(|s| s.aolp_difference().to_degrees())
        .collect();
    let aolp = PolarPanel {
        title: format!(
            "ΔAoLP = AoLP(target) − AoLP(background){}",
            if max_abs(&d_aolp) < 0.05 {
                ": 0 everywhere"
            } else {
                ""
            }
        ),
        grid: polar_grid(grid, d_aolp)?,
        scale: angle_scale(Colormap::Diverging, "ΔAoLP (°)"),
        marks: light.clone(),
    };
    let pc = values(ContrastSample::polarization_contrast);
    let pc_max = nice_ceil(max_abs(&pc).max(1e-3));
    let pol_contrast = PolarPanel {
        title: "Polarization contrast |ΔS_lin| / mean S₀".into(),
        grid: polar_grid(grid, pc)?,
        scale: ColorScale::linear(Colormap::Viridis, 0.0, pc_max, "|ΔS_lin| / mean S₀"),
        marks: if opts.by == Ranking::PolarizationContrast {
            ranked
        } else {
            light.clone()
        },
    };

    let third = match opts.by {
        Ranking::DeltaDolp => delta_dolp.clone(),
        Ranking::PolarizationContrast => pol_contrast.clone(),
    };
    let overview = PolarFigure {
        panel_size: PANEL,
        columns: 3,
        panels: vec![dolp_t.clone(), dolp_b.clone(), third],
    };
    let mut list = vec![
        ("dolp_target", single(dolp_t)),
        ("dolp_background", single(dolp_b)),
        ("delta_dolp", single(delta_dolp)),
        ("intensity_ratio", single(ratio_panel)),
        ("aolp_difference", single(aolp)),
        ("polarization_contrast", single(pol_contrast)),
        ("overview", overview),
    ];
    if nulls.is_some() {
        let diff = values(ContrastSample::radiance_difference);
        let lim = nice_ceil(max_abs(&diff).max(1e-30));
        list.push((
            "radiance_difference",
            single(PolarPanel {
                title: "Radiance difference S₀(target) − S₀(background)".into(),
                grid: polar_grid(grid, diff)?,
                scale: ColorScale::linear(Colormap::Diverging, -lim, lim, "ΔS₀"),
                marks: light,
            }),
        ));
    }
    render_all(files, &list)
}

/// A scene's sky as JSON: its model and its parameters, as the scene file names them.
fn sky_json(sky: &polbrdf::analysis::SkyModel) -> Value {
    use polbrdf::analysis::SkyModel;
    match sky {
        SkyModel::None => json!({"model": "none"}),
        SkyModel::Uniform { radiance } => json!({"model": "uniform", "radiance": num(*radiance)}),
        SkyModel::Thermal { temperature_k } => {
            json!({"model": "thermal", "temperature_k": num(*temperature_k)})
        }
        SkyModel::Profile(p) => {
            let (z, l) = p.table();
            json!({"model": "profile", "zenith_deg": z, "radiance": l})
        }
        SkyModel::ClearSky {
            irradiance,
            dop_max,
        } => {
            json!({"model": "cie-clear", "irradiance": num(*irradiance), "dop_max": num(*dop_max)})
        }
        SkyModel::Table(t) => {
            let (z, p) = t.grid();
            json!({"model": "table", "theta_deg": z, "phi_deg": p})
        }
    }
}
