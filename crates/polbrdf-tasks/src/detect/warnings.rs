//! The setup warnings of a detection study (valid, but probably not what was meant), as
//! values the adapters show: the scene's checks judged over the sensor's band, the materials'
//! unit checks, a scene whose own wavelength or band lies outside the sensor's band, and
//! views where the camera saturates (docs/detection.md, "Warnings").

use super::study::{DetectStudy, ViewResult};
use crate::scene::{contrast_warnings_over, material_warnings, Warning};
use polbrdf::analysis::detection::MaxRange;
use polbrdf::Spectrum;

/// The spectrum's range, µm (a wavelength: that wavelength twice).
fn range(spectrum: &Spectrum) -> (f64, f64) {
    match spectrum {
        Spectrum::Wavelength(l) => (*l, *l),
        Spectrum::Band(b, _) => b.range(),
    }
}

/// The spectrum in words for a warning.
fn words(spectrum: &Spectrum) -> String {
    match spectrum {
        Spectrum::Wavelength(l) => format!("wavelength_um = {l}"),
        Spectrum::Band(b, _) => {
            let (lo, hi) = b.range();
            format!("its [band] ({lo}–{hi} µm)")
        }
    }
}

/// The scene's own spectrum against the sensor's band: `detect` observes over the sensor's
/// band and uses the scene's spectral radiances (sun, sky, `[path]` horizon radiance) as
/// given, so a scene written for another part of the spectrum (its wavelength, or its band's
/// centre, outside the sensor's band) is probably the wrong scene for this sensor.
fn band_mismatch(study: &DetectStudy) -> Option<Warning> {
    let (slo, shi) = range(&study.scene.spectrum);
    let (lo, hi) = range(&study.spectrum);
    let centre = 0.5 * (slo + shi);
    (centre < lo || centre > hi).then(|| Warning {
        message: format!(
            "{}: the scene is written for {}, outside the band of the sensor {} ({lo}–{hi} µm): \
             detect observes over the sensor's band and takes the scene's sun, sky and path \
             radiances as given (spectral radiances for the scene's wavelengths); give a scene \
             for the sensor's band",
            study.scene.path.display(),
            words(&study.scene.spectrum),
            study.sensor.path.display(),
        ),
    })
}

impl DetectStudy {
    /// Whether a channel of the target or the background saturates at the view: at any of its
    /// rows' ranges or at its detection range (the range limit when beyond it or not
    /// detectable). Saturation is flagged, never clipped (docs/detection.md).
    pub fn view_saturated(&self, view: &ViewResult) -> bool {
        if view.at_ranges.iter().any(|d| d.saturated) {
            return true;
        }
        let r = match view.max_range {
            None => return false,
            Some(MaxRange::At { range_m, .. }) => range_m,
            Some(_) => self.detector.criteria.range_limit_m,
        };
        self.detector
            .detect(&view.target, &view.background, view.theta_r, r)
            .is_ok_and(|d| d.saturated)
    }

    /// The views where the camera saturates ([`DetectStudy::view_saturated`]).
    pub fn saturated_views(&self) -> Vec<&ViewResult> {
        self.views
            .iter()
            .filter(|v| self.view_saturated(v))
            .collect()
    }
}

/// A warning when the camera saturates at some views, naming the first.
fn saturation(study: &DetectStudy) -> Option<Warning> {
    let views = study.saturated_views();
    let first = views.first()?;
    Some(Warning {
        message: format!(
            "{}: a channel saturates (beyond full_well_e) at {} of {} views (the first at θr = \
             {:.1}°, φr = {:.1}°): d′ and P_d there assume a linear response the camera does \
             not have (the `saturated` column of detect.csv, `saturated` in best.json); a \
             shorter integration_time_ms or a larger f_number avoids it",
            study.sensor.path.display(),
            views.len(),
            study.views.len(),
            first.theta_r.to_degrees(),
            first.phi_r.to_degrees(),
        ),
    })
}

/// The setup warnings of a study that do not depend on its views: the same at every time of a
/// day's sweep.
pub(crate) fn setup_warnings(study: &DetectStudy) -> Vec<Warning> {
    let mut w = contrast_warnings_over(&study.scene, &study.spectrum);
    w.extend(material_warnings(&study.target));
    w.extend(material_warnings(&study.background));
    w.extend(band_mismatch(study));
    w
}

/// Every setup warning of a study.
pub(crate) fn warnings(study: &DetectStudy) -> Vec<Warning> {
    let mut w = setup_warnings(study);
    w.extend(saturation(study));
    w
}
