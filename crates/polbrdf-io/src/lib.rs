//! File formats of polbrdf: material files (flat TOML), geometry and result CSV, refractive-index
//! files of the refractiveindex.info database (YAML) with a built-in library of them, scene files
//! (TOML, with band, sky profile and sky table CSV), and atomic output. Every error names the
//! file, and where it applies the line and the field.

#![warn(missing_docs)]

#[cfg(feature = "arrow")]
pub mod arrow;
pub mod csv_io;
pub mod date_time;
pub mod detection_csv;
pub mod error;
pub mod library;
pub mod lut;
pub mod material;
pub mod measurements;
pub mod npy;
pub mod pbsdf;
pub mod refractive;
pub mod scene;
pub mod sensor;
pub mod stream;
pub mod table;
pub mod tensorfile;
pub mod toml_doc;
pub mod units;
pub mod write;
pub mod write_set;

pub use csv_io::{
    parse_band_csv, parse_geometry_csv, parse_sky_profile_csv, parse_sky_table_csv,
    parse_views_csv, read_band_csv, read_geometry_csv, read_sky_profile_csv, read_sky_table_csv,
    read_views_csv, CsvReader, CsvTable, GeometryTable,
};
pub use detection_csv::{parse_path_csv, parse_qe_csv, read_path_csv, read_qe_csv};
pub use error::{Error, Result};
pub use material::{load_material, material_to_toml, parse_material, read_material};
pub use measurements::{parse_measurements_csv, read_measurements_csv, MeasurementTable};
pub use pbsdf::{write_pbsdf, PbsdfTable};
pub use refractive::{
    parse_refractiveindex_yaml, parse_refractiveindex_yaml_bytes, read_refractiveindex_yaml,
};
pub use scene::{
    parse_scene, parse_scene_with_files, read_scene, read_scene_keys, Scene, SceneObject,
    SceneValue,
};
pub use sensor::{parse_sensor, read_sensor, SensorFile};
pub use tensorfile::TensorFile;
pub use units::{material_warnings, AngleScan, UnitWarning};
pub use write::{check_distinct, install_signal_cleanup, write_atomic, Output, Target};
pub use write_set::{write_files, StagingDir};
