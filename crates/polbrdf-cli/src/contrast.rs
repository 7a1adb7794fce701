//! `polbrdf contrast`: target against background over the viewing hemisphere — polar maps of
//! DoLP, ΔDoLP, intensity ratio, AoLP difference and polarization contrast, `contrast.csv`, and
//! the best viewing directions in `best.json`.

use crate::closed_set;
use crate::error::CliError;
use crate::figures::{
    angle_scale, dolp_scale, input_stokes, invalid_marks, light_marks, polar_grid, render_all,
    short, single, INVALID_LEGEND_SHORT, PANEL,
};
use crate::output::{csv, write_all, OutputFile};
use crate::values::{self, Range};
use crate::view::ViewArgs;
use polbrdf::analysis::contrast::{ContrastSample, Ranking};
use polbrdf_plot::{
    nice_ceil, ColorScale, Colormap, MarkShape, PolarFigure, PolarMark, PolarPanel,
};
use polbrdf_tasks::contrast::{
    contrast_with_progress, ContrastRequest, ContrastStudy, RankRequest, Setting, SourceRequest,
};
use polbrdf_tasks::hemisphere::deg;
use polbrdf_tasks::spectrum::describe;
use std::path::PathBuf;

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
    /// materials and temperatures; see docs/guide-emission.md): target and background compared by their
    /// observed Stokes radiances — thermal emission and sky included — instead of under one
    /// collimated source.
    #[arg(long, value_name = "SCENE.toml",
          conflicts_with_all = ["sun_zenith_deg", "sun_azimuth_deg", "stokes", "wavelength_um", "band", "band_step_um"])]
    pub scene: Option<PathBuf>,
    #[command(flatten)]
    pub view: ViewArgs,
    /// What the best directions are ranked by: |ΔDoLP|, or the polarization contrast
    /// |ΔS_lin|/mean(S0), which also weighs intensity (docs/model.md §11).
    #[arg(long, value_name = "SCORE", default_value = Ranking::DeltaDolp.as_str(),
          value_parser = closed_set::parser(&Ranking::ALL, |r| r.as_str()))]
    pub rank_by: Ranking,
    /// Number of best directions listed in best.json.
    #[arg(long, value_name = "N", default_value_t = 10,
          value_parser = values::count(1, polbrdf_tasks::limits::TOP))]
    pub top: usize,
    /// Minimum angle between two listed directions, degrees.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 10.0,
        allow_negative_numbers = true,
        value_parser = values::number(Range::closed(0.0, 180.0))
    )]
    pub min_separation_deg: f64,
    /// Largest viewing zenith angle the ranking considers, degrees (the maps cover the whole
    /// hemisphere).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 80.0,
        allow_negative_numbers = true,
        value_parser = values::number(Range::open(0.0, 90.0))
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
    /// The request: options parsed (and limited), the rest validated by the task.
    fn request(&self) -> Result<ContrastRequest, CliError> {
        let by = self.rank_by;
        let source = match &self.scene {
            Some(path) => SourceRequest::Scene(path.clone()),
            None => SourceRequest::Collimated {
                light: self.view.light()?,
                spectral: self.view.spectral.request(),
            },
        };
        Ok(ContrastRequest {
            target: self.target.clone(),
            background: self.background.clone(),
            source,
            grid_deg: self.view.grid_deg(),
            rank: RankRequest {
                by,
                top: self.top,
                min_separation_deg: self.min_separation_deg,
                max_zenith_deg: self.max_zenith_deg,
                refine: !self.no_refine,
            },
        })
    }
}

/// Runs `polbrdf contrast`: everything is validated before anything is computed or written.
pub fn run(args: &Args) -> Result<(), CliError> {
    let request = args.request()?;
    let started = std::time::Instant::now();
    // A bar (on a terminal) for a scene, whose sky integrals take seconds; none under a
    // collimated source, done in milliseconds.
    let bar = args
        .scene
        .as_ref()
        .map(|_| crate::progress::Progress::new(0, "contrast: viewing directions"));
    let study = contrast_with_progress(&request, &mut |done, total| {
        if let Some(bar) = &bar {
            bar.set(done as u64, total as u64, None);
        }
    })?;
    drop(bar);
    let elapsed = started.elapsed();
    for w in &study.warnings {
        crate::note!("polbrdf contrast: note: {w}");
    }
    let mut best = serde_json::to_string_pretty(&study.best_json()).expect("JSON of numbers");
    best.push('\n');
    let mut files = vec![
        (
            "contrast.csv".to_string(),
            csv(&study.columns(), study.rows()),
        ),
        ("best.json".to_string(), best.into_bytes()),
    ];
    figures(&mut files, &study)?;
    let paths = write_all(&args.out, &files)?;
    summary(&study, elapsed);
    crate::note!("Wrote {} files to {}", paths.len(), args.out.display());
    Ok(())
}

