//! Tests of the file formats (one test binary).

#[cfg(feature = "arrow")]
mod arrow_files;
mod csv_files;
mod csv_limits;
mod file_sets;
mod layers;
mod material_files;
mod npy_files;
mod refractive;
mod scene;
mod scene_sun;
