//! Tests of the figures (one test binary, modules by topic).

mod heatmap;
mod polar;
