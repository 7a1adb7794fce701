//! `polbrdf daytime`: a scene whose sun is placed by date, time and place, swept through the
//! day (docs/sun-position.md) by `polbrdf_tasks::daytime`: `daytime.csv` and
//! `daytime.png`/`.svg` (ΔDoLP of the best and of a fixed view, and with a sensor their
//! detection ranges, against local time).

use crate::error::CliError;
use crate::output::{write_all, OutputFile};
use crate::view::numbers;
use polbrdf_plot::{render_files, Figure, LegendAt, Line, Panel, Render, PALETTE};
use polbrdf_tasks::contrast::RankRequest;
use polbrdf_tasks::daytime::{
    daytime, time_range, DaytimeDetect, DaytimeRequest, DaytimeStudy, DAYTIME_GRID_DEG,
};
use polbrdf_tasks::detect::{DetectRequest, SceneSource, SensorSource};
use std::path::PathBuf;

/// `polbrdf daytime`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scene, its [sun] placed by date_time, latitude_deg and longitude_deg.
    #[arg(long, value_name = "SCENE.toml")]
    pub scene: PathBuf,
    /// A sensor file: adds the detection range of the best view and of the fixed view.
    #[arg(long, value_name = "SENSOR.toml")]
    pub sensor: Option<PathBuf>,
    /// Target material (a TOML file or preset), replacing the scene's.
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub target: Option<String>,
    /// Background material, replacing the scene's.
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub background: Option<String>,
    /// The date, YYYY-MM-DD. Default: the date of the scene's date_time.
    #[arg(long, value_name = "YYYY-MM-DD")]
    pub date: Option<String>,
    /// First local time, HH:MM (the scene's UTC offset).
    #[arg(long, value_name = "HH:MM", default_value = "06:00")]
    pub from: String,
    /// Last local time, HH:MM (included when on a step).
    #[arg(long, value_name = "HH:MM", default_value = "18:00")]
    pub to: String,
    /// Minutes between two times.
    #[arg(long, value_name = "MIN", default_value_t = 30.0)]
    pub step_min: f64,
    /// Listed local times (HH:MM, comma separated) instead of --from/--to/--step-min.
    #[arg(long, value_name = "HH:MM", value_delimiter = ',', conflicts_with_all = ["from", "to", "step_min"])]
    pub times: Vec<String>,
    /// Grid steps DTHETA,DPHI in degrees (or one value for both) of every time's study.
    /// Default 5,10.
    #[arg(long, value_name = "DTHETA,DPHI")]
    pub grid_deg: Option<String>,
    /// The fixed view THETA,PHI in degrees. Default 0,0 (nadir).
    #[arg(
        long,
        value_name = "THETA,PHI",
        allow_hyphen_values = true,
        default_value = "0,0"
    )]
    pub fixed_view_deg: String,
    /// The target's area, m² (with --sensor).
    #[arg(long, value_name = "M2")]
    pub area_m2: Option<f64>,
    /// False-alarm probability (with --sensor).
    #[arg(long)]
    pub pfa: Option<f64>,
    /// Required probability of detection (with --sensor).
    #[arg(long)]
    pub pd: Option<f64>,
    /// Largest range searched, m (with --sensor).
    #[arg(long, value_name = "M")]
    pub range_limit_m: Option<f64>,
    /// Output directory (created; files replaced atomically).
    #[arg(long, value_name = "DIR", default_value = "daytime-out")]
    pub out: PathBuf,
}

/// The task's request from the command line.
fn request(args: &Args) -> Result<DaytimeRequest, CliError> {
    let times = if args.times.is_empty() {
        time_range(&args.from, &args.to, args.step_min)?
    } else {
        args.times.clone()
    };
    let detect = args.sensor.as_ref().map(|s| {
        let d = DetectRequest::default();
        DaytimeDetect {
            template: DetectRequest {
                sensor: SensorSource::File(s.clone()),
                area_m2: args.area_m2.unwrap_or(d.area_m2),
                pfa: args.pfa.unwrap_or(d.pfa),
                pd: args.pd.unwrap_or(d.pd),
                range_limit_m: args.range_limit_m.unwrap_or(d.range_limit_m),
                ..d
            },
        }
    });
    if detect.is_none() {
        let given = [
            ("--area-m2", args.area_m2),
            ("--pfa", args.pfa),
            ("--pd", args.pd),
            ("--range-limit-m", args.range_limit_m),
        ];
        if let Some((name, _)) = given.iter().find(|(_, v)| v.is_some()) {
            return Err(CliError::Usage(format!(
                "{name} is a detection option: give --sensor too"
            )));
        }
    }
    Ok(DaytimeRequest {
        scene: SceneSource::File(args.scene.clone()),
        target: args.target.clone(),
        background: args.background.clone(),
        date: args.date.clone(),
        times,
        grid_deg: match &args.grid_deg {
            None => DAYTIME_GRID_DEG,
            Some(text) => {
                match numbers(text, "--grid-deg", "DTHETA or DTHETA,DPHI in degrees")?[..] {
                    [a] => (a, a),
                    [a, b] => (a, b),
                    _ => return Err(invalid_pair(text, "--grid-deg", "DTHETA or DTHETA,DPHI")),
                }
            }
        },
        // The best view is the best grid node: refining it costs a sky integral per trial
        // view under a clear sky, at every time.
        rank: RankRequest {
            refine: false,
            ..RankRequest::default()
        },
        fixed_view_deg: match numbers(&args.fixed_view_deg, "--fixed-view-deg", "THETA,PHI")?[..] {
            [a, b] => (a, b),
            _ => {
                return Err(invalid_pair(
                    &args.fixed_view_deg,
                    "--fixed-view-deg",
                    "THETA,PHI",
                ))
            }
        },
        detect,
    })
}

