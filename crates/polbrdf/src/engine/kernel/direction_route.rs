//! The native direction route (`block::geometry_of_directions`) against the route it replaced
//! (the vectors converted to the sines and cosines of their angles, then the angle route's
//! stages): every entry of F within 1.2e-13·F00 in f64 (plus twice what the previous route
//! changes when one input component moves by ε·|w|, where it is that ill-conditioned), on the
//! peer benchmark's conductor, paint, a σ = 5° conductor and random materials (every term, eq. 3 included), over random,
//! grazing, near-specular, near-retro-reflection and degenerate directions (along the normal,
//! exactly specular, exactly retro-reflected, in the plane of incidence), at every length.

use super::index::SpectralCache;
use super::{Kernel, BLOCK};
use crate::engine::block::{self, AngleNeeds, Front, GeomScratch};
use crate::geometry::direction;
use crate::model::{AzimuthTerm, MaterialSpec};
use crate::numeric::math::{FastFused, FastUnfused, Math};
use crate::numeric::sample::SplitMix64;

/// A pair of direction vectors of one of the kinds the module documentation lists, of random
/// lengths, or with `pow2` of unit length as computed times a power of two (the kernel's
/// normalization without a square root).
fn pair(rng: &mut SplitMix64, pow2: bool) -> ([f64; 3], [f64; 3]) {
    let theta = |rng: &mut SplitMix64| rng.range(0.0, 89.9f64.to_radians());
    let phi = |rng: &mut SplitMix64| rng.range(-7.0, 7.0);
    let (ti, pi) = (theta(rng), phi(rng));
    let wi = direction(ti, pi);
    let grazing = |rng: &mut SplitMix64| {
        let p = phi(rng);
        let z = 10f64.powf(rng.range(-9.0, -2.0));
        let c = (1.0 - z * z).sqrt();
        [c * p.cos(), c * p.sin(), z]
    };
    let nudge = |w: [f64; 3], rng: &mut SplitMix64| {
        let e = 10f64.powf(rng.range(-10.0, -3.0));
        [
            w[0] + e * rng.range(-1.0, 1.0),
            w[1] + e * rng.range(-1.0, 1.0),
            w[2],
        ]
    };
    let (wi, wr) = match rng.below(12) {
        0 => ([0.0, 0.0, 1.0], direction(theta(rng), phi(rng))),
        1 => (wi, [0.0, 0.0, 1.0]),
        2 => ([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]),
        3 => (wi, [-wi[0], -wi[1], wi[2]]),
        4 => (wi, wi),
        5 => (wi, direction(theta(rng), pi)),
        6 => (wi, direction(theta(rng), pi + std::f64::consts::PI)),
        7 => (grazing(rng), grazing(rng)),
        8 => (wi, grazing(rng)),
        9 => (wi, nudge([-wi[0], -wi[1], wi[2]], rng)),
        10 => (wi, nudge(wi, rng)),
        _ => (wi, direction(theta(rng), phi(rng))),
    };
    let len = |rng: &mut SplitMix64| {
        if pow2 {
            2f64.powi(rng.below(41) as i32 - 20)
        } else {
            10f64.powf(rng.range(-6.0, 6.0))
        }
    };
    let (a, b) = (len(rng), len(rng));
    (wi.map(|c| c * a), wr.map(|c| c * b))
}

