//! Small dense linear algebra for symmetric matrices (coherency matrices, normal equations).

/// Eigen-decomposition of a small real symmetric matrix (fixed size), by
/// [`symmetric_eigen_dyn`]. Returns the eigenvalues (unsorted) and the eigenvectors as the
/// columns of the second value.
pub fn symmetric_eigen<const N: usize>(a: [[f64; N]; N]) -> ([f64; N], [[f64; N]; N]) {
    let flat: Vec<f64> = a.iter().flatten().copied().collect();
    let (values, vectors) = symmetric_eigen_dyn(&flat, N);
    let mut ev = [0.0; N];
    ev.copy_from_slice(&values);
    let mut v = [[0.0; N]; N];
    for (i, row) in v.iter_mut().enumerate() {
        row.copy_from_slice(&vectors[i * N..(i + 1) * N]);
    }
    (ev, v)
}

/// Eigen-decomposition of a real symmetric matrix of run-time size `n` (row-major `n×n`), by
/// cyclic Jacobi rotations. Returns eigenvalues and eigenvectors (column `j` of the returned
/// row-major matrix belongs to eigenvalue `j`).
pub fn symmetric_eigen_dyn(a: &[f64], n: usize) -> (Vec<f64>, Vec<f64>) {
    assert_eq!(a.len(), n * n, "symmetric_eigen_dyn: matrix must be n×n");
    let mut a = a.to_vec();
    let mut v = vec![0.0; n * n];
    for i in 0..n {
        v[i * n + i] = 1.0;
    }
    for _sweep in 0..100 {
        let (mut off, mut diag) = (0.0, 0.0);
        for p in 0..n {
            for q in 0..n {
                let x = a[p * n + q];
                if p == q {
                    diag += x * x;
                } else {
                    off += x * x;
                }
            }
        }
        if off == 0.0 || off <= 1e-30 * diag {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[p * n + q];
                if apq == 0.0 {
                    continue;
                }
                let theta = (a[q * n + q] - a[p * n + p]) / (2.0 * apq);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..n {
                    let (akp, akq) = (a[k * n + p], a[k * n + q]);
                    a[k * n + p] = c * akp - s * akq;
                    a[k * n + q] = s * akp + c * akq;
                }
                for k in 0..n {
                    let (apk, aqk) = (a[p * n + k], a[q * n + k]);
                    a[p * n + k] = c * apk - s * aqk;
                    a[q * n + k] = s * apk + c * aqk;
                }
                for k in 0..n {
                    let (vkp, vkq) = (v[k * n + p], v[k * n + q]);
                    v[k * n + p] = c * vkp - s * vkq;
                    v[k * n + q] = s * vkp + c * vkq;
                }
            }
        }
    }
    ((0..n).map(|i| a[i * n + i]).collect(), v)
}