fn invalid_pair(text: &str, option: &str, what: &str) -> CliError {
    CliError::Invalid(format!("{option} {text:?}: expected {what} in degrees"))
}

/// One line of the figure: column `name` against local time, finite points only.
fn line(study: &DaytimeStudy, name: &str, label: String, k: usize, scale: f64) -> Line {
    let cols = study.columns();
    let c = cols
        .iter()
        .position(|n| *n == name)
        .expect("a daytime column");
    Line {
        label,
        points: study
            .rows()
            .filter(|r| r[c].is_finite())
            .map(|r| (r[0], r[c] * scale))
            .collect(),
        color: PALETTE[k % PALETTE.len()],
        dashed: k % 2 == 1,
        width: 3,
    }
}

/// A panel against local time, its y range from the lines' points.
fn panel(title: String, y_desc: &str, x_range: (f64, f64), lines: Vec<Line>) -> Panel {
    let top = lines
        .iter()
        .flat_map(|l| l.points.iter().map(|p| p.1))
        .fold(0.0, f64::max);
    Panel {
        title,
        x_desc: "local time (h)".into(),
        y_desc: y_desc.into(),
        x_range,
        y_range: (0.0, if top > 0.0 { 1.1 * top } else { 1.0 }),
        log_y: false,
        log_x: false,
        x_ticks: 12,
        y_ticks: 8,
        lines,
        markers: Vec::new(),
        vlines: Vec::new(),
        legend: LegendAt::UpperRight,
    }
}

/// The figure: ΔDoLP of the best and the fixed view; with a sensor, their detection ranges
/// (km; a range beyond the limit drawn at the limit).
fn figure(study: &DaytimeStudy) -> Figure {
    let (ft, fp) = study.request.fixed_view_deg;
    let hours: Vec<f64> = study.rows().map(|r| r[0]).collect();
    let lo = hours.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = hours.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let x = if hi > lo {
        (lo, hi)
    } else {
        (lo - 0.5, lo + 0.5)
    };
    let fixed = format!("fixed view θr = {ft}°, φr = {fp}°");
    let mut panels = vec![panel(
        "ΔDoLP, target against background".into(),
        "ΔDoLP",
        x,
        vec![
            line(study, "best_delta_dolp", "best view".into(), 0, 1.0),
            line(study, "fixed_delta_dolp", fixed.clone(), 1, 1.0),
        ],
    )];
    if let Some(d) = &study.request.detect {
        let limit = d.template.range_limit_m;
        let mut lines = vec![
            line(study, "best_max_range_m", "best view".into(), 2, 1e-3),
            line(study, "fixed_max_range_m", fixed, 3, 1e-3),
        ];
        for l in &mut lines {
            for p in &mut l.points {
                p.1 = p.1.min(limit * 1e-3);
            }
        }
        panels.push(panel(
            format!(
                "detection range (P_d ≥ {}, P_fa = {})",
                d.template.pd, d.template.pfa
            ),
            "range (km)",
            x,
            lines,
        ));
    }
    Figure {
        size: (1100 * panels.len() as u32 / 2 + 550, 650),
        panels,
    }
}

/// Runs `polbrdf daytime`.
pub fn run(args: &Args) -> Result<(), CliError> {
    let study = daytime(&request(args)?)?;
    let mut files: Vec<OutputFile> = vec![("daytime.csv".into(), study.csv())];
    files.extend(
        render_files(&[("daytime", &figure(&study) as &dyn Render)])
            .map_err(|(_, e)| CliError::Plot(e))?,
    );
    let written = write_all(&args.out, &files)?;
    let up = study.rows().filter(|r| r[4] == 1.0).count();
    println!(
        "polbrdf daytime: {} times on {}, the sun up at {up}",
        study.rows.len(),
        study.date_times().first().map_or("", |d| &d[..10])
    );
    for p in written {
        println!("  wrote {}", p.display());
    }
    Ok(())
}
