//! Tests of the inversion (one test binary).

mod general;
mod zero_bistatic;
