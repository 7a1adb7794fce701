//! `polbrdf lut`: a lookup table over materials × wavelengths × in-plane geometries, written
//! as a `.npy` table plus an `attrs.json` sidecar (docs/scaling.md) — the table of the Python
//! `polbrdf.lut`, for users without Python; `polbrdf.xarray.open_lut(DIR)` opens it as the same
//! `xarray.Dataset`, memory-mapped.
//!
//! `DIR/table.npy`: one row per (material, wavelength, θi, θr, Δφ), in that C order, with the
//! columns of the quantities asked for — `m00 … m33` (F row-major, sr⁻¹, psps basis), `brdf`
//! (sr⁻¹), `dolp`, `aolp_deg` — the values of `polbrdf eval` at `φi = 0`, `φr = Δφ`, each
//! material evaluated with its index at each wavelength. `DIR/attrs.json`: the dimensions, the
//! coordinates, the columns and the attributes that pin the conventions (the same file the
//! Python package uses), the materials' parameters and the version.
//!
//! The directory is written as a temporary sibling and renamed into place at the end: a failed
//! run leaves nothing; an existing `DIR` is refused.

use crate::error::CliError;
use polbrdf::model::KeyValue;
use polbrdf::{Engine, GeometryBatch, MaterialSpec};
use polbrdf_io::lut::{LutConfig, Quantity};
use polbrdf_io::npy::NpyWriter;
use serde_json::{json, Map, Value};
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// The attributes that pin the conventions, shared with the Python package.
const CONVENTIONS: &str = include_str!("../../../python/polbrdf/lut_conventions.json");

/// Geometries per engine call.
const BLOCK: usize = 1 << 16;

/// The table's columns for the quantities (in their order).
fn columns(quantities: &[Quantity]) -> Vec<String> {
    let mut out = Vec::new();
    for q in quantities {
        match q {
            Quantity::Mueller => {
                for i in 0..4 {
                    for j in 0..4 {
                        out.push(format!("m{i}{j}"));
                    }
                }
            }
            Quantity::Brdf => out.push("brdf".into()),
            Quantity::Dolp => out.push("dolp".into()),
            Quantity::Aolp => out.push("aolp_deg".into()),
        }
    }
    out
}

