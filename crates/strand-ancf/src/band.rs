//! Banded matrices and their LU factorization with partial pivoting.
//!
//! A beam of cable elements numbered node by node couples each coordinate only with the
//! coordinates of its own and the neighbouring nodes, so its tangent and mass matrices are
//! banded with half-bandwidth `2 n_node - 1`. Factorizing the band costs O(n b^2) instead of
//! O(n^3) for a dense matrix; for the few hundred unknowns of a strand it also avoids the
//! set-up cost of a general sparse factorization. Pivoting rows within the band (LAPACK
//! `gbtrf` style) keeps the factorization stable for the non-symmetric, possibly indefinite
//! tangents of the stick/slip law.

/// A square band matrix with `kl` sub- and `ku` super-diagonals, stored by rows with room for
/// the `kl` extra super-diagonals that pivoting fills in.
#[derive(Debug, Clone, PartialEq)]
pub struct BandMatrix {
    n: usize,
    kl: usize,
    ku: usize,
    /// Row `i` holds columns `i - kl ..= i + kl + ku` at offsets `0 ..= 2 kl + ku`.
    data: Vec<f64>,
}

impl BandMatrix {
    /// A zero `n x n` band matrix with `kl` sub- and `ku` super-diagonals.
    pub fn zeros(n: usize, kl: usize, ku: usize) -> Self {
        BandMatrix {
            n,
            kl,
            ku,
            data: vec![0.0; n * (2 * kl + ku + 1)],
        }
    }

    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.n
    }

    fn width(&self) -> usize {
        2 * self.kl + self.ku + 1
    }

    #[inline]
    fn index(&self, i: usize, j: usize) -> usize {
        i * self.width() + (j + self.kl - i)
    }

    /// Sets every entry to zero, keeping the storage.
    pub fn fill_zero(&mut self) {
        self.data.fill(0.0);
    }

    /// Whether `(i, j)` lies in the band.
    #[inline]
    pub fn in_band(&self, i: usize, j: usize) -> bool {
        i < self.n && j < self.n && j + self.kl >= i && j <= i + self.ku
    }

    /// Entry `(i, j)` (zero outside the band).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        if self.in_band(i, j) {
            self.data[self.index(i, j)]
        } else {
            0.0
        }
    }

    /// Adds `v` to entry `(i, j)`, which must lie in the band.
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        debug_assert!(self.in_band(i, j), "({i}, {j}) outside the band");
        let k = self.index(i, j);
        self.data[k] += v;
    }

    /// `y = A x`.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        let w = self.width();
        for (i, yi) in y.iter_mut().enumerate().take(self.n) {
            let lo = i.saturating_sub(self.kl);
            let hi = (i + self.ku).min(self.n - 1);
            let start = i * w + (lo + self.kl - i);
            let row = &self.data[start..start + (hi - lo + 1)];
            *yi = row.iter().zip(&x[lo..=hi]).map(|(a, b)| a * b).sum();
        }
    }

    /// `self += a * other` (same shape).
    pub fn add_scaled(&mut self, a: f64, other: &BandMatrix) {
        debug_assert_eq!((self.n, self.kl, self.ku), (other.n, other.kl, other.ku));
        for (s, o) in self.data.iter_mut().zip(&other.data) {
            *s += a * o;
        }
    }

    /// Factorizes in place into `P A = L U` (row pivots in `pivots`); `false` if singular
    /// or not finite.
    fn factorize_in_place(&mut self, pivots: &mut Vec<usize>) -> bool {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        pivots.clear();
        pivots.resize(n, 0);
        let mut scale = 0.0f64;
        for v in &self.data {
            if !v.is_finite() {
                return false;
            }
            scale = scale.max(v.abs());
        }
        for k in 0..n {
            let last_row = (k + kl).min(n - 1);
            let last_col = (k + kl + ku).min(n - 1);
            let mut p = k;
            let mut best = self.data[self.index(k, k)].abs();
            for i in k + 1..=last_row {
                let v = self.data[self.index(i, k)].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            pivots[k] = p;
            if best <= f64::EPSILON * 1e-6 * scale || best == 0.0 {
                return false;
            }
            if p != k {
                for j in k..=last_col {
                    let (a, b) = (self.index(k, j), self.index(p, j));
                    self.data.swap(a, b);
                }
            }
            let pivot = self.data[self.index(k, k)];
            for i in k + 1..=last_row {
                let ik = self.index(i, k);
                let l = self.data[ik] / pivot;
                self.data[ik] = l;
                if l != 0.0 {
                    let (ri, rk) = (self.index(i, k + 1), self.index(k, k + 1));
                    for d in 0..last_col - k {
                        self.data[ri + d] -= l * self.data[rk + d];
                    }
                }
            }
        }
        true
    }
}

