//! The closed sets of names the Python module accepts (its stub's `Literal` types) and the
//! defaults it takes, each from its one source in Rust: the core's enums, `polbrdf-io`'s scene
//! format, `polbrdf-fit`'s parameters and quantities. The Python tests compare the stub with
//! these, so that neither can drift.

use polbrdf::analysis::contrast::Ranking;
use polbrdf::analysis::detection::Feature;
use polbrdf::engine::Precision;
use polbrdf::{AzimuthTerm, Form};
use polbrdf_fit::fit::Observable;
use polbrdf_fit::Param;
use pyo3::prelude::*;
use std::collections::BTreeMap;

/// The layouts of a pBRDF result (`layout=`): one row-major 4×4 per geometry, or 16 planes.
pub(crate) const LAYOUTS: [&str; 2] = ["interleaved", "planar"];

/// `{set: names}` of every closed set of names the module accepts: `form`, `azimuth_term`
/// (material keys), `precision`, `layout`, `sky` (the scene files' sky models), `quantity`
/// (what a fit takes as measured), `parameter` (what a fit frees), `scene_key` (every key and
/// table of a scene file, dotted), `rank_by` (the scores of a contrast's ranking),
/// `lut_quantity` (the quantities of a lookup table), `feature` (what a detector may use),
/// `mueller_column` (the names `m00 … m33` of the Mueller entries in every file and table).
#[pyfunction]
pub(crate) fn vocabulary() -> BTreeMap<&'static str, Vec<String>> {
    let names = |it: &mut dyn Iterator<Item = &'static str>| it.map(String::from).collect();
    BTreeMap::from([
        ("form", names(&mut Form::ALL.iter().map(|f| f.as_str()))),
        (
            "azimuth_term",
            names(&mut AzimuthTerm::ALL.iter().map(|a| a.as_str())),
        ),
        (
            "precision",
            names(&mut Precision::ALL.iter().map(|p| p.name())),
        ),
        ("layout", names(&mut LAYOUTS.into_iter())),
        ("sky", names(&mut polbrdf_io::scene::sky_model_names())),
        (
            "quantity",
            Observable::all().iter().map(Observable::name).collect(),
        ),
        ("parameter", names(&mut Param::ALL.iter().map(|p| p.name()))),
        ("scene_key", names(&mut polbrdf_io::scene::key_names())),
        (
            "rank_by",
            names(&mut Ranking::ALL.iter().map(|r| r.as_str())),
        ),
        (
            "feature",
            names(&mut Feature::ALL.iter().map(|f| f.as_str())),
        ),
        (
            "lut_quantity",
            names(&mut polbrdf_io::lut::Quantity::ALL.iter().map(|(n, _)| *n)),
        ),
        (
            "mueller_column",
            names(&mut polbrdf::Mueller::COLUMNS.into_iter()),
        ),
    ])
}
