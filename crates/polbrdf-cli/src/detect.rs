//! `polbrdf detect`: will a sensor see the target on its background, from where, by which
//! feature and how far (docs/detection.md) — `detect.csv`, `best.json` and polar maps of the
//! detection range and of P_d, all computed by the task layer (`polbrdf_tasks::detect`).

use crate::closed_set;
use crate::error::CliError;
use crate::figures::{polar_grid, render_all, short, single};
use crate::output::{write_all, OutputFile};
use crate::values::{self, GridDeg, Pair, Range};
use polbrdf::analysis::detection::Feature;
use polbrdf_plot::{ColorScale, Colormap, PolarPanel};
use polbrdf_tasks::detect::RangeUncertainty;
use polbrdf_tasks::detect::{
    detect, DetectRequest, DetectStudy, FitSource, SceneSource, SensorSource, Views,
};
use std::path::PathBuf;

/// Options of `polbrdf detect`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scene: target, background, sun, sky and [path] (TOML; docs/detection.md).
    #[arg(long, value_name = "SCENE.toml")]
    pub scene: PathBuf,
    /// The sensor file (TOML; docs/detection.md).
    #[arg(long, value_name = "SENSOR.toml")]
    pub sensor: PathBuf,
    /// The target material, replacing the scene's [target] material.
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub target: Option<String>,
    /// The background material, replacing the scene's [background] material.
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub background: Option<String>,
    /// Grid steps over the hemisphere, DTHETA or DTHETA,DPHI in degrees (default 1,2).
    #[arg(long, value_name = "DTHETA[,DPHI]", conflicts_with_all = ["theta_deg", "phi_deg"])]
    pub grid_deg: Option<GridDeg>,
    /// Listed view zenith angle(s), degrees; with --phi-deg, every combination (no maps).
    #[arg(
        long,
        value_name = "DEG",
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = values::zenith()
    )]
    pub theta_deg: Vec<f64>,
    /// Listed view azimuth(s), degrees (default 0).
    #[arg(
        long,
        value_name = "DEG",
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = values::azimuth()
    )]
    pub phi_deg: Vec<f64>,
    /// Ranges (m) at which every view is evaluated (rows of detect.csv; the P_d map is at the
    /// first). Default 1000.
    #[arg(
        long,
        value_name = "M",
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = values::positive()
    )]
    pub ranges_m: Vec<f64>,
    /// Do not search each view's detection range.
    #[arg(long)]
    pub no_search: bool,
    /// The largest range searched, m.
    #[arg(
        long,
        value_name = "M",
        default_value_t = DetectRequest::default().range_limit_m,
        allow_negative_numbers = true,
        value_parser = values::positive()
    )]
    pub range_limit_m: f64,
    /// The target's area, m² (a flat patch).
    #[arg(
        long,
        value_name = "M2",
        default_value_t = DetectRequest::default().area_m2,
        allow_negative_numbers = true,
        value_parser = values::positive()
    )]
    pub area_m2: f64,
    /// False-alarm probability.
    #[arg(
        long,
        value_name = "P",
        default_value_t = DetectRequest::default().pfa,
        allow_negative_numbers = true,
        value_parser = values::probability()
    )]
    pub pfa: f64,
    /// Required probability of detection.
    #[arg(
        long,
        value_name = "P",
        default_value_t = DetectRequest::default().pd,
        allow_negative_numbers = true,
        value_parser = values::probability()
    )]
    pub pd: f64,
    /// Features the detector may use, comma-separated (default: all of them).
    #[arg(
        long,
        value_name = "LIST",
        value_delimiter = ',',
        value_parser = closed_set::parser(&Feature::ALL, Feature::as_str)
    )]
    pub features: Vec<Feature>,
    /// The sun's zenith and azimuth, degrees, replacing the scene's [sun] position.
    #[arg(long, value_name = "ZENITH,AZIMUTH", allow_hyphen_values = true,
          value_parser = values::pair(Range::ZENITH, Range::AZIMUTH, "ZENITH,AZIMUTH in degrees"))]
    pub sun_deg: Option<Pair>,
    /// The target material's fit (fit.json of `polbrdf fit`, of the target's material and its
    /// values): the detection range gets σ and a 95 % interval (docs/detection.md).
    #[arg(long, value_name = "FIT.json")]
    pub target_fit: Option<PathBuf>,
    /// The background material's fit, likewise (independent of the target's).
    #[arg(long, value_name = "FIT.json")]
    pub background_fit: Option<PathBuf>,
    /// With a fit: the best-ranked views given an interval, a number or `all` (default 10;
    /// each costs 2 range searches per free parameter).
    #[arg(long, value_name = "N|all", value_parser = view_count)]
    pub uncertainty_views: Option<ViewCount>,
    /// Also simulate the camera frame at the best view and the first range: frame.png/.svg
    /// and frame_*.npy (photon-counting DoFP sensors; docs/detection-frame.md).
    #[arg(long)]
    pub frame: bool,
    /// The seed of the simulated frame.
    #[arg(long, value_name = "N", default_value_t = 0, requires = "frame")]
    pub seed: u64,
    /// Output directory.
    #[arg(long, value_name = "DIR", default_value = "detect-out")]
    pub out: PathBuf,
}