/// A reusable factorization workspace: refactorizes a matrix without allocating.
#[derive(Debug, Clone, Default)]
pub struct BandSolver {
    lu: Option<BandMatrix>,
    pivots: Vec<usize>,
}

impl BandSolver {
    /// Copies `a` into the workspace and factorizes it; `false` if it is singular.
    pub fn factorize(&mut self, a: &BandMatrix) -> bool {
        match &mut self.lu {
            Some(m) if m.n == a.n && m.kl == a.kl && m.ku == a.ku => {
                m.data.copy_from_slice(&a.data)
            }
            _ => self.lu = Some(a.clone()),
        }
        let m = self.lu.as_mut().expect("set above");
        m.factorize_in_place(&mut self.pivots)
    }

    /// Solves `A x = b` in place with the last factorization.
    pub fn solve(&self, b: &mut [f64]) {
        let m = self.lu.as_ref().expect("factorize before solve");
        solve_factored(m, &self.pivots, b);
    }
}

fn solve_factored(a: &BandMatrix, pivots: &[usize], b: &mut [f64]) {
    let (n, kl, ku) = (a.n, a.kl, a.ku);
    // Forward: apply the row swaps and L.
    for k in 0..n {
        let p = pivots[k];
        if p != k {
            b.swap(k, p);
        }
        let bk = b[k];
        if bk != 0.0 {
            // Entry (i, k) of row i sits at offset k + kl - i: one row down is w - 1 further.
            let step = a.width() - 1;
            let mut idx = a.index(k, k) + step;
            for bi in &mut b[k + 1..=(k + kl).min(n - 1)] {
                *bi -= a.data[idx] * bk;
                idx += step;
            }
        }
    }
    // Backward: U has kl + ku super-diagonals.
    for i in (0..n).rev() {
        let hi = (i + kl + ku).min(n - 1);
        let row = a.index(i, i);
        let upper = &a.data[row + 1..=row + (hi - i)];
        // Sequential subtraction (not a separate sum): the ill-conditioned statics of very
        // thin strands (EA L^2 / EI = 1e7) are sensitive to the rounding of this loop.
        let mut s = b[i];
        for (u, x) in upper.iter().zip(&b[i + 1..=hi]) {
            s -= u * x;
        }
        b[i] = s / a.data[row];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lcg(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    }

    #[test]
    fn solves_like_dense_lu_with_pivoting() {
        let mut seed = 7u64;
        for (n, kl, ku) in [(1, 0, 0), (5, 1, 2), (40, 7, 7), (123, 11, 11), (30, 3, 5)] {
            let mut a = BandMatrix::zeros(n, kl, ku);
            let mut dense = faer::Mat::<f64>::zeros(n, n);
            for i in 0..n {
                for j in 0..n {
                    if a.in_band(i, j) {
                        // Weak diagonal: pivoting is needed.
                        let v = lcg(&mut seed) + if i == j { 0.01 } else { 0.0 };
                        a.add(i, j, v);
                        dense[(i, j)] = v;
                    }
                }
            }
            let b: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
            let mut x = b.clone();
            let mut solver = BandSolver::default();
            assert!(solver.factorize(&a));
            solver.solve(&mut x);
            // Residual of the band solve.
            let mut ax = vec![0.0; n];
            a.mul_vec(&x, &mut ax);
            let res = ax
                .iter()
                .zip(&b)
                .map(|(p, q)| (p - q).abs())
                .fold(0.0, f64::max);
            assert!(res < 1e-10, "n {n}: residual {res}");
            // Agreement with faer's dense LU.
            let rhs = faer::Mat::<f64>::from_fn(n, 1, |i, _| b[i]);
            use faer::linalg::solvers::Solve;
            let xd = dense.partial_piv_lu().solve(&rhs);
            for i in 0..n {
                assert!((xd[(i, 0)] - x[i]).abs() < 1e-8 * (1.0 + x[i].abs()));
            }
        }
    }

    #[test]
    fn reports_singular_matrices() {
        let a = BandMatrix::zeros(4, 1, 1);
        assert!(!BandSolver::default().factorize(&a));
        let mut b = BandMatrix::zeros(2, 1, 1);
        b.add(0, 0, f64::NAN);
        assert!(!BandSolver::default().factorize(&b));
    }
}
