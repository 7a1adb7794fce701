//! Lookup tables (`polbrdf lut`, Python's `polbrdf.lut`; docs/scaling.md): the rows over
//! materials × wavelengths × in-plane geometries (θi, θr, Δφ = φr − φi) and the `attrs.json`
//! sidecar, with the attributes that pin the conventions ([`CONVENTIONS`], this crate's
//! `lut_conventions.json`, shared with the Python package).
//!
//! `DIR/table.npy`: one row per (material, wavelength, θi, θr, Δφ), in that C order, with the
//! columns of the quantities asked for — `m00 … m33` (F row-major, sr⁻¹, psps basis), `brdf`
//! (sr⁻¹), `dolp`, `aolp_deg` — the values of `polbrdf eval` at `φi = 0`, `φr = Δφ`, each
//! material evaluated with its index at each wavelength. The files are staged next to their
//! destination (`polbrdf_io::StagingDir`) and moved into place at the end as a set (with the
//! `_COMPLETE` marker last): a failed or killed run leaves nothing a later run does not remove;
//! in an existing `DIR` the set's files are replaced and every other file is left alone, as
//! every command's `--out DIR` does.

use crate::{TaskError, TaskResult};
use polbrdf::model::KeyValue;
use polbrdf::{Engine, GeometryBatch, Material, MaterialSpec};
use polbrdf_io::lut::{LutConfig, Quantity};
use polbrdf_io::npy::NpyWriter;
use serde_json::{json, Map, Value};
use std::io::BufWriter;
use std::path::Path;

/// The attributes that pin the conventions, shared with the Python package (which reads this
/// crate's copy: see the report of issue 33).
pub const CONVENTIONS: &str = include_str!("../lut_conventions.json");

/// The version written into `attrs.json`.
const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Geometries per engine call.
const BLOCK: usize = 1 << 16;

/// The table's columns for the quantities (in their order).
pub fn columns(quantities: &[Quantity]) -> Vec<String> {
    let mut out = Vec::new();
    for q in quantities {
        match q {
            Quantity::Mueller => out.extend(polbrdf::Mueller::COLUMNS.map(String::from)),
            Quantity::Brdf => out.push("brdf".into()),
            Quantity::Dolp => out.push("dolp".into()),
            Quantity::Aolp => out.push("aolp_deg".into()),
        }
    }
    out
}

/// A material's parameters as the Python `Material.to_dict()` gives them: every key, `null`
/// when unset; the index (`index`) or the constant `n`, `k`.
pub fn material_dict(spec: &MaterialSpec) -> Value {
    let mut d = Map::new();
    for key in polbrdf::model::KEYS {
        let omitted = match *key {
            "index" => !spec.is_spectral(),
            "n" | "k" => spec.is_spectral(),
            _ => false,
        };
        if omitted {
            continue;
        }
        let v = match spec.get(key) {
            Some(KeyValue::Number(x)) => json!(x),
            Some(KeyValue::Text(t)) => json!(t),
            Some(KeyValue::Bool(b)) => json!(b),
            None => Value::Null,
        };
        d.insert((*key).to_string(), v);
    }
    Value::Object(d)
}

/// The `attrs.json` document.
pub fn sidecar(cfg: &LutConfig, columns: &[String]) -> TaskResult<Value> {
    let mut attrs: Map<String, Value> =
        serde_json::from_str(CONVENTIONS).expect("lut_conventions.json is a JSON object (tested)");
    attrs.insert("polbrdf_version".into(), json!(VERSION));
    let materials: Map<String, Value> = cfg
        .materials
        .iter()
        .map(|(n, s)| (n.clone(), material_dict(s)))
        .collect();
    attrs.insert(
        "materials_json".into(),
        json!(Value::Object(materials).to_string()),
    );
    Ok(json!({
        "format": "polbrdf-lut 1",
        "table": "table.npy",
        "dims": ["material", "wavelength", "theta_i", "theta_r", "dphi"],
        "shape": [cfg.materials.len(), cfg.wavelength_um.len(), cfg.theta_i_deg.len(),
                  cfg.theta_r_deg.len(), cfg.dphi_deg.len()],
        "columns": columns,
        "quantities": cfg.quantities.iter().map(|q| q.name()).collect::<Vec<_>>(),
        "coords": {
            "material": cfg.materials.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(),
            "wavelength": cfg.wavelength_um,
            "theta_i": cfg.theta_i_deg,
            "theta_r": cfg.theta_r_deg,
            "dphi": cfg.dphi_deg,
        },
        "attrs": attrs,
    }))
}

/// The in-plane geometry axes of a table, degrees: `θi`, `θr`, `Δφ = φr − φi`.
#[derive(Debug, Clone, Copy)]
pub struct Axes<'a> {
    /// Zenith of the direction to the source.
    pub theta_i_deg: &'a [f64],
    /// Zenith of the direction to the detector.
    pub theta_r_deg: &'a [f64],
    /// Azimuth difference.
    pub dphi_deg: &'a [f64],
}

impl Axes<'_> {
    /// Geometries of the grid.
    pub fn len(&self) -> usize {
        self.theta_i_deg.len() * self.theta_r_deg.len() * self.dphi_deg.len()
    }

    /// Whether the grid is empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The rows of one material (`polbrdf lut`'s table for that material, and Python's