/// `--uncertainty-views`: a number of views (`Some`) or `all` (`None`).
#[derive(Debug, Clone, Copy)]
pub struct ViewCount(pub Option<usize>);

/// The value parser of `--uncertainty-views` (a bad value exits 2, as every bad option value).
fn view_count(text: &str) -> Result<ViewCount, String> {
    match text.trim() {
        "all" => Ok(ViewCount(None)),
        t => t
            .parse::<usize>()
            .ok()
            .filter(|n| *n > 0)
            .map(|n| ViewCount(Some(n)))
            .ok_or_else(|| format!("{text:?}: expected a number of views ≥ 1 or `all`")),
    }
}

impl Args {
    fn request(&self) -> Result<DetectRequest, CliError> {
        let mut r = DetectRequest::new(
            SceneSource::File(self.scene.clone()),
            SensorSource::File(self.sensor.clone()),
        );
        if self.theta_deg.is_empty() {
            if !self.phi_deg.is_empty() {
                return Err(CliError::Usage("--phi-deg needs --theta-deg".into()));
            }
            if let Some(GridDeg(g)) = self.grid_deg {
                r.views = Views::Grid(g);
            }
        } else {
            crate::limits::at_most(
                "--theta-deg × --phi-deg",
                self.theta_deg.len() * self.phi_deg.len().max(1),
                1_000_000,
            )?;
            r.views = Views::listed(&self.theta_deg, &self.phi_deg);
        }
        if !self.features.is_empty() {
            r.features.clone_from(&self.features);
        }
        crate::limits::at_most("--ranges-m", self.ranges_m.len(), 1000)?;
        if !self.ranges_m.is_empty() {
            r.ranges_m.clone_from(&self.ranges_m);
        }
        r.target.clone_from(&self.target);
        r.background.clone_from(&self.background);
        r.search = !self.no_search;
        (r.range_limit_m, r.area_m2, r.pfa, r.pd) =
            (self.range_limit_m, self.area_m2, self.pfa, self.pd);
        r.sun_deg = self.sun_deg.map(|Pair(z, a)| (z, a));
        r.target_fit = self.target_fit.clone().map(FitSource::File);
        r.background_fit = self.background_fit.clone().map(FitSource::File);
        if let Some(ViewCount(n)) = self.uncertainty_views {
            r.uncertainty_views = n;
        }
        Ok(r)
    }
}

/// Runs `polbrdf detect`.
pub fn run(args: &Args) -> Result<(), CliError> {
    let request = args.request()?;
    let started = std::time::Instant::now();
    let study = detect(&request)?;
    let elapsed = started.elapsed();
    for w in &study.warnings {
        crate::note!("polbrdf detect: note: {w}");
    }
    let mut best = serde_json::to_string_pretty(&study.best_json()).expect("JSON of numbers");
    best.push('\n');
    let mut files: Vec<OutputFile> = vec![
        ("detect.csv".into(), study.csv()),
        ("best.json".into(), best.into_bytes()),
    ];
    figures(&mut files, &study)?;
    let frame = if args.frame {
        Some(crate::detect_frame::add(&mut files, &study, args.seed)?)
    } else {
        None
    };
    let paths = write_all(&args.out, &files)?;
    summary(&study, elapsed);
    if let Some(line) = frame {
        crate::note!("{line}");
    }
    crate::note!("Wrote {} files to {}", paths.len(), args.out.display());
    Ok(())
}

