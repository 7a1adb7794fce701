//! Spectral setup shared by every job that evaluates materials: one wavelength or a band (with
//! its quadrature step), materials loaded from a file or a preset with a display name, and the
//! materials built at the spectrum's nodes with the weights of its mean (docs/model.md §15).

use crate::error::{TaskError, TaskResult};
use polbrdf::{Band, Material, MaterialSpec, Spectrum};
use std::path::{Path, PathBuf};

/// At what wavelength(s) a job evaluates its materials: `wavelength_um` or a `band` (a CSV of
/// wavelength_um,response) with an optional quadrature step, or neither (constant-index
/// materials only).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SpectralRequest {
    /// One wavelength, µm (finite, > 0). Excludes `band`.
    pub wavelength_um: Option<f64>,
    /// A band file (columns wavelength_um,response).
    pub band: Option<PathBuf>,
    /// The band's largest quadrature step, µm (finite, > 0; default 1/16 of its width).
    pub band_step_um: Option<f64>,
}

impl SpectralRequest {
    /// One wavelength.
    pub fn wavelength(wavelength_um: f64) -> Self {
        Self {
            wavelength_um: Some(wavelength_um),
            ..Self::default()
        }
    }

    /// The validated spectrum; `None` when neither a wavelength nor a band is given. The band
    /// file is read (after the numbers are checked).
    ///
    /// # Errors
    /// [`TaskError::Invalid`] (`wavelength_um`, `band_step_um`), [`TaskError::Usage`] for a
    /// wavelength and a band together, [`TaskError::Io`] for the band file.
    pub fn spectrum(&self) -> TaskResult<Option<Spectrum>> {
        spectrum_of(
            self.wavelength_um,
            self.band
                .as_ref()
                .map(|p| move || polbrdf_io::read_band_csv(p)),
            self.band_step_um,
        )
    }
}

/// Where a job's spectrum comes from: a [`SpectralRequest`] (a band file) or a
/// [`SpectralText`] (a band file's text).
pub trait SpectrumSource {
    /// The validated spectrum; `None` when neither a wavelength nor a band is given.
    ///
    /// # Errors
    /// As [`SpectralRequest::spectrum`].
    fn spectrum(&self) -> TaskResult<Option<Spectrum>>;
}

impl SpectrumSource for SpectralRequest {
    fn spectrum(&self) -> TaskResult<Option<Spectrum>> {
        SpectralRequest::spectrum(self)
    }
}

/// A [`SpectralRequest`] whose band is the text of a band file rather than its path: for an
/// adapter without files (the web explorer). The same checks and messages, the band file's
/// named by its name here.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SpectralText {
    /// One wavelength, µm (finite, > 0). Excludes `band`.
    pub wavelength_um: Option<f64>,
    /// A band file (columns wavelength_um,response): its name (in messages) and its text.
    pub band: Option<(String, String)>,
    /// The band's largest quadrature step, µm (finite, > 0; default 1/16 of its width).
    pub band_step_um: Option<f64>,
}

impl SpectrumSource for SpectralText {
    fn spectrum(&self) -> TaskResult<Option<Spectrum>> {
        spectrum_of(
            self.wavelength_um,
            self.band.as_ref().map(|(name, text)| {
                move || polbrdf_io::parse_band_csv(text.as_bytes(), Path::new(name))
            }),
            self.band_step_um,
        )
    }
}

/// The spectrum of a wavelength or a band (read by `band` after the numbers are checked) with
/// its quadrature step.
fn spectrum_of(
    wavelength_um: Option<f64>,
    band: Option<impl FnOnce() -> polbrdf_io::Result<Band>>,
    band_step_um: Option<f64>,
) -> TaskResult<Option<Spectrum>> {
    if wavelength_um.is_some() && band.is_some() {
        return Err(TaskError::usage(
            "wavelength_um",
            "give one wavelength or a band, not both",
        ));
    }
    if let Some(l) = wavelength_um {
        if !(l.is_finite() && l > 0.0) {
            return Err(TaskError::invalid(
                "wavelength_um",
                format!("{l}: must be finite and > 0 (µm)"),
            ));
        }
        return Ok(Some(Spectrum::Wavelength(l)));
    }
    let Some(band) = band else {
        return Ok(None);
    };
    if let Some(s) = band_step_um {
        if !(s.is_finite() && s > 0.0) {
            return Err(TaskError::invalid(
                "band_step_um",
                format!("{s}: must be finite and > 0 (µm)"),
            ));
        }
    }
    let band = band()?;
    if let Some(s) = band_step_um {
        band.check_step(s)
            .map_err(|e| TaskError::invalid("band_step_um", e.to_string()))?;
    }
    Ok(Some(Spectrum::Band(band, band_step_um)))
}

/// The spectrum in words (` at λ = 0.55 µm`, ` over the band NAME (8–12 µm)`; empty for none),
/// for summaries and titles.
pub fn describe(spectrum: Option<&Spectrum>) -> String {
    match spectrum {
        None => String::new(),
        Some(Spectrum::Wavelength(l)) => format!(" at λ = {l} µm"),
        Some(Spectrum::Band(b, _)) => {
            let (lo, hi) = b.range();
            format!(" over the band {} ({lo}–{hi} µm)", b.name())
        }
    }
}

