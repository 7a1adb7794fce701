//! Tests of the inversion (one test binary).

mod diagnostics;
mod general;
mod zero_bistatic;
