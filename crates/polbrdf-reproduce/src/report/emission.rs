//! Interpretation (c) of `report.md`: Table 1 as the polarized thermal emission of the rough
//! surface, from the core's Kirchhoff emissivity.

use super::{col, interp, table_row};
use crate::analysis::{Analysis, EmissionNotes, InterpResult};
use crate::compute::Roughness;
use crate::params::*;
use std::fmt::Write as _;

/// The section on interpretation (c): Table 1 as the polarized thermal emission of the rough
/// surface, from the core's Kirchhoff emissivity.
/// A cell of Table 1 by name: `roughness/angle°`.
fn cell_name(ri: usize, ci: usize) -> String {
    format!("{:.1}/{:.0}°", ROUGHNESS[ri], TABLE_ANGLES_DEG[ci])
}

/// The smallest and largest relative loss of (c)'s DoLP from roughness 0 to 0.1 over the
/// table's angles.
fn first_loss(d: &[[f64; 5]; 6]) -> (f64, f64) {
    let first_loss: Vec<f64> = (0..5).map(|ci| 1.0 - d[1][ci] / d[0][ci]).collect();
    first_loss
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &x| {
            (l.min(x), h.max(x))
        })
}

pub(super) fn emission_section(a: &Analysis) -> String {
    let Some(c) = interp(a, |h| matches!(h, Roughness::Emission(_, true))) else {
        return String::new();
    };
    let mut s = String::new();
    emission_table(&mut s, a, c);
    emission_provenance(&mut s, a);
    emission_against_table(&mut s, a, c);
    emission_no_shadowing_table(&mut s, a, c);
    emission_no_shadowing_verdict(&mut s, a, c);
    s
}

/// (c)'s table: the emitted DoLP beside the paper's two columns.
fn emission_table(s: &mut String, a: &Analysis, c: &InterpResult) {
    let en = &a.emission_notes;
    let d = &c.cells;
    let (pm, pl) = (&TABLE_PAPER_MODEL, &TABLE_PAPER_LAWRENCE);
    // The table.
    let _ = write!(
        s,
        r#"
### Interpretation (c): Table 1 as polarized thermal emission

If Table 1 were the polarization of the light the rough paint *emits* — Kirchhoff's law applied
to this model, roughness = σ of D in radians, n = {:.1}, shadowing on, standard form, no volume
term — it would read (**(c)** / paper's model / Lawrence–Wolff; DoLP of the emitted light in %
at view angle θ):

| roughness | 20° | 30° | 45° | 60° | 80° |
|---|---|---|---|---|---|
"#,
        en.n
    );
    for (ri, r) in ROUGHNESS.iter().enumerate() {
        let mut cells = vec![format!("{r:.1}")];
        for ci in 0..5 {
            cells.push(format!(
                "**{:.1}** / {:.0} / {:.0}",
                d[ri][ci], pm[ri][ci], pl[ri][ci]
            ));
        }
        s.push_str(&table_row(&cells));
    }
}

