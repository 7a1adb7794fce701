//! `polbrdf materials`: the built-in materials.

use crate::error::CliError;
use crate::output::write_output;

/// Runs `polbrdf materials`.
pub fn run(show: Option<&str>) -> Result<(), CliError> {
    let text = match show {
        Some(name) => polbrdf_io::material_to_toml(&polbrdf::preset(name)?),
        None => {
            let mut text = String::from("Built-in materials (use the name with --material):\n\n");
            for p in polbrdf::presets::all() {
                text.push_str(&format!("  {:<13} {}\n", p.name, p.description));
            }
            text.push_str("\n`polbrdf materials --show NAME` prints one as a material file.\n");
            text
        }
    };
    write_output(None, text.as_bytes())
}