/// The summary on standard error: setting, null loci, the best directions.
fn summary(study: &ContrastStudy, elapsed: std::time::Duration) {
    let (t_name, b_name) = (&study.target.name, &study.background.name);
    let score_name = match study.options.by {
        Ranking::DeltaDolp => "|ΔDoLP|",
        Ranking::PolarizationContrast => "polarization contrast |ΔS_lin|/mean S0",
    };
    let lighting = match &study.setting {
        Setting::Collimated {
            light, spectrum, ..
        } => format!(
            "{}; sun at θi = {}°, φi = {}°",
            describe(spectrum.as_ref()),
            short(light.theta_i().to_degrees()),
            short(light.phi_i().to_degrees())
        ),
        Setting::Scene(s) => format!("; scene {}", s.path.display()),
    };
    crate::note!(
        "polbrdf contrast: target {t_name}, background {b_name}{lighting}; {} viewing directions \
         in {:.0} ms",
        study.map.grid.len(),
        elapsed.as_secs_f64() * 1e3
    );
    for (which, zeniths) in [
        ("target", &study.invalid_zeniths.target),
        ("background", &study.invalid_zeniths.background),
    ] {
        if let Some(t) = zeniths.first() {
            crate::note!(
                "  {which} model flagged invalid (emissivity outside [0, 1]) at {} zenith(s) \
                 from θr = {}° (marked on the maps)",
                zeniths.len(),
                short(deg(*t))
            );
        }
    }
    let symmetric = study.problem.is_azimuth_independent();
    if let (Some(n), true) = (&study.nulls, symmetric) {
        crate::note!(
            "  polarization null: {} direction(s) on the target's map, {} on the background's{}",
            n.target.len(),
            n.background.len(),
            n.uniform_sky_temperature_k
                .map_or(String::new(), |t| format!(
                    "; under this uniform sky both lose their polarization everywhere at {t:.2} K"
                ))
        );
    }
    crate::note!(
        "  best directions by {score_name} (θr ≤ {}°, at least {}° apart{}){}:",
        short(study.rank.max_zenith_deg),
        short(study.rank.min_separation_deg),
        if study.options.refine {
            ", refined"
        } else {
            ""
        },
        if symmetric {
            "; the scene is symmetric about the surface normal, so each is a ring of view \
             directions at every azimuth, listed at φr = 0"
        } else {
            ""
        }
    );
    crate::note!(
        "  {:>3} {:>8} {:>8} {:>11} {:>11} {:>8} {:>9} {:>9}",
        "#",
        "θr (°)",
        "φr (°)",
        "DoLP targ.",
        "DoLP back.",
        "ΔDoLP",
        "I_t/I_b",
        "pol. con."
    );
    for (k, s) in study.top.iter().enumerate() {
        crate::note!(
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
}

fn score_label(by: Ranking) -> &'static str {
    match by {
        Ranking::DeltaDolp => "|ΔDoLP|",
        Ranking::PolarizationContrast => "pol. contrast",
    }
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

/// The marks of the maps beside the null loci.
struct Marks {
    /// The target's DoLP map: the light, where its model is flagged invalid.
    light_t: Vec<PolarMark>,
    /// The background's DoLP map, likewise.
    light_b: Vec<PolarMark>,
    /// The maps comparing the two: the light, where either model is flagged invalid.
    light: Vec<PolarMark>,
    /// The map of the ranking score: the light, the ranked directions, where either model is
    /// flagged invalid (last: the legend lists the ranked directions first).
    ranked: Vec<PolarMark>,
}

fn marks(study: &ContrastStudy) -> Marks {
    let sun = study
        .problem
        .light()
        .map_or_else(Vec::new, |l| light_marks(&l));
    let invalid = &study.invalid_zeniths;
    let with_invalid = |mut marks: Vec<PolarMark>, zeniths: &[f64]| -> Vec<PolarMark> {
        marks.extend(invalid_marks(zeniths, INVALID_LEGEND_SHORT));
        marks
    };
    let either = invalid.either();
    let ranked = sun
        .iter()
        .cloned()
        .chain(ranked_marks(&study.top, study.options.by))
        .collect();
    Marks {
        light_t: with_invalid(sun.clone(), &invalid.target),
        light_b: with_invalid(sun.clone(), &invalid.background),
        light: with_invalid(sun, &either),
        ranked: with_invalid(ranked, &either),
    }
}

/// The polar maps (PNG and SVG) of a study: each surface's DoLP, the comparisons (ΔDoLP,
/// intensity ratio, ΔAoLP, polarization contrast), an overview of the two DoLP maps beside the
/// ranking score's, and in a scene the radiance difference.
fn figures(files: &mut Vec<OutputFile>, study: &ContrastStudy) -> Result<(), CliError> {
    let Marks {
        light_t,
        light_b,
        light,
        ranked,
    } = marks(study);
    let (ranked_delta, ranked_pc) = match study.options.by {
        Ranking::DeltaDolp => (ranked, light.clone()),
        Ranking::PolarizationContrast => (light.clone(), ranked),
    };
    let (dolp_t, dolp_b) = dolp_panels(study, light_t, light_b)?;
    let delta_dolp = delta_dolp_panel(study, ranked_delta)?;
    let ratio = ratio_panel(study, light.clone())?;
    let aolp = aolp_panel(study, light.clone())?;
    let pol_contrast = polarization_contrast_panel(study, ranked_pc)?;
    let third = match study.options.by {
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
        ("intensity_ratio", single(ratio)),
        ("aolp_difference", single(aolp)),
        ("polarization_contrast", single(pol_contrast)),
        ("overview", overview),
    ];
    if study.nulls.is_some() {
        list.push((
            "radiance_difference",
            single(radiance_difference_panel(study, light)?),
        ));
    }
    render_all(files, &list)
}

/// One value per sample of the study's map.
fn sample_values(study: &ContrastStudy, f: impl Fn(&ContrastSample) -> f64) -> Vec<f64> {
    study.map.samples.iter().map(f).collect()
}

/// The largest finite |value| of `v` (aligned with the map's samples) over the directions that
/// are ranked (θr ≤ --max-zenith-deg): the colour limit of a map. Toward grazing, values (and,
/// for some parameter sets, unphysical ones) would set the scale of the whole map; beyond, the
/// colours saturate.
fn ranked_max_abs(study: &ContrastStudy, v: &[f64]) -> f64 {
    let max_zenith = study.options.max_zenith;
    v.iter()
        .zip(&study.map.samples)
        .filter(|(_, s)| s.theta_r <= max_zenith * (1.0 + 1e-12))
        .map(|(x, _)| *x)
        .filter(|x| x.is_finite())
        .fold(0.0, |m: f64, x| m.max(x.abs()))
}

/// The polarization null of a surface (in a scene): a dotted locus on its DoLP map.
fn null_marks(v: &[(f64, f64)]) -> Vec<PolarMark> {
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
}

/// The DoLP maps of the target and the background, with `light_t` and `light_b` and each
/// surface's null locus. In a scene (thermal emission: DoLP of a few per cent) both share a
/// scale from 0 to the larger of their maxima over the ranked directions, when that is below
/// 0.5; otherwise the full [0, 1].
fn dolp_panels(
    study: &ContrastStudy,
    light_t: Vec<PolarMark>,
    light_b: Vec<PolarMark>,
) -> Result<(PolarPanel, PolarPanel), CliError> {
    let (t_name, b_name) = (&study.target.name, &study.background.name);
    let grid = &study.map.grid;
    let (null_t, null_b) = study.nulls.as_ref().map_or((Vec::new(), Vec::new()), |n| {
        (null_marks(&n.target), null_marks(&n.background))
    });
    let input = study
        .problem
        .light()
        .map_or_else(String::new, |l| input_stokes(&l, (" (input S = ", ")")));
    let (dt_values, db_values) = (
        sample_values(study, ContrastSample::dolp_target),
        sample_values(study, ContrastSample::dolp_background),
    );
    let dolp_top = ranked_max_abs(study, &dt_values).max(ranked_max_abs(study, &db_values));
    let dolp_scale = || {
        if study.nulls.is_some() && dolp_top < 0.5 {
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
        marks: light_t.into_iter().chain(null_t).collect(),
    };
    let dolp_b = PolarPanel {
        title: format!("DoLP — background: {b_name}"),
        grid: polar_grid(grid, db_values)?,
        scale: dolp_scale(),
        marks: light_b.into_iter().chain(null_b).collect(),
    };
    Ok((dolp_t, dolp_b))
}

/// ΔDoLP = DoLP(target) − DoLP(background), on a symmetric diverging scale.
fn delta_dolp_panel(study: &ContrastStudy, marks: Vec<PolarMark>) -> Result<PolarPanel, CliError> {
    let delta = sample_values(study, ContrastSample::delta_dolp);
    let lim = nice_ceil(ranked_max_abs(study, &delta).max(1e-3));
    Ok(PolarPanel {
        title: "ΔDoLP = DoLP(target) − DoLP(background)".into(),
        grid: polar_grid(&study.map.grid, delta)?,
        scale: ColorScale::linear(Colormap::Diverging, -lim, lim, "ΔDoLP"),
        marks,
    })
}

/// The intensity ratio S₀(target) / S₀(background), on a logarithmic scale symmetric about 1
/// (half-decade steps, 0.5 to 4 decades).
fn ratio_panel(study: &ContrastStudy, marks: Vec<PolarMark>) -> Result<PolarPanel, CliError> {
    let ratio = sample_values(study, ContrastSample::intensity_ratio);
    let logs: Vec<f64> = ratio.iter().map(|r| r.log10()).collect();
    let decades = (ranked_max_abs(study, &logs) * 2.0).ceil().clamp(1.0, 8.0) / 2.0;
    Ok(PolarPanel {
        title: "Intensity ratio S₀(target) / S₀(background)".into(),
        grid: polar_grid(&study.map.grid, ratio)?,
        scale: ColorScale::log10(
            Colormap::Diverging,
            10f64.powf(-decades),
            10f64.powf(decades),
            "intensity ratio I_t / I_b",
        ),
        marks,
    })
}

/// ΔAoLP = AoLP(target) − AoLP(background) in degrees, on a cyclic scale; the title says when
/// it is 0 everywhere (below 0.05° over the ranked directions).
fn aolp_panel(study: &ContrastStudy, marks: Vec<PolarMark>) -> Result<PolarPanel, CliError> {
    let d_aolp = sample_values(study, |s| s.aolp_difference().to_degrees());
    Ok(PolarPanel {
        title: format!(
            "ΔAoLP = AoLP(target) − AoLP(background){}",
            if ranked_max_abs(study, &d_aolp) < 0.05 {
                ": 0 everywhere"
            } else {
                ""
            }
        ),
        grid: polar_grid(&study.map.grid, d_aolp)?,
        scale: angle_scale(Colormap::CyclicDiverging, "ΔAoLP (°)"),
        marks,
    })
}

/// The polarization contrast |ΔS_lin| / mean S₀ (docs/model.md §11), from 0.
fn polarization_contrast_panel(
    study: &ContrastStudy,
    marks: Vec<PolarMark>,
) -> Result<PolarPanel, CliError> {
    let pc = sample_values(study, ContrastSample::polarization_contrast);
    let pc_max = nice_ceil(ranked_max_abs(study, &pc).max(1e-3));
    Ok(PolarPanel {
        title: "Polarization contrast |ΔS_lin| / mean S₀".into(),
        grid: polar_grid(&study.map.grid, pc)?,
        scale: ColorScale::linear(Colormap::Viridis, 0.0, pc_max, "|ΔS_lin| / mean S₀"),
        marks,
    })
}

/// The radiance difference S₀(target) − S₀(background) of a scene, on a symmetric diverging
/// scale.
fn radiance_difference_panel(
    study: &ContrastStudy,
    marks: Vec<PolarMark>,
) -> Result<PolarPanel, CliError> {
    let diff = sample_values(study, ContrastSample::radiance_difference);
    let lim = nice_ceil(ranked_max_abs(study, &diff).max(1e-30));
    Ok(PolarPanel {
        title: "Radiance difference S₀(target) − S₀(background)".into(),
        grid: polar_grid(&study.map.grid, diff)?,
        scale: ColorScale::linear(Colormap::Diverging, -lim, lim, "ΔS₀"),
        marks,
    })
}
