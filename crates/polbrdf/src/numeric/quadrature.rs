//! Gauss–Legendre quadrature: the hemispherical normalization of D (docs/model.md §5), the albedo
//! (§11) and every hemispherical integral.

use std::sync::OnceLock;

/// Nodes and weights of the `N`-point Gauss–Legendre rule on [−1, 1], by Newton iteration on
/// the Legendre polynomial (Golub–Welsch accuracy for small N, no tables to mistype).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    for i in 0..n.div_ceil(2) {
        // Tricomi's initial guess for the i-th root.
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 0 { 1.0 } else { p1 };
            let pn1 = if n <= 1 { 1.0 } else { p0 };
            dp = n as f64 * (z * pn - pn1) / (z * z - 1.0);
            let dz = pn / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        x[i] = -z;
        x[n - 1 - i] = z;
        let wi = 2.0 / ((1.0 - z * z) * dp * dp);
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    (x, w)
}

/// The 20-point rule, computed once.
pub(crate) fn gl20() -> &'static (Vec<f64>, Vec<f64>) {
    gl(20)
}

/// The `n`-point rule (`1 ≤ n ≤ 32`), computed once per `n`.
///
/// # Panics
/// For `n` outside `1..=32`.
pub fn gl(n: usize) -> &'static (Vec<f64>, Vec<f64>) {
    static RULES: [OnceLock<(Vec<f64>, Vec<f64>)>; 33] = [const { OnceLock::new() }; 33];
    assert!(
        (1..=32).contains(&n),
        "Gauss–Legendre rules of 1 to 32 points"
    );
    RULES[n].get_or_init(|| gauss_legendre(n))
}

/// The nodes and weights of the composite 20-point rule on `panels` equal panels of
/// `[lo, hi]`: `∫_lo^hi f ≈ Σ w·f(x)`.
pub fn composite(lo: f64, hi: f64, panels: usize) -> impl Iterator<Item = (f64, f64)> {
    let (x, w) = gl20();
    let h = (hi - lo) / panels as f64;
    let half = 0.5 * h;
    (0..panels).flat_map(move |p| {
        let mid = lo + (p as f64 + 0.5) * h;
        x.iter()
            .zip(w)
            .map(move |(xi, wi)| (mid + half * xi, wi * half))
    })
}

/// `∫_lo^hi f` by the 20-point rule on `panels` equal panels ([`composite`]).
pub fn integrate(f: impl Fn(f64) -> f64, lo: f64, hi: f64, panels: usize) -> f64 {
    composite(lo, hi, panels).map(|(x, w)| w * f(x)).sum()
}
