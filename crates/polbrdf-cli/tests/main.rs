//! Integration tests of the `polbrdf` binary (one test binary, modules by topic).

mod adapters;
mod albedo;
#[cfg(feature = "arrow")]
mod arrow;
mod bad_inputs;
mod bench;
mod cli_reference;
mod common;
mod contrast;
mod daylight;
mod daytime;
mod detect_frame;
mod doc_snippets;
mod emission;
mod eval;
mod fit;
mod golden;
mod lut;
mod map;
mod options;
mod outputs;
mod pbsdf;
mod presets;
mod spectral;
mod streams;
mod units;
