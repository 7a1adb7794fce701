//! Mitsuba 3 `measured_polarized` tables (`.pbsdf`; docs/model.md §20) on top of
//! [`crate::tensorfile`]: the fields `phi_d`, `theta_d`, `theta_h` (float32, shape `[1, n]`,
//! radians, strictly increasing), `wvls` (uint16, nm) and `M` (float32, shape
//! `[n_phi_d, n_theta_d, n_theta_h, n_wvls, 4, 4]`, the pBRDF in the plane-of-reflection frame,
//! without the cosine factor), checked as the plugin checks them.

use crate::error::{Error, Result};
use crate::tensorfile::{write_tensor_file, Dtype, FieldData, TensorFile};
use std::io::Write;
use std::path::Path;

/// Nodes of an axis, and bands, a table may have: reading the axes costs memory in proportion
/// to what the header claims (12 bytes a node), so the claim is bounded before anything is
/// read. Far above any measured table (the KAIST tables have 361 × 91 × 91 nodes, 5 bands).
pub const MAX_NODES: u64 = 1 << 16;

/// Cells of a slab written per call of the producer of [`write_pbsdf`]: the writer's memory is
/// bounded by this, not by the grid.
pub const CELL_BLOCK: usize = 1 << 14;

/// An open `.pbsdf` table: its axes; the matrices are read on demand (one cell or one φ_d
/// slab at a time).
#[derive(Debug)]
pub struct PbsdfTable {
    file: TensorFile,
    /// φ_d nodes (rad).
    pub phi_d: Vec<f64>,
    /// θ_d nodes (rad).
    pub theta_d: Vec<f64>,
    /// θ_h nodes (rad).
    pub theta_h: Vec<f64>,
    /// Band wavelengths (nm).
    pub wavelengths_nm: Vec<u16>,
}

fn field_err(path: &Path, field: &str, message: String) -> Error {
    Error::File {
        path: path.to_path_buf(),
        message: format!("TensorFile field `{field}`: {message}"),
    }
}

impl PbsdfTable {
    /// Opens and validates a `.pbsdf` file (header, the five fields, their dtypes and
    /// consistent shapes, axes finite and strictly increasing); reads only the axes.
    ///
    /// # Errors
    /// [`Error::Read`] or [`Error::File`] naming the file and field.
    pub fn open(path: &Path) -> Result<Self> {
        let mut file = TensorFile::open(path)?;
        let mut axis = |name: &str, lo: f64, hi: f64| -> Result<Vec<f64>> {
            file.expect_dtype(name, Dtype::F32)?;
            let f = file.field(name)?;
            if f.shape.len() != 2 || f.shape[0] != 1 || f.shape[1] == 0 {
                return Err(field_err(
                    path,
                    name,
                    format!("shape {:?} where [1, n ≥ 1] is required", f.shape),
                ));
            }
            if f.shape[1] > MAX_NODES {
                return Err(field_err(
                    path,
                    name,
                    format!("{} nodes: at most {MAX_NODES} are read", f.shape[1]),
                ));
            }
            let n = f.shape[1] as usize;
            let v = file.read_f32(name, 0, n)?;
            for (i, &x) in v.iter().enumerate() {
                if !x.is_finite() || x < lo - 1e-6 || x > hi + 1e-6 {
                    return Err(field_err(
                        path,
                        name,
                        format!("node {i} = {x} is outside [{lo}, {hi}] rad"),
                    ));
                }
                if i > 0 && x <= v[i - 1] {
                    return Err(field_err(
                        path,
                        name,
                        format!("node {i} = {x} does not increase"),
                    ));
                }
            }
            Ok(v)
        };
        let pi = std::f64::consts::PI;
        let phi_d = axis("phi_d", -pi, pi)?;
        let theta_d = axis("theta_d", 0.0, pi / 2.0)?;
        let theta_h = axis("theta_h", 0.0, pi / 2.0)?;
        let w = file.field("wvls")?;
        if w.shape.len() != 1 || w.shape[0] == 0 || w.shape[0] > MAX_NODES {
            return Err(field_err(
                path,
                "wvls",
                format!(
                    "shape {:?} where [n] with 1 ≤ n ≤ {MAX_NODES} is required",
                    w.shape
                ),
            ));
        }
        let wavelengths_nm = file.read_u16_all("wvls")?;
        file.expect_dtype("M", Dtype::F32)?;
        let m = file.field("M")?;
        let want = vec![
            phi_d.len() as u64,
            theta_d.len() as u64,
            theta_h.len() as u64,
            wavelengths_nm.len() as u64,
            4,
            4,
        ];
        if m.shape != want {
            return Err(field_err(
                path,
                "M",
                format!("shape {:?} is inconsistent with the axes: [phi_d, theta_d, theta_h, wvls, 4, 4] = {:?}", m.shape, want),
            ));
        }
        Ok(Self {
            file,
            phi_d,
            theta_d,
            theta_h,
            wavelengths_nm,
        })
    }

