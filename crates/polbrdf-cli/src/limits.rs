//! The sizes of the commands that only the command line has (`bench`, `spectrum`) and of its
//! own view grids, bounded before anything is allocated (issue 18; docs/reliability.md
//! lists them). The limits of the jobs (`check`'s grid, a contrast's `top`, the angles
//! of `albedo`, `emission` and `radiance`, a fit's starts) live in the task layer
//! (`polbrdf_tasks::limits`), so Python is bounded the same way. A value over its limit is a
//! usage error naming the option and the limit (exit code 2).

use crate::error::CliError;

/// `fit --starts`, the task layer's.
pub use polbrdf_tasks::limits::STARTS;

/// `bench --count`: random geometries (about 250 bytes each with the results: 2.5 GB).
pub const BENCH_COUNT: usize = 10_000_000;

/// `bench --repeats`.
pub const BENCH_REPEATS: usize = 1000;

/// `bench --threads`: threads of a pool. Fixed rather than a multiple of the cores, so that a
/// benchmark's command line means the same on every machine; far above any useful count.
pub const THREADS: usize = 1024;

/// `spectrum --points`: wavelengths of the sweep.
pub const SPECTRUM_POINTS: usize = 1_000_000;

/// `radiance --theta-deg × --phi-deg`: view directions of the grid, the task layer's bound
/// of a request's angles.
pub use polbrdf_tasks::limits::ANGLES;

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
        assert!(at_most("--repeats", BENCH_REPEATS, BENCH_REPEATS).is_ok());
        let e = at_most("--repeats", BENCH_REPEATS + 1, BENCH_REPEATS).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("--repeats = 1001: at most 1000"));
        assert!(product_at_most("x", usize::MAX, 2, ANGLES).is_err());
        assert_eq!(product_at_most("x", 1000, 1000, ANGLES).unwrap(), ANGLES);
    }
}
