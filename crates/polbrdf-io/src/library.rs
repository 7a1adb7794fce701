//! The built-in library of refractive indices: pages of the refractiveindex.info database
//! (CC0), embedded unchanged from `crates/polbrdf-io/library/<book>/<page>.yml` (see its
//! README for the database version, the licence and the list). A material file names one as
//! `index = "library:<id>"`, the id being the database's `<book>/<page>`, e.g. `Au/Johnson`.

use crate::error::{Error, Result};
use crate::refractive::{parse_refractiveindex_yaml, read_refractiveindex_yaml};
use polbrdf::optics::dispersion::SpectralIndex;
use std::path::{Path, PathBuf};

/// One library entry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LibraryEntry {
    /// The database's `<book>/<page>`, e.g. `Au/Johnson`; [`load`] takes it.
    pub id: &'static str,
    /// The material in plain words, e.g. `gold`.
    pub material: &'static str,
    /// One line: what the data are, with their reference.
    pub description: &'static str,
}

/// The prefix of a library source in [`resolve`] (and in material files).
pub const PREFIX: &str = "library:";

macro_rules! library {
    ($( $id:literal, $material:literal, $description:literal; )*) => {
        /// Every entry with its file's text, in listing order.
        const ENTRIES: &[(LibraryEntry, &str)] = &[$(
            (
                LibraryEntry { id: $id, material: $material, description: $description },
                include_str!(concat!("../library/", $id, ".yml")),
            ),
        )*];
    };
}

library! {
    "Al/Rakic-LD", "aluminium", "Rakić et al., Appl. Opt. 37, 5271 (1998): Lorentz–Drude model fitted to several measurements";
    "Al/Ordal", "aluminium", "Ordal et al., Appl. Opt. 27, 1203 (1988): near to far infrared";
    "Ag/Johnson", "silver", "Johnson & Christy, Phys. Rev. B 6, 4370 (1972): evaporated films";
    "Ag/Yang", "silver", "Yang et al., Phys. Rev. B 91, 235137 (2015): template-stripped silver, UV to far infrared";
    "Au/Johnson", "gold", "Johnson & Christy, Phys. Rev. B 6, 4370 (1972): evaporated films";
    "Au/Ordal", "gold", "Ordal et al., Appl. Opt. 26, 744 (1987): near to far infrared";
    "Cu/Johnson", "copper", "Johnson & Christy, Phys. Rev. B 6, 4370 (1972): evaporated films";
    "Cu/Ordal", "copper", "Ordal et al., Appl. Opt. 24, 4493 (1985): visible to far infrared";
    "Fe/Johnson", "iron", "Johnson & Christy, Phys. Rev. B 9, 5056 (1974): evaporated films";
    "Fe/Ordal", "iron", "Ordal et al., Appl. Opt. 27, 1203 (1988): near to far infrared";
    "Ni/Johnson", "nickel", "Johnson & Christy, Phys. Rev. B 9, 5056 (1974): evaporated films";
    "Ni/Ordal", "nickel", "Ordal et al., Appl. Opt. 26, 744 (1987): near to far infrared";
    "Ti/Johnson", "titanium", "Johnson & Christy, Phys. Rev. B 9, 5056 (1974): evaporated films";
    "Ti/Ordal", "titanium", "Ordal et al., Appl. Opt. 27, 1203 (1988): near to far infrared";
    "W/Weaver", "tungsten", "Weaver, Olson & Lynch, Phys. Rev. B 12, 1293 (1975): crystalline tungsten (read from a figure)";
    "W/Ordal", "tungsten", "Ordal et al., Appl. Opt. 27, 1203 (1988): near to far infrared";
    "Cr/Johnson", "chromium", "Johnson & Christy, Phys. Rev. B 9, 5056 (1974): evaporated films";
    "Cr/Rakic-LD", "chromium", "Rakić et al., Appl. Opt. 37, 5271 (1998): Lorentz–Drude model fitted to several measurements";
    "H2O/Hale", "water", "Hale & Querry, Appl. Opt. 12, 555 (1973): liquid water at 25 °C";
    "SiO2/Malitson", "fused silica", "Malitson, J. Opt. Soc. Am. 55, 1205 (1965): Sellmeier formula (fitted 0.21–3.71 µm), k = 0";
    "SiO2/Popova", "fused silica", "Popova et al., Opt. Spectrosc. 33, 444 (1972), as modelled by Kitamura et al., Appl. Opt. 46, 8118 (2007): infrared";
    "BK7/SCHOTT", "N-BK7 glass", "SCHOTT Zemax catalogue 2017-01-20b: Sellmeier formula for n, tabulated k";
    "TiO2/Devore-o", "rutile TiO2", "Devore, J. Opt. Soc. Am. 41, 416 (1951): rutile crystal, ordinary ray, formula, k = 0";
    "TiO2/Siefke", "TiO2 film", "Siefke et al., Adv. Opt. Mater. 4, 1780 (2016): 350-nm ALD film, universal dispersion model";
    "Al2O3/Malitson-o", "sapphire Al2O3", "Malitson & Dodge, J. Opt. Soc. Am. 62, 1405 (1972): synthetic sapphire, ordinary ray, Sellmeier formula, k = 0";
    "Al2O3/Franta", "Al2O3 film", "Franta et al., Proc. SPIE 9628, 96281U (2015): 121.5-nm e-beam film, amorphous, universal dispersion model";
    "Fe2O3/Querry-e", "hematite Fe2O3", "Querry, report CRDC-CR-85034 (1985): α-Fe2O3, extraordinary ray";
    "illite/Querry", "illite (clay)", "Querry, report CRDEC-CR-88009 (1987): pressed pellet";
    "kaolinite/Querry", "kaolinite (clay)", "Querry, report CRDEC-CR-88009 (1987): pressed pellet";
    "montmorillonite/Querry", "montmorillonite (clay)", "Querry, report CRDEC-CR-88009 (1987): pressed pellet";
}