/// `polbrdf.xarray.lut` block): per wavelength, the geometries of `axes` in C order
/// (θi, θr, Δφ), in blocks of at most `BLOCK` rows handed to `sink` (row-major, the columns
/// of [`columns`]). Each block is one engine call with the index at the wavelength of every
/// element, so the CLI and Python give the same values bit for bit.
///
/// # Errors
/// [`TaskError::Model`] for a geometry or wavelength the engine refuses; what `sink` returns.
pub fn material_rows(
    material: &Material,
    wavelength_um: &[f64],
    axes: Axes<'_>,
    quantities: &[Quantity],
    mut sink: impl FnMut(&[f64]) -> TaskResult<()>,
) -> TaskResult<()> {
    let (nr, np) = (axes.theta_r_deg.len(), axes.dphi_deg.len());
    let geometries = axes.len();
    let width = columns(quantities).len();
    let block = BLOCK.min(geometries.max(1));
    let has = |q: Quantity| quantities.contains(&q);
    let (mut ti, mut tr, mut pr) = (vec![0.0; block], vec![0.0; block], vec![0.0; block]);
    let pi = vec![0.0; block];
    let mut m = vec![[0.0; 16]; block];
    let (mut b, mut d, mut a) = (vec![0.0; block], vec![0.0; block], vec![0.0; block]);
    let mut rows = vec![0.0; block * width];
    for &l in wavelength_um {
        let wl = vec![l; block];
        for start in (0..geometries).step_by(block) {
            let len = block.min(geometries - start);
            for k in 0..len {
                let g = start + k;
                let (i, r, p) = (g / (nr * np), (g / np) % nr, g % np);
                ti[k] = axes.theta_i_deg[i].to_radians();
                tr[k] = axes.theta_r_deg[r].to_radians();
                pr[k] = axes.dphi_deg[p].to_radians();
            }
            let batch = GeometryBatch::new(&ti[..len], &pi[..len], &tr[..len], &pr[..len])?;
            let engine = Engine::new(material).with_wavelengths(&wl[..len])?;
            if has(Quantity::Mueller) {
                engine.mueller_into(&batch, &mut m[..len])?;
            }
            if has(Quantity::Brdf) || has(Quantity::Dolp) || has(Quantity::Aolp) {
                engine.brdf_dolp_aolp_into(&batch, &mut b[..len], &mut d[..len], &mut a[..len])?;
            }
            for k in 0..len {
                let row = &mut rows[k * width..(k + 1) * width];
                let mut c = 0;
                for q in quantities {
                    if *q == Quantity::Mueller {
                        row[c..c + 16].copy_from_slice(&m[k]);
                        c += 16;
                        continue;
                    }
                    row[c] = match q {
                        Quantity::Brdf => b[k],
                        Quantity::Dolp => d[k],
                        _ => a[k].to_degrees(),
                    };
                    c += 1;
                }
            }
            sink(&rows[..len * width])?;
        }
    }
    Ok(())
}

/// Streams the rows of every material of `cfg` ([`material_rows`]) into `path`, calling
/// `progress(rows written, rows)` after each block.
fn write_table(
    cfg: &LutConfig,
    cols: &[String],
    path: &Path,
    progress: &mut dyn FnMut(u64, u64),
) -> TaskResult<()> {
    let io_err = |source: std::io::Error| {
        TaskError::Io(polbrdf_io::Error::Write {
            path: path.to_path_buf(),
            source,
        })
    };
    let file = std::fs::File::create(path).map_err(io_err)?;
    let mut w = NpyWriter::new(BufWriter::with_capacity(1 << 22, file), cols, cfg.rows())
        .map_err(io_err)?;
    let axes = Axes {
        theta_i_deg: &cfg.theta_i_deg,
        theta_r_deg: &cfg.theta_r_deg,
        dphi_deg: &cfg.dphi_deg,
    };
    let (mut done, total) = (0, cfg.rows());
    for (_, spec) in &cfg.materials {
        // As the Python package builds it: a spectral index at the first wavelength of its
        // data (every evaluation takes the index at its own wavelength).
        let material = match spec.wavelength_range() {
            Some((lo, _)) => spec.build_at(lo),
            None => spec.build(),
        }?;
        material_rows(
            &material,
            &cfg.wavelength_um,
            axes,
            &cfg.quantities,
            |rows| {
                w.write_rows(rows).map_err(io_err)?;
                done += (rows.len() / cols.len()) as u64;
                progress(done, total);
                Ok(())
            },
        )?;
    }
    let file = w.finish().map_err(io_err)?;
    let file = file.into_inner().map_err(|e| io_err(e.into_error()))?;
    file.sync_all().map_err(io_err)?;
    Ok(())
}

/// Writes the lookup table of `cfg` as the new directory `out`: `table.npy` and `attrs.json`.
///
/// # Errors
/// [`TaskError::Io`] naming the file (an existing `out` is refused); [`TaskError::Model`] for
/// a material the engine refuses.
pub fn write_lut(cfg: &LutConfig, out: &Path) -> TaskResult<()> {
    write_lut_with_progress(cfg, out, &mut |_, _| {})
}

/// [`write_lut`], calling `progress(rows written, rows)` after each block of rows (for a
/// progress bar: the adapters draw it).
///
/// # Errors
/// As [`write_lut`].
pub fn write_lut_with_progress(
    cfg: &LutConfig,
    out: &Path,
    progress: &mut dyn FnMut(u64, u64),
) -> TaskResult<()> {
    let stage = polbrdf_io::StagingDir::create(out)?;
    let cols = columns(&cfg.quantities);
    write_table(cfg, &cols, &stage.path().join("table.npy"), progress)?;
    let doc = sidecar(cfg, &cols)?;
    let text = serde_json::to_string_pretty(&doc).expect("JSON of finite values");
    std::fs::write(stage.path().join("attrs.json"), text + "\n").map_err(|source| {
        polbrdf_io::Error::Write {
            path: out.join("attrs.json"),
            source,
        }
    })?;
    Ok(stage.commit()?)
}