/// A material's parameters as the Python `Material.to_dict()` gives them: every key, `null`
/// when unset; the index (`index`) or the constant `n`, `k`.
fn material_dict(spec: &MaterialSpec) -> Value {
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
fn sidecar(cfg: &LutConfig, columns: &[String]) -> Result<Value, CliError> {
    let mut attrs: Map<String, Value> = serde_json::from_str(CONVENTIONS)
        .map_err(|e| CliError::Invalid(format!("internal: lut_conventions.json: {e}")))?;
    attrs.insert("polbrdf_version".into(), json!(env!("CARGO_PKG_VERSION")));
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

/// Runs `polbrdf lut --config FILE --out DIR`.
pub fn run(config: &Path, out: &Path) -> Result<(), CliError> {
    let cfg = polbrdf_io::lut::read_lut_config(config)?;
    let write_err = |path: &Path, source: std::io::Error| {
        CliError::Io(polbrdf_io::Error::Write {
            path: path.to_path_buf(),
            source,
        })
    };
    if out.exists() {
        return Err(write_err(
            out,
            std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                "exists: polbrdf lut writes a new directory and never replaces one",
            ),
        ));
    }
    let parent = match out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let stem = out
        .file_name()
        .map_or_else(|| "lut".into(), |s| s.to_string_lossy().into_owned());
    let tmp = tempfile_dir(&parent, &stem).map_err(|e| write_err(out, e))?;
    let cols = columns(&cfg.quantities);
    let result = write_table(&cfg, &cols, &tmp.join("table.npy")).and_then(|()| {
        let doc = sidecar(&cfg, &cols)?;
        let text = serde_json::to_string_pretty(&doc)
            .map_err(|e| CliError::Invalid(format!("internal: attrs.json: {e}")))?;
        std::fs::write(tmp.join("attrs.json"), text + "\n")
            .map_err(|e| write_err(&out.join("attrs.json"), e))?;
        std::fs::rename(&tmp, out).map_err(|e| write_err(out, e))
    });
    if result.is_err() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    result
}

/// A new, empty directory next to the destination, `.polbrdf-<stem>.partial-<pid>-<n>`.
fn tempfile_dir(parent: &Path, stem: &str) -> std::io::Result<PathBuf> {
    let pid = std::process::id();
    let mut n = 0u32;
    loop {
        let p = parent.join(format!(".polbrdf-{stem}.partial-{pid}-{n}"));
        match std::fs::create_dir(&p) {
            Ok(()) => return Ok(p),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && n < 1000 => n += 1,
            Err(e) => return Err(e),
        }
    }
}

/// Streams the rows: per material and wavelength, blocks of [`BLOCK`] geometries, each one
/// engine call (with the index at the wavelength of every element, as the Python package
/// calls it, so that the values are the same bit for bit).
fn write_table(cfg: &LutConfig, cols: &[String], path: &Path) -> Result<(), CliError> {
    let io_err = |source: std::io::Error| {
        CliError::Io(polbrdf_io::Error::Write {
            path: path.to_path_buf(),
            source,
        })
    };
    let file = std::fs::File::create(path).map_err(io_err)?;
    let mut w = NpyWriter::new(BufWriter::with_capacity(1 << 22, file), cols, cfg.rows())
        .map_err(io_err)?;
    let (ni, nr, np) = (
        cfg.theta_i_deg.len(),
        cfg.theta_r_deg.len(),
        cfg.dphi_deg.len(),
    );
    let geometries = ni * nr * np;
    let width = cols.len();
    let has = |q: Quantity| cfg.quantities.contains(&q);
    let mut ti = vec![0.0; BLOCK];
    let mut tr = vec![0.0; BLOCK];
    let mut pr = vec![0.0; BLOCK];
    let pi = vec![0.0; BLOCK];
    let mut m = vec![[0.0; 16]; BLOCK];
    let (mut b, mut d, mut a) = (vec![0.0; BLOCK], vec![0.0; BLOCK], vec![0.0; BLOCK]);
    let mut rows = vec![0.0; BLOCK * width];
    for (_, spec) in &cfg.materials {
        // As the Python package builds it: a spectral index at the first wavelength of its
        // data (every evaluation takes the index at its own wavelength).
        let material = match spec.wavelength_range() {
            Some((lo, _)) => spec.build_at(lo),
            None => spec.build(),
        }?;
        for &l in &cfg.wavelength_um {
            let wl = vec![l; BLOCK];
            for start in (0..geometries).step_by(BLOCK) {
                let len = BLOCK.min(geometries - start);
                for k in 0..len {
                    let g = start + k;
                    let (i, r, p) = (g / (nr * np), (g / np) % nr, g % np);
                    ti[k] = cfg.theta_i_deg[i].to_radians();
                    tr[k] = cfg.theta_r_deg[r].to_radians();
                    pr[k] = cfg.dphi_deg[p].to_radians();
                }
                let batch = GeometryBatch::new(&ti[..len], &pi[..len], &tr[..len], &pr[..len])?;
                let engine = Engine::new(&material).with_wavelengths(&wl[..len])?;
                if has(Quantity::Mueller) {
                    engine.mueller_into(&batch, &mut m[..len])?;
                }
                if has(Quantity::Brdf) || has(Quantity::Dolp) || has(Quantity::Aolp) {
                    engine.brdf_dolp_aolp_into(
                        &batch,
                        &mut b[..len],
                        &mut d[..len],
                        &mut a[..len],
                    )?;
                }
                for k in 0..len {
                    let row = &mut rows[k * width..(k + 1) * width];
                    let mut c = 0;
                    for q in &cfg.quantities {
                        match q {
                            Quantity::Mueller => {
                                row[c..c + 16].copy_from_slice(&m[k]);
                                c += 16;
                            }
                            Quantity::Brdf => {
                                row[c] = b[k];
                                c += 1;
                            }
                            Quantity::Dolp => {
                                row[c] = d[k];
                                c += 1;
                            }
                            Quantity::Aolp => {
                                row[c] = a[k].to_degrees();
                                c += 1;
                            }
                        }
                    }
                }
                w.write_rows(&rows[..len * width]).map_err(io_err)?;
            }
        }
    }
    let file = w.finish().map_err(io_err)?;
    let file = file.into_inner().map_err(|e| io_err(e.into_error()))?;
    file.sync_all().map_err(io_err)?;
    Ok(())
}
