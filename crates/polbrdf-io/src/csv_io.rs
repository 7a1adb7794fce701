//! Geometry CSV in, result CSV out (the `polbrdf eval` contract in the README), and the CSV
//! tables of a scene or a run (band, sky profile, sky table, view directions). This module only
//! gathers its parts, each of one job; their `use` edges point one way, from the table readers
//! down to the record reader and the messages:
//!
//! - `message`: names, lists and numbers cut for messages (uses nothing here);
//! - `whole_file`: small files read whole, as bounded UTF-8 text (uses nothing here);
//! - `fields`: a header's required columns, a field as a number, a core error at its row
//!   (uses `message`);
//! - `reader`: the streaming record reader [`CsvReader`] (uses `fields`, `message`);
//! - `geometry`: the geometry table and the row checks every table reader shares;
//! - `band`, `sky`, `views`: the band, sky profile / sky table and view-direction files
//!   (these three and `geometry` use `reader`, `fields`, `message`);
//! - `writer`: [`CsvTable`], [`fmt_f64`] and the result table of `eval` (uses `geometry`).

mod band;
mod fields;
mod geometry;
mod message;
mod reader;
mod sky;
mod views;
mod whole_file;
mod writer;

pub use band::{parse_band_csv, read_band_csv, BAND_COLUMNS};
pub use geometry::{
    geometry_chunk, parse_geometry_csv, read_geometry_csv, GeometryTable, ANGLE_COLUMNS,
    DIRECTION_COLUMNS, WAVELENGTH_COLUMN,
};
pub use message::{short_list, short_name, MAX_LIST_IN_MESSAGE, MAX_NAME_IN_MESSAGE};
pub use reader::{CsvReader, Record, MAX_LINE_BYTES};
pub use sky::{
    parse_sky_profile_csv, parse_sky_table_csv, read_sky_profile_csv, read_sky_table_csv,
    SKY_PROFILE_COLUMNS, SKY_TABLE_COLUMNS,
};
pub use views::{parse_views_csv, read_views_csv, VIEW_COLUMNS};
pub use whole_file::MAX_WHOLE_FILE_BYTES;
pub use writer::{fmt_f64, fmt_f64_into, result_columns, results_csv, CsvTable};

pub(crate) use fields::{check_header, parse_number, row_error};
pub(crate) use geometry::{
    check_wavelength, directions_of, geometry_of_degrees, record_geometry, record_wavelength,
    row_directions, row_geometry, row_wavelength,
};
pub(crate) use message::{short_message, show};
pub(crate) use whole_file::{line_of, lone_cr_to_lf, read_all, read_text};
