//! Integration tests of the `polbrdf` binary (one test binary, modules by topic).

mod common;
mod eval;
mod fit;
