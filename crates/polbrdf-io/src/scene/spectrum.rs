//! The spectrum of a scene file: one wavelength (`wavelength_um`) or a band (`[band]`).

use crate::csv_io::{parse_band_csv, read_band_csv, show};
use crate::error::{Error, Result};
use crate::toml_doc::TomlDoc;
use polbrdf::Spectrum;

/// `wavelength_um` or `[band]`: exactly one of them.
pub(super) fn spectrum(doc: &TomlDoc<'_>) -> Result<Spectrum> {
    match (doc.number("wavelength_um"), doc.has("band")) {
        (Some(_), true) => Err(doc.error(
            "wavelength_um",
            format!(
                "give either `wavelength_um` (one wavelength) or a [band] table (line {}), not \
                 both",
                doc.line("band")
            ),
        )),
        (None, false) => Err(Error::File {
            path: doc.path().to_path_buf(),
            message: "no spectrum: give `wavelength_um` (one wavelength, µm) or a [band] table \
                      with response = \"FILE.csv\" (a band CSV file)"
                .into(),
        }),
        (Some(l), false) => {
            if !(l.is_finite() && l > 0.0) {
                return Err(doc.error(
                    "wavelength_um",
                    format!("{}: a wavelength must be finite and > 0 (µm)", show(l)),
                ));
            }
            Ok(Spectrum::Wavelength(l))
        }
        (None, true) => {
            let step = doc.number("band.step_um");
            if let Some(s) = step {
                if !(s.is_finite() && s > 0.0) {
                    return Err(doc.error(
                        "band.step_um",
                        format!("{}: a quadrature step must be finite and > 0 (µm)", show(s)),
                    ));
                }
            }
            let band = doc
                .read_file_or_text("band.response", read_band_csv, parse_band_csv)?
                .ok_or_else(|| {
                    doc.error(
                    "band",
                    "missing required key `response` (the path of a band CSV file with columns \
                     wavelength_um,response)",
                )
                })?;
            if let Some(s) = step {
                band.check_step(s).map_err(|e| {
                    // The core names the option `band_step_um`; here the key is `step_um`.
                    let (lo, hi) = band.range();
                    let why = match e {
                        polbrdf::Error::InvalidParameter { reason, .. } => reason.to_string(),
                        other => other.to_string(),
                    };
                    doc.error(
                        "band.step_um",
                        format!("{s:?}: {why} (the band spans {lo}–{hi} µm)"),
                    )
                })?;
            }
            Ok(Spectrum::Band(band, step))
        }
    }
}
