//! Tests of the task layer: one module per job.

mod lut;
mod pbsdf;