/// The spectrum as JSON (`best.json`'s `spectrum`): `null`, `{"wavelength_um"}`, or the band's
/// name, range, step and number of quadrature `nodes`.
pub fn spectrum_json(spectrum: Option<&Spectrum>, nodes: usize) -> serde_json::Value {
    match spectrum {
        None => serde_json::Value::Null,
        Some(Spectrum::Wavelength(l)) => serde_json::json!({"wavelength_um": l}),
        Some(Spectrum::Band(b, step)) => {
            let (lo, hi) = b.range();
            serde_json::json!({"band": b.name(), "range_um": [lo, hi],
                "step_um": step.unwrap_or_else(|| b.default_step()), "nodes": nodes,
                "integrated": "Stokes vectors, response-weighted mean"})
        }
    }
}

/// A material named by a request: its spec, its display name and what the request gave.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedMaterial {
    /// The material.
    pub spec: MaterialSpec,
    /// The display name: the material's `name` key, else the preset name or the file stem.
    pub name: String,
    /// What the request gave (a file or a preset name), or the scene's material name.
    pub source: String,
    /// The request field it came from (for messages).
    pub field: String,
}

impl NamedMaterial {
    /// Loads a material file or preset `arg` given as the request field `field`.
    ///
    /// # Errors
    /// [`TaskError::Invalid`] naming `field` for a malformed file or an unknown preset;
    /// [`TaskError::Io`] when the file cannot be read.
    pub fn load(arg: &str, field: &str) -> TaskResult<Self> {
        Self::named(polbrdf_io::load_material(arg), arg, field)
    }

    /// Parses the text of a material file named `file_name` (in error messages, and the stem
    /// is the display name without a `name` key), given as the request field `field`: for an
    /// adapter holding a material's text rather than a file (the web explorer). The messages
    /// are those of the file reader (`polbrdf_io::parse_material`).
    ///
    /// # Errors
    /// [`TaskError::Invalid`] naming `field` for malformed text; [`TaskError::Io`] when a
    /// refractive-index file it names cannot be read.
    pub fn parse(text: &str, file_name: &str, field: &str) -> TaskResult<Self> {
        Self::named(
            polbrdf_io::parse_material(text, Path::new(file_name)),
            file_name,
            field,
        )
    }

    /// The material `read` from `source` (a file, preset or file name) for the request field
    /// `field`: a malformed material names the field, a file that cannot be read is an I/O
    /// error; the display name is the `name` key, else the stem of `source`.
    fn named(
        read: polbrdf_io::Result<MaterialSpec>,
        source: &str,
        field: &str,
    ) -> TaskResult<Self> {
        let spec = read.map_err(|e| {
            if e.is_data_error() {
                TaskError::invalid(field, e.to_string())
            } else {
                TaskError::Io(e)
            }
        })?;
        let name = spec.name.clone().unwrap_or_else(|| {
            Path::new(source)
                .file_stem()
                .map_or_else(|| source.to_string(), |s| s.to_string_lossy().into_owned())
        });
        Ok(Self {
            spec,
            name,
            source: source.to_string(),
            field: field.to_string(),
        })
    }

    fn error(&self, e: &polbrdf::Error) -> TaskError {
        TaskError::invalid(&self.field, format!("{}: {e}", self.source))
    }
}

/// The materials at each spectral node: `(weight, [one material per entry of materials])`
/// with the weights of the spectrum's mean (one node of weight 1 for a wavelength, and for
/// constant-index materials without a spectrum).
///
/// # Errors
/// [`TaskError::Invalid`] naming the material's field: a spectral material without a spectrum,
/// a wavelength outside its data, parameters the model refuses.
pub fn materials_at(
    materials: &[&NamedMaterial],
    spectrum: Option<&Spectrum>,
) -> TaskResult<Vec<(f64, Vec<Material>)>> {
    let Some(spectrum) = spectrum else {
        let ms = materials
            .iter()
            .map(|m| {
                if m.spec.is_spectral() {
                    let (lo, hi) = m.spec.wavelength_range().unwrap_or((f64::NAN, f64::NAN));
                    Err(TaskError::invalid(
                        &m.field,
                        format!(
                            "{}: the material has a spectral index ({lo}–{hi} µm): give \
                             `wavelength_um` or `band`",
                            m.source
                        ),
                    ))
                } else {
                    m.spec.build().map_err(|e| m.error(&e))
                }
            })
            .collect::<TaskResult<Vec<_>>>()?;
        return Ok(vec![(1.0, ms)]);
    };
    let plain: Vec<&MaterialSpec> = materials.iter().map(|m| &m.spec).collect();
    let nodes = spectrum.mean_nodes(&plain);
    let per_material = materials
        .iter()
        .map(|m| Spectrum::materials(&m.spec, &nodes).map_err(|e| m.error(&e)))
        .collect::<TaskResult<Vec<_>>>()?;
    Ok(nodes
        .iter()
        .enumerate()
        .map(|(j, (_, w))| (*w, per_material.iter().map(|ms| ms[j].clone()).collect()))
        .collect())
}

/// One material at each spectral node: `(weight, material)`.
///
/// # Errors
/// As [`materials_at`].
pub fn material_at(
    material: &NamedMaterial,
    spectrum: Option<&Spectrum>,
) -> TaskResult<Vec<(f64, Material)>> {
    Ok(materials_at(&[material], spectrum)?
        .into_iter()
        .map(|(w, mut ms)| (w, ms.remove(0)))
        .collect())
}
