//! Tests of the task layer: one module per job, each asserting physics or behaviour (analytic
//! limits, symmetries, the request's validation), not a re-computation of the same code.

mod common;

mod albedo_check;
mod contrast;
mod daytime;
mod detect;
mod detect_uncertainty;
mod detect_warnings;
mod emission;
mod explore;
mod frame;
mod radiance;
mod scene;
mod spectrum;

mod lut;
mod pbsdf;
