//! `polbrdf daytime`: a scene whose sun is placed by date, time and place, swept through the
//! day (docs/sun-position.md) by `polbrdf_tasks::daytime`: `daytime.csv` and
//! `daytime.png`/`.svg` (ΔDoLP of the best and of a fixed view, and with a sensor their
//! detection ranges, against local time).

use crate::error::CliError;
use crate::output::{write_all, OutputFile};
use crate::values::{self, GridDeg, Pair, Range};
use polbrdf_plot::{render_files, Figure, LegendAt, Line, Panel, Render, PALETTE};
use polbrdf_tasks::daytime::{
    daytime, time_range, DaytimeDetect, DaytimeRequest, DaytimeStudy, DEFAULT_TIMES,
};
use polbrdf_tasks::detect::{SceneSource, SensorSource};
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
    #[arg(long, value_name = "YYYY-MM-DD", value_parser = values::date())]
    pub date: Option<String>,
    /// First local time, HH:MM (the scene's UTC offset).
    #[arg(long, value_name = "HH:MM", default_value = DEFAULT_TIMES.0, value_parser = values::clock())]
    pub from: String,
    /// Last local time, HH:MM (included when on a step).
    #[arg(long, value_name = "HH:MM", default_value = DEFAULT_TIMES.1, value_parser = values::clock())]
    pub to: String,
    /// Minutes between two times.
    #[arg(long, value_name = "MIN", default_value_t = DEFAULT_TIMES.2,
          value_parser = values::number(Range::closed(1.0 / 60.0, f64::MAX)))]
    pub step_min: f64,
    /// Listed local times (HH:MM, comma separated) instead of --from/--to/--step-min.
    #[arg(long, value_name = "HH:MM", value_delimiter = ',', value_parser = values::clock(),
          conflicts_with_all = ["from", "to", "step_min"])]
    pub times: Vec<String>,
    /// Grid steps DTHETA,DPHI in degrees (or one value for both) of every time's study.
    /// Default 5,10.
    #[arg(long, value_name = "DTHETA,DPHI")]
    pub grid_deg: Option<GridDeg>,
    /// The fixed view THETA,PHI in degrees. Default 0,0 (nadir).
    #[arg(
        long,
        value_name = "THETA,PHI",
        allow_hyphen_values = true,
        value_parser = values::pair(Range::ZENITH, Range::AZIMUTH, "THETA,PHI in degrees")
    )]
    pub fixed_view_deg: Option<Pair>,
    /// The target's area, m² (with --sensor).
    #[arg(long, value_name = "M2", value_parser = values::positive())]
    pub area_m2: Option<f64>,
    /// False-alarm probability (with --sensor).
    #[arg(long, value_parser = values::probability())]
    pub pfa: Option<f64>,
    /// Required probability of detection (with --sensor).
    #[arg(long, value_parser = values::probability())]
    pub pd: Option<f64>,
    /// Largest range searched, m (with --sensor).
    #[arg(long, value_name = "M", value_parser = values::positive())]
    pub range_limit_m: Option<f64>,
    /// Output directory (created; files replaced atomically).
    #[arg(long, value_name = "DIR", default_value = "daytime-out")]
    pub out: PathBuf,
}

/// The task's request from the command line: [`DaytimeRequest::new`] with what was given.
fn request(args: &Args) -> Result<DaytimeRequest, CliError> {
    let times = if args.times.is_empty() {
        time_range(&args.from, &args.to, args.step_min).map_err(CliError::usage)?
    } else {
        args.times.clone()
    };
    let mut r = DaytimeRequest::new(SceneSource::File(args.scene.clone()), times);
    r.detect = args.sensor.as_ref().map(|s| {
        let mut d = DaytimeDetect::new(SensorSource::File(s.clone()));
        let t = &mut d.template;
        t.area_m2 = args.area_m2.unwrap_or(t.area_m2);
        t.pfa = args.pfa.unwrap_or(t.pfa);
        t.pd = args.pd.unwrap_or(t.pd);
        t.range_limit_m = args.range_limit_m.unwrap_or(t.range_limit_m);
        d
    });
    if r.detect.is_none() {
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
    r.target.clone_from(&args.target);
    r.background.clone_from(&args.background);
    r.date.clone_from(&args.date);
    if let Some(GridDeg(g)) = args.grid_deg {
        r.grid_deg = g;
    }
    if let Some(Pair(theta, phi)) = args.fixed_view_deg {
        r.fixed_view_deg = (theta, phi);
    }
    Ok(r)
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
    for w in &study.warnings {
        crate::note!("polbrdf daytime: note: {w}");
    }
    let mut files: Vec<OutputFile> = vec![("daytime.csv".into(), study.csv())];
    files.extend(
        render_files(&[("daytime", &figure(&study) as &dyn Render)])
            .map_err(|(_, e)| CliError::Plot(e))?,
    );
    let written = write_all(&args.out, &files)?;
    let up = study.rows().filter(|r| r[4] == 1.0).count();
    crate::note!(
        "polbrdf daytime: {} times on {}, the sun up at {up}",
        study.rows.len(),
        study.date_times().first().map_or("", |d| &d[..10])
    );
    for p in written {
        crate::note!("  wrote {}", p.display());
    }
    Ok(())
}