/// (c)'s provenance: the emissivities' checks (reciprocity, ε₂, ε₃, validity).
fn emission_provenance(s: &mut String, a: &Analysis) {
    let en = &a.emission_notes;
    // Provenance and checks.
    let grids = [&en.cells[..], &en.cells_no_so[..]];
    let residual = grids
        .iter()
        .map(|g| EmissionNotes::max_residual(g))
        .fold(0.0, f64::max);
    let eps23 = grids
        .iter()
        .map(|g| EmissionNotes::max_eps23(g))
        .fold(0.0, f64::max);
    let n_cells = en.cells.iter().flatten().count();
    let invalid = EmissionNotes::invalid(&en.cells);
    let range = |f: &dyn Fn(&polbrdf::analysis::Emissivity) -> f64| {
        en.cells
            .iter()
            .flatten()
            .map(f)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    };
    let (s_lo, s_hi) = range(&|e| e.eps_s());
    let (p_lo, p_hi) = range(&|e| e.eps_p());
    let invalid_list = |list: &[(usize, usize, polbrdf::analysis::Emissivity)]| {
        list.iter()
            .map(|(ri, ci, e)| {
                format!(
                    "{} (ε_s = {:.3}, ε_p = {:.3})",
                    cell_name(*ri, *ci),
                    e.eps_s(),
                    e.eps_p()
                )
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let validity = if invalid.is_empty() {
        format!(
            "All {n_cells} cells are physically valid (`is_valid`): ε_s and ε_p lie in [0, 1] \
             everywhere (ε_s from {s_lo:.3} to {s_hi:.3}, ε_p from {p_lo:.3} to {p_hi:.3})."
        )
    } else {
        format!(
            "{} of the {n_cells} cells are not physically valid (ε_s or ε_p outside [0, 1]): {}.",
            invalid.len(),
            invalid_list(&invalid)
        )
    };
    let _ = write!(
        s,
        r#"
**Where the numbers come from.** Row 0 is the σ → 0 limit, the Fresnel emission DoLP
|R_s − R_p|/(2 − R_s − R_p) of the flat surface. The model approaches it: at σ =
{SMOOTH_CHECK_SIGMA_DEG}° its emission DoLP differs from it by at most {:.1e} points with
shadowing off (the core's smooth limit converges as σ²) and by {:.2} points with shadowing on
({:.2} at σ = {}°: linear in σ, because SO's loss (θN/Ω)·(1 − exp(−2β/τ)) is first order in the
facet tilt). Every other cell is the DoLP sqrt(ε1² + ε2²)/ε0 of the core's Kirchhoff emissivity
(`polbrdf::analysis::emission::emissivities`, one batched call per roughness): route A, the
definition ε = e0 − ∫F[:, 0] cosθi dω_i over the incidence hemisphere, on the core's
facet-normal rule (stated to 1e-6 absolute from σ = 0.05° to 80°). Route B — one minus the
directional–hemispherical reflectance of s- and p-polarized light incident from the view
direction — agrees with route A to a largest reciprocity residual of {:.1e} over these
{n_cells} cells and the {} of (c′) below (rounding: the standard form is reciprocal); ε2 and ε3
{}. {validity}
"#,
        100.0 * en.smooth_gap_no_so,
        100.0 * en.smooth_gap_so.0,
        100.0 * en.smooth_gap_so.1,
        2.0 * SMOOTH_CHECK_SIGMA_DEG,
        residual,
        en.cells_no_so.iter().flatten().count(),
        if eps23 == 0.0 {
            "vanish exactly (mirror symmetry)".to_string()
        } else {
            format!("are at most {eps23:.1e} (0 by mirror symmetry)")
        },
    );
}

/// (c) against the printed table: the sign and the pattern of the roughness effect.
fn emission_against_table(s: &mut String, a: &Analysis, c: &InterpResult) {
    let d = &c.cells;
    let (pm, pl) = (&TABLE_PAPER_MODEL, &TABLE_PAPER_LAWRENCE);
    let (c20, c80) = (col(20.0), col(80.0));
    // Against the printed table.
    let monotone = (0..5).all(|ci| (1..6).all(|ri| d[ri][ci] <= d[ri - 1][ci]));
    let (fl_lo, fl_hi) = first_loss(d);
    let table_step = |t: &[[f64; 5]; 6]| {
        (0..5)
            .map(|ci| (t[1][ci] - t[0][ci]).abs())
            .fold(0.0, f64::max)
    };
    let keep = |t: &[[f64; 5]; 6], ci: usize| 100.0 * t[5][ci] / t[0][ci];
    let rough_rms = |t: &[[f64; 5]; 6]| {
        let s: f64 = (1..6)
            .flat_map(|ri| (0..5).map(move |ci| (ri, ci)))
            .map(|(ri, ci)| (d[ri][ci] - t[ri][ci]).powi(2))
            .sum();
        (s / 25.0).sqrt()
    };
    let row0_rms = |t: &[[f64; 5]; 6]| {
        ((0..5).map(|ci| (d[0][ci] - t[0][ci]).powi(2)).sum::<f64>() / 5.0).sqrt()
    };
    let p = a.primary();
    let falls = |t: &[[f64; 5]; 6]| (0..5).all(|ci| (1..6).all(|ri| t[ri][ci] <= t[ri - 1][ci]));
    let sign = match (monotone, falls(pm) && falls(pl)) {
        (true, true) => {
            "the same: (c)'s emission DoLP falls with roughness at every angle, as both \
                         printed columns do"
        }
        (true, false) => {
            "(c)'s emission DoLP falls with roughness at every angle; the printed \
                          columns do not everywhere"
        }
        (false, _) => {
            "not the same everywhere: (c)'s emission DoLP does not fall monotonically \
                       with roughness at every angle"
        }
    };
    let c_more_small = keep(d, c20) < keep(d, c80);
    let pm_more_small = keep(pm, c20) < keep(pm, c80);
    let c_pattern = match (c_more_small, pm_more_small) {
        (true, false) => {
            "(c) loses relatively more at small angles than toward grazing, the \
                          paper's model column the other way round (the Lawrence/Wolff 29 % at \
                          20° rests on its 2 %, which breaks its row's trend, see below)"
        }
        (false, true) => {
            "(c) loses relatively more toward grazing, the paper's model column at \
                          small angles"
        }
        (true, true) => "both lose relatively more at small angles than toward grazing",
        (false, false) => "both lose relatively more toward grazing than at small angles",
    };
    let _ = write!(
        s,
        r#"
**Against the printed table.**

* *Row 0* is {:.2} points RMS from the Lawrence/Wolff row and {:.2} from the paper's model row,
  by construction: n was fitted to the Lawrence/Wolff row as emission. It is no evidence for
  (c).
* *Sign of the roughness trend*: {sign}.
* *Magnitude*: far too large. The first step, roughness 0 → 0.1, removes {:.0}–{:.0} % of the
  DoLP at every angle ({:.1} → {:.1} % at 20°, {:.1} → {:.1} % at 80°); the printed columns
  change by at most {:.0} (paper's model) and {:.0} (Lawrence/Wolff) points at that step. At
  roughness 0.5, (c) keeps {:.0} % of its row-0 DoLP at 20° and {:.0} % at 80°; the table keeps
  {:.0} % and {:.0} % (paper's model), {:.0} % and {:.0} % (Lawrence/Wolff): {c_pattern}.
* *Overall*: RMS {:.1} points from the paper's model column and {:.1} from Lawrence/Wolff over
  the 30 cells; over the 25 rough cells alone {:.1} and {:.1}. The relative roughness effect
  DoLP(r)/DoLP(0) misses by {:.1} and {:.1} % of row 0, against {:.1} and {:.1} for the
  reflection interpretation (a). **(c) does not reproduce Table 1**: it matches the fitted
  smooth row and none of the rough rows.
"#,
        row0_rms(pl),
        row0_rms(pm),
        100.0 * fl_lo,
        100.0 * fl_hi,
        d[0][c20],
        d[1][c20],
        d[0][c80],
        d[1][c80],
        table_step(pm),
        table_step(pl),
        keep(d, c20),
        keep(d, c80),
        keep(pm, c20),
        keep(pm, c80),
        keep(pl, c20),
        keep(pl, c80),
        c.rms_model,
        c.rms_lawrence,
        rough_rms(pm),
        rough_rms(pl),
        c.rel_model,
        c.rel_lawrence,
        p.rel_model,
        p.rel_lawrence,
    );
}

/// Why (c) is what it is: the energy balance, and the table of the variant without shadowing.
fn emission_no_shadowing_table(s: &mut String, a: &Analysis, c: &InterpResult) {
    let en = &a.emission_notes;
    let d = &c.cells;
    let c20 = col(20.0);
    // Why: the energy balance, and the variant without shadowing.
    let flat0 = |ci: usize| 0.5 * (en.flat[ci].0 + en.flat[ci].1);
    let e_so = en.cells[0][c20].eps.0[0];
    let e_no = en.cells_no_so[0][c20].eps.0[0];
    let _ = write!(
        s,
        r#"
**Why the DoLP collapses.** With n = {:.1} the flat surface reflects {:.1} % at 20° (ε0 =
{:.4}), so its emission DoLP |R_s − R_p|/(2 − R_s − R_p) has a small denominator and reacts
strongly to any reflectance the surface loses. The MB model loses reflectance by shadowing: SO
removes light without scattering it anywhere, and Kirchhoff's law counts that as absorption,
hence emission. At 20° and σ = 0.1 rad the hemispherical reflectance 1 − ε0 is {:.4} against
{:.4} for the flat surface: ε0 grows {:.1}-fold and the DoLP falls from {:.1} % to {:.1} %. With
shadowing off (variant (c′) below) ε0 there is {:.5} (flat {:.5}) and the DoLP {:.1} %.

**(c′) the same without shadowing** — DoLP (%) of the emitted light; a cell whose ε_s or ε_p
leaves [0, 1] is marked *invalid*:

| roughness | 20° | 30° | 45° | 60° | 80° |
|---|---|---|---|---|---|
"#,
        en.n,
        100.0 * (1.0 - flat0(c20)),
        flat0(c20),
        1.0 - e_so,
        1.0 - flat0(c20),
        e_so / flat0(c20),
        d[0][c20],
        d[1][c20],
        e_no,
        flat0(c20),
        en.dolp_no_so[1][c20],
    );
    for (ri, r) in ROUGHNESS.iter().enumerate() {
        let mut cells = vec![format!("{r:.1}")];
        for ci in 0..5 {
            let valid = ri == 0 || en.cells_no_so[ri - 1][ci].is_valid();
            cells.push(if valid {
                format!("{:.1}", en.dolp_no_so[ri][ci])
            } else {
                let e = en.cells_no_so[ri - 1][ci];
                format!("*invalid* (ε_s = {:.3}, ε_p = {:.3})", e.eps_s(), e.eps_p())
            });
        }
        s.push_str(&table_row(&cells));
    }
}

/// The variant without shadowing against the table, and the verdict on (c).
fn emission_no_shadowing_verdict(s: &mut String, a: &Analysis, c: &InterpResult) {
    let (fl_lo, fl_hi) = first_loss(&c.cells);
    let en = &a.emission_notes;
    let (c20, c80) = (col(20.0), col(80.0));
    let invalid_no_so = EmissionNotes::invalid(&en.cells_no_so);
    let dn = &en.dolp_no_so;
    // How much (c′) changes with roughness at small and at large angles, over its valid cells
    // up to σ = 0.2 rad.
    let change = |cols: &[usize]| {
        cols.iter()
            .flat_map(|&ci| (1..3).map(move |ri| (ri, ci)))
            .filter(|&(ri, ci)| en.cells_no_so[ri - 1][ci].is_valid())
            .map(|(ri, ci)| (dn[ri][ci] - dn[0][ci]).abs())
            .fold(0.0, f64::max)
    };
    let breaks = if invalid_no_so.is_empty() {
        "every cell is physically valid".to_string()
    } else {
        let above_one = |x: f64| x > 1.0 + polbrdf::analysis::emission::VALIDITY_TOLERANCE;
        let both = invalid_no_so
            .iter()
            .any(|(_, _, e)| above_one(1.0 - e.eps_p()));
        let rs: Vec<String> = invalid_no_so
            .iter()
            .map(|(ri, ci, e)| {
                format!(
                    "R_s = {:.3}, R_p = {:.3} at {}",
                    1.0 - e.eps_s(),
                    1.0 - e.eps_p(),
                    cell_name(*ri, *ci)
                )
            })
            .collect();
        format!(
            "it is not a physical emission: the s-polarized{} hemispherical reflectance exceeds 1 \
             in {} cells — {} — so the model creates energy there and Kirchhoff's law gives a \
             negative emissivity",
            if both {
                " (in the roughest cells also the p-polarized)"
            } else {
                ""
            },
            invalid_no_so.len(),
            rs.join("; ")
        )
    };
    let (small, large) = (change(&[c20, col(30.0)]), change(&[col(60.0), c80]));
    let like_table = if small < large {
        "the printed table's angular pattern"
    } else {
        "unlike the printed table, whose losses are largest at 60°–80°"
    };
    let first_invalid_80 = invalid_no_so
        .iter()
        .filter(|(_, ci, _)| *ci == c80)
        .map(|(ri, _, _)| ROUGHNESS[*ri])
        .fold(f64::INFINITY, f64::min);
    let no_so_verdict = if first_invalid_80.is_finite() {
        format!(
            "without shadowing the model violates energy conservation at 80° from σ = \
             {first_invalid_80:.1} rad on"
        )
    } else {
        format!(
            "without shadowing it stays {:.1}–{:.1} points RMS from the table",
            en.rms_no_so_valid.0, en.rms_no_so_valid.1
        )
    };
    let _ = write!(
        s,
        r#"
Without SO the emission DoLP changes by at most {small:.1} points at 20°–30° and by up to
{large:.1} points at 60°–80° up to σ = 0.2 rad — {like_table} — and its {} physically valid
cells (row 0 included) are
{:.1} (paper's model) and {:.1} (Lawrence/Wolff) points RMS from the table. But {breaks}.

**What it shows about the paper.** The paper sets its reflection model beside the "Lawrence
model", Wolff's model of polarized *thermal emission*, as if the two predicted the same
quantity. Only Table 1's smooth row behaves like emission — of a metal-like, high-|N| surface,
not of the paint's n = {N}. Reading the whole table as the emission this model predicts, the
consistent way to set it beside an emission model, does not give the rough rows: with
shadowing the emission depolarizes by {:.0}–{:.0} % at the first roughness step where the table
barely moves, and {no_so_verdict}. Neither the model's reflected DoLP ((a), (a′), (b)) nor its emitted DoLP ((c),
(c′)) gives the printed roughness dependence, so Table 1's agreement between "the model" and
"Lawrence" did not come from this model's equations under either reading.
"#,
        en.rms_no_so_valid.2,
        en.rms_no_so_valid.0,
        en.rms_no_so_valid.1,
        100.0 * fl_lo,
        100.0 * fl_hi,
    );
}