/// The largest `|ΔF_ij|/F00` of the two routes over `blocks` blocks of `pair`s, and how many
/// elements both sent to the one-geometry path (the rest: neither did).
fn compare<M: Math<F = f64>>(spec: &MaterialSpec, rng: &mut SplitMix64, blocks: usize) -> f64 {
    let m = spec.build().unwrap();
    let k = Kernel::new(&m);
    let needs = AngleNeeds::of(&k.params);
    let mut worst = 0.0_f64;
    let (mut new, mut old) = (
        GeomScratch::<BLOCK>::zeroed(),
        GeomScratch::<BLOCK>::zeroed(),
    );
    for b in 0..blocks {
        for j in 0..BLOCK {
            let (wi, wr) = pair(rng, b % 2 == 0);
            for c in 0..3 {
                (new.dirs[c][j], new.dirs[c + 3][j]) = (wi[c], wr[c]);
            }
        }
        old.dirs = new.dirs;
        block::geometry_of_directions::<M, BLOCK, true>(&mut new, needs);
        block::geometry_of_directions_via_angles::<M, BLOCK>(&mut old, needs);
        let idx = k.index.lanes::<BLOCK>(0, BLOCK, &mut SpectralCache::new());
        let run = |s: &GeomScratch<BLOCK>| {
            let (mut f, mut rows) = (Front::<BLOCK>::zeroed(), [[0.0; BLOCK]; 16]);
            block::front::<M, BLOCK>(&k.params, &s.geo, &idx, &mut f);
            block::mueller::<M, BLOCK>(&mut f, &s.geo, &mut rows);
            (f.fallback, rows)
        };
        let ((fb_new, f_new), (fb_old, f_old)) = (run(&new), run(&old));
        // The previous route's own spread where one component of the input moves by one
        // rounding of a unit vector's component (ε·|w|): far down D's tail (b·θN² in the
        // hundreds), near grazing and, for ΦN (eq. 3), near specular its relative change
        // reaches 1e-12 and more, which no two roundings of the geometry can undercut.
        let mut kappa = [0.0_f64; BLOCK];
        let mut moved = GeomScratch::<BLOCK>::zeroed();
        for c in 0..6 {
            moved.dirs = new.dirs;
            for j in 0..BLOCK {
                // One rounding of a unit vector's component: ε times the vector's length.
                let w = &new.dirs[3 * (c / 3)..3 * (c / 3) + 3];
                let len = (w[0][j] * w[0][j] + w[1][j] * w[1][j] + w[2][j] * w[2][j]).sqrt();
                moved.dirs[c][j] += f64::EPSILON * len;
            }
            block::geometry_of_directions_via_angles::<M, BLOCK>(&mut moved, needs);
            let (_, f_moved) = run(&moved);
            for j in 0..BLOCK {
                let d = (0..16)
                    .map(|e| (f_moved[e][j] - f_old[e][j]).abs())
                    .fold(0.0, f64::max);
                kappa[j] = kappa[j].max(d);
            }
        }
        for j in 0..BLOCK {
            assert_eq!(new.geo.valid[j], old.geo.valid[j]);
            assert_eq!(new.geo.out_of_range[j], old.geo.out_of_range[j]);
            if fb_new[j] || fb_old[j] {
                continue;
            }
            let f00 = f_old[0][j];
            let dev = (0..16)
                .map(|e| (f_new[e][j] - f_old[e][j]).abs())
                .fold(0.0, f64::max);
            let w: Vec<f64> = new.dirs.iter().map(|c| c[j]).collect();
            assert!(
                dev <= 1.2e-13 * f00 + 2.0 * kappa[j] || (f00 == 0.0 && dev == 0.0),
                "{spec:?}: w {w:?}: {:e}·F00 (F00 {f00:e}, κ {:e})\nnew {:?}\nold {:?}",
                dev / f00,
                kappa[j] / f00,
                (0..16).map(|e| f_new[e][j]).collect::<Vec<_>>(),
                (0..16).map(|e| f_old[e][j]).collect::<Vec<_>>(),
            );
            if f00 > 0.0 && kappa[j] <= 1e-14 * f00 {
                worst = worst.max(dev / f00);
            }
        }
    }
    worst
}

fn materials(rng: &mut SplitMix64) -> Vec<MaterialSpec> {
    let peer = MaterialSpec {
        k: 7.0,
        shadowing: false,
        ..MaterialSpec::new(1.2, 0.2f64.atan().to_degrees())
    };
    let narrow = MaterialSpec {
        k: 7.0,
        ..MaterialSpec::new(1.2, 5.0)
    };
    let eq3 = MaterialSpec {
        azimuth_term: AzimuthTerm::Eq3,
        ..MaterialSpec::new(1.5, 20.0)
    };
    let paint = crate::model::presets::preset("paint").unwrap();
    let mut all = vec![peer, narrow, eq3, paint];
    for _ in 0..12 {
        let n = rng.range(1.1, 2.5);
        let mut s = MaterialSpec::new(n, rng.range(1.0, 40.0));
        s.k = if rng.below(2) == 0 {
            0.0
        } else {
            rng.range(0.5, 8.0)
        };
        s.shadowing = rng.below(4) != 0;
        s.azimuth_term = if rng.below(3) == 0 {
            AzimuthTerm::Eq3
        } else {
            AzimuthTerm::None
        };
        s.rho_d = rng.range(0.0, 0.1);
        all.push(s);
    }
    all
}

#[test]
fn the_native_direction_route_stays_within_1_2e_13_of_the_previous_one() {
    let mut rng = SplitMix64::new(0x7ec7);
    let mut worst = 0.0_f64;
    for spec in materials(&mut rng) {
        worst = worst.max(compare::<FastUnfused>(&spec, &mut rng, 150));
        worst = worst.max(compare::<FastFused>(&spec, &mut rng, 30));
    }
    eprintln!("native direction route vs the previous one: worst {worst:e}·F00 (κ ≤ 1e-14)");
    assert!(worst <= 1.2e-13, "{worst:e}");
}
