//! Every size a user can type on the command line, bounded before anything is allocated
//! (issue 18; docs/reliability.md lists them). A value over its limit is a usage
//! error naming the option and the limit (exit code 2).

use crate::error::CliError;

/// `check --grid-deg`: geometries of the validity grid (θi × θr × Δφ). Each costs about 400
/// bytes (the geometry, its reciprocal and two Mueller matrices): 2·10⁶ is under 1 GB, a
/// zenith step of about 0.9°.
pub const CHECK_GEOMETRIES: usize = 2_000_000;

/// `fit --starts` (and Python's `fit(starts=…)`, through `polbrdf_fit::MAX_EXTRA_STARTS`).
pub const STARTS: usize = polbrdf_fit::MAX_EXTRA_STARTS;

/// `contrast --top`: best directions listed (each refined by brute force).
pub const TOP: usize = 1000;

/// `bench --count`: random geometries (about 250 bytes each with the results: 2.5 GB).
pub const BENCH_COUNT: usize = 10_000_000;

/// `bench --repeats`.
pub const BENCH_REPEATS: usize = 1000;

/// `bench --threads`: threads of a pool. Fixed rather than a multiple of the cores, so that a
/// benchmark's command line means the same on every machine; far above any useful count.
pub const THREADS: usize = 1024;

/// `spectrum --points`: wavelengths of the sweep.
pub const SPECTRUM_POINTS: usize = 1_000_000;

/// `radiance --theta-deg × --phi-deg`, `emission --theta-deg`, `albedo --theta-i-deg`: view
/// directions or angles given on the command line.
pub const ANGLES: usize = 1_000_000;

/// `value` of `option` at most `max`.
pub fn at_most(option: &str, value: usize, max: usize) -> Result<(), CliError> {
    if value > max {
        Err(CliError::Usage(format!(
            "{option} = {value}: at most {max} (the limit of this option; see docs/reliability.md)"
        )))
    } else {
        Ok(())
    }
}

/// The product of sizes `a · b` of `option`, at most `max` (checked arithmetic).
pub fn product_at_most(option: &str, a: usize, b: usize, max: usize) -> Result<usize, CliError> {
    match a.checked_mul(b) {
        Some(n) if n <= max => Ok(n),
        _ => Err(CliError::Usage(format!(
            "{option}: {a} × {b} values, at most {max} (the limit of this option; see \
             docs/reliability.md)"
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_refuse_above_and_accept_at_the_bound() {
        assert!(at_most("--top", TOP, TOP).is_ok());
        let e = at_most("--top", TOP + 1, TOP).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("--top = 1001: at most 1000"));
        assert!(product_at_most("x", usize::MAX, 2, ANGLES).is_err());
        assert_eq!(product_at_most("x", 1000, 1000, ANGLES).unwrap(), ANGLES);
    }
}