fn summary(study: &DetectStudy, elapsed: std::time::Duration) {
    crate::note!(
        "polbrdf detect: target {}, background {}, sensor {}; {} views in {:.0} ms",
        study.target.name,
        study.background.name,
        study.sensor.spec.name,
        study.views.len(),
        elapsed.as_secs_f64() * 1e3
    );
    for (k, v) in study.ranked().into_iter().take(5).enumerate() {
        crate::note!(
            "  {:>2}. θr = {:>6}°, φr = {:>7}°: max range {}{}{}",
            k + 1,
            short(v.theta_r.to_degrees()),
            short(v.phi_r.to_degrees()),
            match polbrdf_tasks::detect::out::max_range_text(v.max_range).as_str() {
                "" => "not searched".to_string(),
                t if t.parse::<f64>().is_ok() => format!("{} m", short(t.parse().unwrap_or(0.0))),
                t => t.to_string(),
            },
            match v.range_uncertainty {
                Some(RangeUncertainty::Interval {
                    sigma_m,
                    lo_m,
                    hi_m,
                }) => format!(
                    " ± {} m (95 %: {}–{} m)",
                    short(sigma_m),
                    short(lo_m),
                    short(hi_m)
                ),
                Some(RangeUncertainty::Undefined) => " (no interval: see best.json)".into(),
                None => String::new(),
            },
            if study.view_saturated(v) {
                " (saturated)"
            } else {
                ""
            }
        );
    }
    let saturated = study.saturated_views().len();
    if saturated > 0 {
        crate::note!(
            "  saturated: {saturated} of {} views (see the notes above)",
            study.views.len()
        );
    }
}

/// The polar maps (grid views only): the detection range (beyond the limit drawn at the limit;
/// not detectable: undefined grey) and P_d at the first row range.
fn figures(files: &mut Vec<OutputFile>, study: &DetectStudy) -> Result<(), CliError> {
    let Some(grid) = &study.grid else {
        return Ok(());
    };
    let limit = study.detector.criteria.range_limit_m;
    let mut figs = Vec::new();
    if study.views.iter().any(|v| v.max_range.is_some()) {
        let ranges: Vec<f64> = study
            .max_ranges()
            .into_iter()
            .map(|r| r.min(limit))
            .collect();
        // The scale ends at the longest range found (rounded up), not at the search limit, so
        // that the map resolves the ranges it has; a view beyond the limit lifts it to the limit.
        let top = polbrdf_plot::nice_ceil(
            ranges
                .iter()
                .copied()
                .filter(|r| r.is_finite())
                .fold(0.0, f64::max),
        );
        figs.push((
            "max_range",
            single(PolarPanel {
                title: format!(
                    "Detection range (P_d ≥ {}, P_fa = {}; grey: none)",
                    short(study.detector.criteria.pd_required),
                    study.detector.criteria.pfa
                ),
                grid: polar_grid(grid, ranges)?,
                scale: ColorScale::linear(Colormap::Viridis, 0.0, top.min(limit), "range (m)"),
                marks: Vec::new(),
            }),
        ));
    }
    if let Some(r) = study.views.first().and_then(|v| v.at_ranges.first()) {
        figs.push((
            "pd",
            single(PolarPanel {
                title: format!(
                    "P_d at {} m (P_fa = {})",
                    short(r.range_m),
                    study.detector.criteria.pfa
                ),
                grid: polar_grid(grid, study.pd_at(0))?,
                scale: ColorScale::linear(Colormap::Viridis, 0.0, 1.0, "P_d"),
                marks: Vec::new(),
            }),
        ));
    }
    render_all(files, &figs)
}
