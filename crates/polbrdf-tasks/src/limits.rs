//! Every size a request can ask for, bounded before anything is allocated (issue 18;
//! docs/reliability.md and docs/io.md's Resource model list them). The jobs check
//! their own requests against these, so that the CLI and Python are bounded the same way: a
//! value over its limit is [`TaskError::Limit`] naming the request field (the CLI's usage
//! error, exit code 2, naming the option; Python's `ValueError` naming the keyword).

use crate::error::{TaskError, TaskResult};

/// `check`'s `grid_deg`: geometries of the validity grid (θi × θr × Δφ). Each costs about 400
/// bytes (the geometry, its reciprocal and two Mueller matrices): 2·10⁶ is under 1 GB, a
/// zenith step of about 0.9°.
pub const CHECK_GEOMETRIES: usize = 2_000_000;

/// A fit's extra starts (`polbrdf_fit::MAX_EXTRA_STARTS`).
pub const STARTS: usize = polbrdf_fit::MAX_EXTRA_STARTS;

/// A contrast's `top`: best directions listed (each refined by brute force).
pub const TOP: usize = 1000;

/// View directions or angles of one request: `radiance`'s views, `emission`'s `theta_deg`,
/// `albedo`'s `theta_i_deg`.
pub const ANGLES: usize = 1_000_000;

/// `value` of `field` at most `max`.
///
/// # Errors
/// [`TaskError::Limit`] naming `field`.
pub fn at_most(field: &str, value: usize, max: usize) -> TaskResult<()> {
    if value > max {
        Err(TaskError::Limit {
            field: field.to_string(),
            what: format!(" = {value}"),
            max,
        })
    } else {
        Ok(())
    }
}

/// The count of values of `field` at most `max`.
///
/// # Errors
/// [`TaskError::Limit`] naming `field`.
pub fn count_at_most(field: &str, count: usize, max: usize) -> TaskResult<()> {
    if count > max {
        Err(TaskError::Limit {
            field: field.to_string(),
            what: format!(": {count} values"),
            max,
        })
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_refuse_above_and_accept_at_the_bound() {
        assert!(at_most("top", TOP, TOP).is_ok());
        let e = at_most("top", TOP + 1, TOP).unwrap_err();
        assert_eq!(e.to_string(), "top = 1001: at most 1000");
        assert!(count_at_most("theta_deg", ANGLES, ANGLES).is_ok());
        let e = count_at_most("theta_deg", ANGLES + 1, ANGLES).unwrap_err();
        assert_eq!(e.to_string(), "theta_deg: 1000001 values: at most 1000000");
    }
}
