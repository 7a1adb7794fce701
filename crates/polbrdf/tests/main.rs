//! Integration tests of the core (one test binary, modules by topic).

mod albedo;
mod bounds;
mod common;
mod contrast;
mod daylight;
mod detection;
mod directions;
mod emission;
mod frame;
mod frame_monte_carlo;
mod golden;
mod kernel;
mod limits;
mod planes;
mod precision;
mod properties;
mod spectral;
mod sun_position;
mod uncertainty;
mod validated_read;
mod vectors;
