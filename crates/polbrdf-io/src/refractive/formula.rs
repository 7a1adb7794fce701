//! The dispersion formulas of `formula N` blocks: the coefficient counts each takes and the
//! check that a formula gives a valid n over all of its range (module docs of `refractive`).

use super::values::{numbers, BlockKeys, GivenRange, Gives};
use crate::error::Result;
use polbrdf::error::MAX_INDEX;
use polbrdf::optics::dispersion::Dispersion;

/// Points per spread (linear, then logarithmic) at which a formula is checked.
const CHECK_POINTS: usize = 1024;

/// What a `formula N` block gives: n by the formula over its range (required), with a count of
/// `coefficients` that formula takes and a valid n over all of the range ([`check_formula`]).
pub(super) fn formula_block(
    keys: &BlockKeys<'_>,
    kind: u8,
    range: GivenRange<'_>,
) -> Result<Gives> {
    let coefficients = keys
        .get("coefficients")
        .ok_or_else(|| keys.missing("coefficients", "C1 C2 …, separated by blanks"))?;
    let Some((_, (lo, hi))) = range else {
        return Err(keys.missing(
            "wavelength_range",
            "`λ_min λ_max` in µm, where the formula holds",
        ));
    };
    let c = numbers(coefficients, keys.ctx)?;
    let (counts, rule) = coefficient_counts(kind).unwrap_or_default();
    if !counts.contains(&c.len()) {
        return Err(keys.ctx.field(
            coefficients.line,
            "coefficients",
            format!(
                "{} coefficient{} for formula {kind}, which takes {rule}",
                c.len(),
                if c.len() == 1 { "" } else { "s" }
            ),
        ));
    }
    let formula = Dispersion::Formula {
        kind,
        coefficients: c,
        range: (lo, hi),
    };
    check_formula(&formula).map_err(|m| {
        keys.ctx.field(
            coefficients.line,
            "coefficients",
            format!("formula {kind} {m} (its range is {lo}–{hi} µm)"),
        )
    })?;
    Ok((Some(formula), None))
}

/// The coefficient counts formula `kind` (1–9) accepts and their rule in words (module docs).
fn coefficient_counts(kind: u8) -> Option<(Vec<usize>, &'static str)> {
    let odd_to = |max: usize| (1..=max).step_by(2).collect::<Vec<_>>();
    Some(match kind {
        1..=3 => (
            odd_to(17),
            "C1, then pairs (C2, C3), (C4, C5), …: an odd number, at most 17",
        ),
        4 => (
            [1, 5].into_iter().chain((9..=17).step_by(2)).collect(),
            "C1, then C2–C5, C6–C9, then pairs (C10, C11), …: 1, 5, 9, 11, …, 17",
        ),
        5 | 6 => (
            odd_to(11),
            "C1, then pairs (C2, C3), (C4, C5), …: an odd number, at most 11",
        ),
        7 | 9 => ((1..=6).collect(), "C1 to C6 (missing ones are 0)"),
        8 => ((1..=4).collect(), "C1 to C4 (missing ones are 0)"),
        _ => return None,
    })
}

/// Checks that a formula gives a valid n over its range: no pole inside it, and
/// 0 < n ≤ 10⁶ at the ends, the geometric mean and `CHECK_POINTS` points spread linearly and
/// logarithmically (plus, for formula 9, the extremes of its resonance term). The message says
/// where not.
fn check_formula(f: &Dispersion) -> std::result::Result<(), String> {
    let Dispersion::Formula {
        kind,
        coefficients: c,
        range: (lo, hi),
    } = f
    else {
        return Ok(());
    };
    let (lo, hi) = (*lo, *hi);
    let at = |i: usize| c.get(i).copied().unwrap_or(0.0);
    // Poles: (λ where a denominator vanishes, which coefficient sets it).
    let mut poles: Vec<(f64, String)> = Vec::new();
    let pairs = (1..c.len()).step_by(2).map(|i| (i, at(i), at(i + 1)));
    match kind {
        1 => poles.extend(
            pairs
                .filter(|p| p.1 != 0.0)
                .map(|(i, _, b)| (b.abs(), format!("λ = |C{}|", i + 2))),
        ),
        2 => poles.extend(
            pairs
                .filter(|p| p.1 != 0.0 && p.2 > 0.0)
                .map(|(i, _, b)| (b.sqrt(), format!("λ² = C{}", i + 2))),
        ),
        6 => poles.extend(
            pairs
                .filter(|p| p.1 != 0.0 && p.2 > 0.0)
                .map(|(i, _, b)| (1.0 / b.sqrt(), format!("λ⁻² = C{}", i + 2))),
        ),
        4 => {
            for i in [1, 5] {
                let p = at(i + 2).powf(at(i + 3));
                if at(i) != 0.0 && p > 0.0 {
                    poles.push((p.sqrt(), format!("λ² = C{}^C{}", i + 3, i + 4)));
                }
            }
        }
        7 if at(1) != 0.0 || at(2) != 0.0 => poles.push((0.028f64.sqrt(), "λ² = 0.028".into())),
        8 | 9 if at(1) != 0.0 && at(2) > 0.0 => poles.push((at(2).sqrt(), "λ² = C3".into())),
        _ => {}
    }
    let mut extra = Vec::new();
    if *kind == 9 && at(3) != 0.0 {
        let (c5, c6) = (at(4), at(5));
        if c6 <= 0.0 {
            let r = (-c6).sqrt();
            poles.push((c5 - r, "(λ − C5)² + C6 = 0".into()));
            poles.push((c5 + r, "(λ − C5)² + C6 = 0".into()));
        } else {
            extra.extend([c5 - c6.sqrt(), c5 + c6.sqrt()]);
        }
    }
    if let Some((l, why)) = poles.iter().find(|(l, _)| *l >= lo && *l <= hi) {
        return Err(format!("has a pole at λ = {l} µm ({why}) inside its range"));
    }
    let n = CHECK_POINTS as f64;
    let linear = (0..=CHECK_POINTS).map(|i| lo + (hi - lo) * (i as f64 / n));
    let log = (0..=CHECK_POINTS).map(|i| lo * (hi / lo).powf(i as f64 / n));
    extra.push((lo * hi).sqrt());
    let inside = extra.into_iter().filter(|l| *l > lo && *l < hi);
    for l in linear.chain(log).chain(inside).chain([lo, hi]) {
        let l = l.clamp(lo, hi);
        match f.eval(l) {
            Some(v) if v.is_finite() && v > 0.0 && v <= MAX_INDEX => {}
            Some(v) if v.is_nan() => {
                return Err(format!(
                    "gives no real index at λ = {l} µm (n² < 0 or not finite there)"
                ))
            }
            Some(v) => return Err(format!("gives n = {v} at λ = {l} µm (must be in (0, 1e6])")),
            None => return Err(format!("cannot be evaluated at λ = {l} µm")),
        }
    }
    Ok(())
}