/// Every entry, in listing order (metals, then water, glasses, oxides and clays).
pub fn entries() -> Vec<LibraryEntry> {
    ENTRIES.iter().map(|(e, _)| *e).collect()
}

/// Loads library entry `id` (e.g. `Au/Johnson`); its [`SpectralIndex::name`] is the id.
///
/// # Errors
/// [`Error::File`] naming `library:<id>` and listing the known ids when there is no such
/// entry. (The entries themselves parse: the tests load every one.)
pub fn load(id: &str) -> Result<SpectralIndex> {
    let path = PathBuf::from(format!("{PREFIX}{id}"));
    let (entry, text) = ENTRIES
        .iter()
        .find(|(e, _)| e.id == id)
        .ok_or_else(|| Error::File {
            path: path.clone(),
            message: format!(
                "no such library entry (known: {})",
                ENTRIES
                    .iter()
                    .map(|(e, _)| e.id)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        })?;
    parse_refractiveindex_yaml(text, &path, entry.id)
}

/// The index a material file names: `library:<id>` loads a library entry ([`load`]); anything
/// else is the path of a refractiveindex.info YAML file ([`read_refractiveindex_yaml`]), a
/// relative path being taken relative to `relative_to` (the folder of the material file that
/// names it; the working directory when `None`).
///
/// # Errors
/// As [`load`] or [`read_refractiveindex_yaml`]; [`Error::File`] for an empty source.
pub fn resolve(source: &str, relative_to: Option<&Path>) -> Result<SpectralIndex> {
    if let Some(id) = source.strip_prefix(PREFIX) {
        return load(id);
    }
    if source.is_empty() {
        return Err(Error::File {
            path: PathBuf::new(),
            message: format!(
                "empty index source: give `{PREFIX}<id>` or the path of a refractiveindex.info \
                 YAML file"
            ),
        });
    }
    let path = Path::new(source);
    let path = match relative_to {
        Some(dir) if path.is_relative() => dir.join(path),
        _ => path.to_path_buf(),
    };
    read_refractiveindex_yaml(&path)
}
