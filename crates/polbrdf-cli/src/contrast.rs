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
    Contrast, ContrastMap, ContrastSample, Illumination, RankOptions, Ranking,
};
use polbrdf::Stokes;
use polbrdf_plot::{
    nice_ceil, ColorScale, Colormap, MarkShape, PolarFigure, PolarMark, PolarPanel,
};
use serde_json::{json, Value};
use std::path::PathBuf;

/// `polbrdf contrast`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Target material: a TOML file, or a preset name (see `polbrdf materials`).
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub target: String,
    /// Background material: a TOML file, or a preset name.
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub background: String,
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

/// Runs `polbrdf contrast`.
pub fn run(args: &Args) -> Result<(), CliError> {
    // Everything is validated before anything is computed or written.
    let (light, grid) = args.view.build()?;
    let opts = args.rank_options()?;
    let spectrum = args.view.spectral.spectrum()?;
    let (target, t_name) = load_spec(&args.target, "--target")?;
    let (background, b_name) = load_spec(&args.background, "--background")?;
    let nodes = materials_at(
        &[
            (&target, "--target", &args.target),
            (&background, "--background", &args.background),
        ],
        &spectrum,
    )?;
    let spectral_json = crate::spectrum::to_json(&spectrum, nodes.len());

    let started = std::time::Instant::now();
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
    let map = problem.map(&grid);
    let top = problem.rank(&map, &opts);
    let elapsed = started.elapsed();

    let names = (t_name.as_str(), b_name.as_str());
    let mut files = vec![
        ("contrast.csv".to_string(), contrast_csv(&map)),
        (
            "best.json".to_string(),
            best_json(args, &light, &map, &top, &opts, names, spectral_json),
        ),
    ];
    figures(&mut files, &map, &top, &opts, &problem, names)?;
    let paths = write_all(&args.out, &files)?;

    let score_name = match opts.by {
        Ranking::DeltaDolp => "|ΔDoLP|",
        Ranking::PolarizationContrast => "polarization contrast |ΔS_lin|/mean S0",
    };
    println!(
        "polbrdf contrast: target {t_name}, background {b_name}{}; sun at θi = {}°, φi = {}°; \
         {} viewing directions in {:.0} ms",
        describe(&spectrum),
        short(args.view.sun_zenith_deg),
        short(args.view.sun_azimuth_deg),
        grid.len(),
        elapsed.as_secs_f64() * 1e3
    );
    println!(
        "  best directions by {score_name} (θr ≤ {}°, at least {}° apart{}):",
        short(args.max_zenith_deg),
        short(args.min_separation_deg),
        if opts.refine { ", refined" } else { "" }
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

fn contrast_csv(map: &ContrastMap) -> Vec<u8> {
    csv(&COLUMNS, map.samples.iter().map(row))
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

fn best_json(
    args: &Args,
    light: &Illumination,
    map: &ContrastMap,
    top: &[ContrastSample],
    opts: &RankOptions,
    (t_name, b_name): (&str, &str),
    spectrum: Value,
) -> Vec<u8> {
    let stokes = light.stokes();
    let doc = json!({
        "best": top.first().map(entry),
        "top": top.iter().map(entry).collect::<Vec<_>>(),
        "ranking": {
            "by": opts.by.as_str(),
            "min_separation_deg": num(args.min_separation_deg),
            "max_zenith_deg": num(args.max_zenith_deg),
            "refined": opts.refine,
        },
        "target": {"material": args.target, "name": t_name},
        "background": {"material": args.background, "name": b_name},
        "illumination": {
            "sun_zenith_deg": num(args.view.sun_zenith_deg),
            "sun_azimuth_deg": num(args.view.sun_azimuth_deg),
            "stokes_normalized": stokes.0.iter().map(|v| num(*v)).collect::<Vec<_>>(),
        },
        "spectrum": spectrum,
        "grid": {
            "theta_step_deg": num(deg(map.grid.theta_step())),
            "phi_step_deg": num(deg(map.grid.phi_step())),
            "directions": map.grid.len(),
        },
    });
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
) -> Result<(), CliError> {
    let grid = &map.grid;
    let values =
        |f: fn(&ContrastSample) -> f64| -> Vec<f64> { map.samples.iter().map(f).collect() };
    let light = light_marks(&problem.light());
    let ranked: Vec<PolarMark> = light
        .iter()
        .cloned()
        .chain(ranked_marks(top, opts.by))
        .collect();
    let input = if problem.light().stokes() == Stokes::unpolarized() {
        String::new()
    } else {
        let s = problem.light().stokes().0;
        format!(
            " (input S = {}, {}, {}, {})",
            short(s[0]),
            short(s[1]),
            short(s[2]),
            short(s[3])
        )
    };
    let max_abs = |v: &[f64]| {
        v.iter()
            .copied()
            .filter(|x| x.is_finite())
            .fold(0.0, |m: f64, x| m.max(x.abs()))
    };

    let dolp_t = PolarPanel {
        title: format!("DoLP — target: {t_name}{input}"),
        grid: polar_grid(grid, values(ContrastSample::dolp_target))?,
        scale: dolp_scale(),
        marks: light.clone(),
    };
    let dolp_b = PolarPanel {
        title: format!("DoLP — background: {b_name}"),
        grid: polar_grid(grid, values(ContrastSample::dolp_background))?,
        scale: dolp_scale(),
        marks: light.clone(),
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
            light
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
    render_all(
        files,
        &[
            ("dolp_target", single(dolp_t)),
            ("dolp_background", single(dolp_b)),
            ("delta_dolp", single(delta_dolp)),
            ("intensity_ratio", single(ratio_panel)),
            ("aolp_difference", single(aolp)),
            ("polarization_contrast", single(pol_contrast)),
            ("overview", overview),
        ],
    )
}