    /// The file.
    pub fn path(&self) -> &Path {
        self.file.path()
    }

    /// Values per φ_d slab: `n_theta_d × n_theta_h × n_wvls × 16`.
    pub fn slab_len(&self) -> usize {
        self.theta_d.len() * self.theta_h.len() * self.wavelengths_nm.len() * 16
    }

    /// Reads the slab of φ_d node `p` (C order `[theta_d, theta_h, wvls, 4, 4]`) into `out`: the
    /// whole slab in memory (a caller that needs a few cells reads them by [`Self::read_cell`]).
    ///
    /// # Errors
    /// [`Error::Read`].
    pub fn read_slab(&mut self, p: usize, out: &mut Vec<f32>) -> Result<()> {
        let n = self.slab_len();
        let mut b = vec![0u8; n * 4];
        self.file.read_bytes("M", (p * n) as u64, &mut b)?;
        out.clear();
        out.extend(
            b.chunks_exact(4)
                .map(|c| f32::from_le_bytes(c.try_into().expect("4 bytes"))),
        );
        Ok(())
    }

    /// Reads the 16 entries (row-major, plane-of-reflection frame) of cell `(p, d, h)` at band
    /// `band`: 64 bytes, whatever the table's size.
    ///
    /// # Errors
    /// [`Error::Read`]; [`Error::File`] when the cell is outside the table.
    pub fn read_cell(&mut self, p: usize, d: usize, h: usize, band: usize) -> Result<[f32; 16]> {
        let (nd, nh, nb) = (
            self.theta_d.len(),
            self.theta_h.len(),
            self.wavelengths_nm.len(),
        );
        if p >= self.phi_d.len() || d >= nd || h >= nh || band >= nb {
            return Err(field_err(
                self.file.path(),
                "M",
                format!("cell ({p}, {d}, {h}) band {band} is outside the table"),
            ));
        }
        let at = ((((p * nd + d) * nh + h) * nb + band) * 16) as u64;
        let mut b = [0u8; 64];
        self.file.read_bytes("M", at, &mut b)?;
        Ok(std::array::from_fn(|k| {
            f32::from_le_bytes(b[4 * k..4 * k + 4].try_into().expect("4 bytes"))
        }))
    }
}

/// Writes a `.pbsdf` table through the output layer ([`crate::Output`]): the axes, then
/// `cells(p, range)`, which returns the cells `range` (indices `d · n_theta_h + h`) of the slab
/// of φ_d node `p` (C order `[cell, wvls, 4, 4]`), streamed in blocks of at most
/// [`CELL_BLOCK`] cells.
///
/// # Errors
/// As [`crate::Output::create`]; [`Error::Write`]; an error of `cells` aborts the write and is
/// returned.
pub fn write_pbsdf<E: std::fmt::Display>(
    path: &Path,
    phi_d: &[f64],
    theta_d: &[f64],
    theta_h: &[f64],
    wavelengths_nm: &[u16],
    mut cells: impl FnMut(usize, std::ops::Range<usize>) -> std::result::Result<Vec<f32>, E>,
) -> Result<()> {
    let f32s =
        |v: &[f64]| -> Vec<u8> { v.iter().flat_map(|&x| (x as f32).to_le_bytes()).collect() };
    let axis = |name: &'static str, v: &[f64]| {
        let bytes = f32s(v);
        FieldData {
            name,
            dtype: Dtype::F32,
            shape: vec![1, v.len() as u64],
            write: Box::new(move |w: &mut dyn Write| w.write_all(&bytes)),
        }
    };
    let wv: Vec<u8> = wavelengths_nm
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    let n_phi = phi_d.len();
    let n_cells = theta_d.len() * theta_h.len();
    let shape = vec![
        n_phi as u64,
        theta_d.len() as u64,
        theta_h.len() as u64,
        wavelengths_nm.len() as u64,
        4,
        4,
    ];
    let fields = vec![
        axis("phi_d", phi_d),
        axis("theta_d", theta_d),
        axis("theta_h", theta_h),
        FieldData {
            name: "wvls",
            dtype: Dtype::U16,
            shape: vec![wavelengths_nm.len() as u64],
            write: Box::new(move |w: &mut dyn Write| w.write_all(&wv)),
        },
        FieldData {
            name: "M",
            dtype: Dtype::F32,
            shape,
            write: Box::new(move |w: &mut dyn Write| {
                for p in 0..n_phi {
                    for start in (0..n_cells).step_by(CELL_BLOCK) {
                        let range = start..n_cells.min(start + CELL_BLOCK);
                        let s =
                            cells(p, range).map_err(|e| std::io::Error::other(e.to_string()))?;
                        let bytes: Vec<u8> = s.iter().flat_map(|x| x.to_le_bytes()).collect();
                        w.write_all(&bytes)?;
                    }
                }
                Ok(())
            }),
        },
    ];
    write_tensor_file(path, fields)
}
