//! Integration tests of the core (one test binary, modules by topic).

mod albedo;
mod bounds;
mod common;
mod contrast;
mod daylight;
mod detection;
mod directions;
mod emission;
mod golden;
mod kernel;
mod limits;
mod planes;
mod precision;
mod properties;
mod spectral;
mod sun_position;
mod vectors;
