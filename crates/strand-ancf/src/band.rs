//! Banded matrices and their factorizations: LDL^T for symmetric positive definite matrices,
//! LU with partial pivoting otherwise.
//!
//! A beam of cable elements numbered node by node couples each coordinate only with the
//! coordinates of its own and the neighbouring nodes, so its tangent and mass matrices are
//! banded with half-bandwidth `2 n_node - 1`. Factorizing the band costs O(n b^2) instead of
//! O(n^3) for a dense matrix; for the few hundred unknowns of a strand it also avoids the
//! set-up cost of a general sparse factorization.
//!
//! [`BandSolver::factorize`] takes the symmetric path when the matrix is exactly symmetric
//! (the tangent of a hyperelastic law, the mass matrix, the iteration matrix built from them)
//! and all pivots of its LDL^T factorization are positive: about a quarter of the work of LU
//! and half the work of a solve, and stable without pivoting for a positive definite matrix.
//! Otherwise (the non-symmetric tangents of the stick/slip laws, an indefinite matrix) it falls
//! back to LU with rows pivoted within the band (LAPACK `gbtrf` style).

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

    /// Adds the dense `m x m` block `block` (column-major) at rows and columns `i0..i0 + m`,
    /// which must lie in the band; with `mirror`, only its lower triangle is read, as a
    /// symmetric matrix (the result is then exactly symmetric if `self` was). Each band row
    /// of the block is one contiguous run of the storage.
    pub fn add_block(&mut self, i0: usize, m: usize, block: &[f64], mirror: bool) {
        debug_assert!(m >= 1 && m - 1 <= self.kl.min(self.ku) && i0 + m <= self.n);
        debug_assert_eq!(block.len(), m * m);
        let w = self.width();
        for a in 0..m {
            // Entry (i0 + a, i0 + b) sits at (i0 + a) w + kl + b - a.
            let start = (i0 + a) * w + self.kl - a;
            let row = &mut self.data[start..start + m];
            // Columns b <= a from row a of the block; the others from row a or, mirrored, from
            // column a.
            let (lower, upper) = row.split_at_mut(a + 1);
            for (b, x) in lower.iter_mut().enumerate() {
                *x += block[a + b * m];
            }
            if mirror {
                for (x, y) in upper.iter_mut().zip(&block[a * m + a + 1..(a + 1) * m]) {
                    *x += y;
                }
            } else {
                for (b, x) in upper.iter_mut().enumerate() {
                    *x += block[a + (a + 1 + b) * m];
                }
            }
        }
    }

    /// `y = A x`.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        match self.kl + self.ku + 1 {
            15 => self.mul_vec_fixed::<15>(x, y),
            23 => self.mul_vec_fixed::<23>(x, y),
            _ => self.mul_vec_rows(0, self.n, x, y),
        }
    }

    /// `y = A x` with the full rows (`kl + ku + 1 = N` entries) as fixed-size arrays.
    fn mul_vec_fixed<const N: usize>(&self, x: &[f64], y: &mut [f64]) {
        let (n, kl, w) = (self.n, self.kl, self.width());
        if n < N {
            return self.mul_vec_rows(0, n, x, y);
        }
        // Rows kl ..= n - 1 - ku hold N entries starting at column i - kl.
        let (first, last) = (kl, n - (N - kl));
        self.mul_vec_rows(0, first, x, y);
        for i in first..=last {
            let row: &[f64; N] = self.data[i * w..i * w + N].try_into().expect("N entries");
            let xs: &[f64; N] = x[i - kl..i - kl + N].try_into().expect("N entries");
            y[i] = dot(row, xs);
        }
        self.mul_vec_rows(last + 1, n, x, y);
    }

    /// Rows `from..to` of `y = A x`.
    fn mul_vec_rows(&self, from: usize, to: usize, x: &[f64], y: &mut [f64]) {
        let w = self.width();
        for (i, yi) in y.iter_mut().enumerate().take(to).skip(from) {
            let lo = i.saturating_sub(self.kl);
            let hi = (i + self.ku).min(self.n - 1);
            let start = i * w + (lo + self.kl - i);
            *yi = dot(&self.data[start..start + (hi - lo + 1)], &x[lo..=hi]);
        }
    }

    /// `y = |A| |x|`, entry by entry: `y_i = sum_j |a_ij| |x_j|`, the scale of the round-off in
    /// `A x` (each term carries a relative error of the order of the unit round-off).
    pub fn abs_mul_vec(&self, x: &[f64], y: &mut [f64]) {
        let w = self.width();
        for (i, yi) in y.iter_mut().enumerate() {
            let lo = i.saturating_sub(self.kl);
            let hi = (i + self.ku).min(self.n - 1);
            let start = i * w + (lo + self.kl - i);
            *yi = self.data[start..start + (hi - lo + 1)]
                .iter()
                .zip(&x[lo..=hi])
                .map(|(a, b)| (a * b).abs())
                .sum();
        }
    }

    /// `self += a * other` (same shape).
    pub fn add_scaled(&mut self, a: f64, other: &BandMatrix) {
        debug_assert_eq!((self.n, self.kl, self.ku), (other.n, other.kl, other.ku));
        for (s, o) in self.data.iter_mut().zip(&other.data) {
            *s += a * o;
        }
    }

    /// Whether the matrix is exactly symmetric (`kl == ku` and every mirrored pair equal).
    #[inline(never)]
    pub fn is_symmetric(&self) -> bool {
        if self.kl != self.ku {
            return false;
        }
        let (n, b, w) = (self.n, self.kl, self.width());
        // Entry (i, i + d) of row i sits at offset b + d; its mirror (i + d, i) at offset b - d
        // of row i + d.
        (0..n).all(|i| {
            (1..=b.min(n - 1 - i))
                .all(|d| self.data[i * w + b + d] == self.data[(i + d) * w + b - d])
        })
    }

    /// Largest magnitude of the entries; `None` if one is not finite.
    fn scale(&self) -> Option<f64> {
        // Four independent lanes; a non-finite entry turns its lane's `v * 0` sum into NaN.
        let (mut m, mut z) = ([0.0f64; 4], [0.0f64; 4]);
        let chunks = self.data.chunks_exact(4);
        let rest = chunks.remainder();
        for c in chunks {
            for k in 0..4 {
                let a = c[k].abs();
                if a > m[k] {
                    m[k] = a;
                }
                z[k] += c[k] * 0.0;
            }
        }
        for &v in rest {
            if v.abs() > m[0] {
                m[0] = v.abs();
            }
            z[0] += v * 0.0;
        }
        if z.iter().any(|v| v.is_nan()) {
            return None;
        }
        Some(m.into_iter().fold(0.0, f64::max))
    }

    /// Factorizes in place into `P A = L U` (row pivots in `pivots`); `false` if singular
    /// or not finite.
    fn factorize_in_place(&mut self, pivots: &mut Vec<usize>, scale: f64) -> bool {
        match (self.kl, self.ku) {
            (7, 7) => self.factorize_in_place_fixed::<15>(pivots, scale),
            (11, 11) => self.factorize_in_place_fixed::<23>(pivots, scale),
            _ => self.factorize_in_place_fixed::<0>(pivots, scale),
        }
    }

    /// [`Self::factorize_in_place`] with the pivot row's `N = kl + ku + 1` entries from the
    /// diagonal on as fixed-size arrays where the band is full (`N = 0`: no fixed size). The
    /// same operations in the same order.
    #[inline(always)]
    fn factorize_in_place_fixed<const N: usize>(
        &mut self,
        pivots: &mut Vec<usize>,
        scale: f64,
    ) -> bool {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        let w = self.width();
        pivots.clear();
        pivots.resize(n, 0);
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
            // Row k from column k on, and the rows below it (disjoint borrows).
            let (head, tail) = self.data.split_at_mut((k + 1) * w);
            let rk = &mut head[k * w + kl..(k + 1) * w][..=last_col - k];
            if p != k {
                let o = (p - k - 1) * w + kl - (p - k);
                rk.swap_with_slice(&mut tail[o..o + rk.len()]);
            }
            let pivot = rk[0];
            if N > 0 && rk.len() == N {
                let rk: &[f64; N] = (&*rk).try_into().expect("N entries");
                for i in k + 1..=last_row {
                    // Row i from column k on: offset kl - (i - k).
                    let o = (i - k - 1) * w + kl - (i - k);
                    let ri: &mut [f64; N] = (&mut tail[o..o + N]).try_into().expect("N entries");
                    let l = ri[0] / pivot;
                    ri[0] = l;
                    if l != 0.0 {
                        for c in 1..N {
                            ri[c] -= l * rk[c];
                        }
                    }
                }
                continue;
            }
            for i in k + 1..=last_row {
                // Row i from column k on: offset kl - (i - k).
                let o = (i - k - 1) * w + kl - (i - k);
                let ri = &mut tail[o..o + rk.len()];
                let l = ri[0] / pivot;
                ri[0] = l;
                if l != 0.0 {
                    for (a, b) in ri[1..].iter_mut().zip(&rk[1..]) {
                        *a -= l * b;
                    }
                }
            }
        }
        true
    }
}

/// `sum_i a_i b_i` with four partial sums (the rows are short: the latency of one chained
/// sum would dominate).
#[inline(always)]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut s = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            s[k] += x[k] * y[k];
        }
    }
    let mut t = (s[0] + s[2]) + (s[1] + s[3]);
    for (x, y) in ra.iter().zip(rb) {
        t += x * y;
    }
    t
}

/// LDL^T factors of a symmetric band matrix with half-bandwidth `b`: `lower` holds row `i`
/// of L at offsets `0..b` (columns `i - b .. i`), `upper` row `k` of L^T at offsets `0..b`
/// (columns `k + 1 ..= k + b`), `diag` holds D.
#[derive(Debug, Clone, Default)]
struct Ldlt {
    n: usize,
    b: usize,
    lower: Vec<f64>,
    upper: Vec<f64>,
    diag: Vec<f64>,
    /// `1 / D`.
    inv_diag: Vec<f64>,
    /// Column `k` below the diagonal during the factorization.
    col: Vec<f64>,
}

impl Ldlt {
    /// Factorizes the symmetric `a`; `false` if a pivot is not positive (beyond round-off of
    /// `scale`), i.e. `a` is not numerically positive definite.
    fn factorize(&mut self, a: &BandMatrix, scale: f64) -> bool {
        match a.kl {
            7 => self.factorize_fixed::<7>(a, scale),
            11 => self.factorize_fixed::<11>(a, scale),
            _ => self.factorize_fixed::<0>(a, scale),
        }
    }

    /// [`Self::factorize`] with the column updates unrolled for the half-bandwidth `B = b`
    /// where the band is full (`B = 0`: no fixed size); the same operations in the same order.
    #[inline(always)]
    fn factorize_fixed<const B: usize>(&mut self, a: &BandMatrix, scale: f64) -> bool {
        let (n, b) = (a.n, a.kl);
        let (w, bw) = (a.width(), b + 1);
        self.n = n;
        self.b = b;
        // Working copy of the lower band, row i at offsets 0..=b (column i - b + offset).
        let work = &mut self.lower;
        work.clear();
        work.resize(n * bw, 0.0);
        for i in 0..n {
            let lo = i.saturating_sub(b);
            let src = i * w + (lo + a.kl - i);
            work[i * bw + lo + b - i..(i + 1) * bw].copy_from_slice(&a.data[src..=i * w + a.kl]);
        }
        self.diag.clear();
        self.diag.resize(n, 0.0);
        self.inv_diag.clear();
        self.inv_diag.resize(n, 0.0);
        let tiny = f64::EPSILON * 1e-6 * scale;
        self.col.resize(b, 0.0);
        for k in 0..n {
            let dk = work[k * bw + b];
            if dk.is_nan() || dk <= tiny {
                return false;
            }
            self.diag[k] = dk;
            let inv = 1.0 / dk;
            self.inv_diag[k] = inv;
            let hi = (k + b).min(n - 1);
            let m = hi - k;
            if B > 0 && m == B {
                // Rows k + 1 ..= k + B of the band, as one slice.
                let rows = &mut work[(k + 1) * bw..(k + 1 + B) * bw];
                let mut c = [0.0; B];
                // Column k below the diagonal: a_jk (kept for the update) and l_jk = a_jk / d_k.
                for t in 0..B {
                    // Row k + 1 + t holds column k at offset b - 1 - t.
                    let e = &mut rows[t * bw + B - 1 - t];
                    c[t] = *e;
                    *e *= inv;
                }
                // a_ij -= l_ik a_jk for k < j <= i <= k + b.
                for t in 0..B {
                    let row = &mut rows[t * bw..(t + 1) * bw];
                    let lik = row[B - 1 - t];
                    if lik != 0.0 {
                        // Columns k + 1 ..= i at offsets b - t ..= b.
                        for u in 0..=t {
                            row[B - t + u] -= lik * c[u];
                        }
                    }
                }
                continue;
            }
            // Column k below the diagonal: a_jk (kept for the update) and l_jk = a_jk / d_k.
            let c = &mut self.col[..m];
            for (t, ct) in c.iter_mut().enumerate() {
                let j = k + 1 + t;
                let e = &mut work[j * bw + k + b - j];
                *ct = *e;
                *e *= inv;
            }
            // a_ij -= l_ik a_jk for k < j <= i <= k + b.
            for t in 0..m {
                let i = k + 1 + t;
                let row = &mut work[i * bw..(i + 1) * bw];
                let lik = row[k + b - i];
                if lik != 0.0 {
                    // Columns k + 1 ..= i at offsets k + 1 + b - i ..= b.
                    for (x, cj) in row[k + 1 + b - i..].iter_mut().zip(&c[..=t]) {
                        *x -= lik * cj;
                    }
                }
            }
        }
        // L^T by rows for the forward substitution.
        self.upper.clear();
        self.upper.resize(n * b, 0.0);
        for k in 0..n {
            for j in k + 1..=(k + b).min(n - 1) {
                self.upper[k * b + (j - k - 1)] = self.lower[j * bw + k + b - j];
            }
        }
        true
    }

    /// Solves `L D L^T x = rhs` in place.
    fn solve(&self, x: &mut [f64]) {
        match self.b {
            7 => self.solve_fixed::<7>(x),
            11 => self.solve_fixed::<11>(x),
            _ => self.solve_fixed::<0>(x),
        }
    }

    /// [`Self::solve`] with the full columns of `B = b` entries as fixed-size arrays
    /// (`B = 0`: no fixed size).
    #[inline(always)]
    fn solve_fixed<const B: usize>(&self, x: &mut [f64]) {
        let (n, b, bw) = (self.n, self.b, self.b + 1);
        // L y = rhs, column by column (rows of L^T).
        for k in 0..n {
            let xk = x[k];
            let hi = (k + b).min(n - 1);
            if B > 0 && hi == k + B {
                let xs: &mut [f64; B] = (&mut x[k + 1..=hi]).try_into().expect("B entries");
                let u: &[f64; B] = self.upper[k * b..k * b + B].try_into().expect("B entries");
                for t in 0..B {
                    xs[t] -= u[t] * xk;
                }
            } else {
                for (xi, u) in x[k + 1..=hi].iter_mut().zip(&self.upper[k * b..]) {
                    *xi -= u * xk;
                }
            }
        }
        for (xi, d) in x.iter_mut().zip(&self.inv_diag) {
            *xi *= d;
        }
        // L^T x = y, row by row of L from the bottom.
        for i in (0..n).rev() {
            let xi = x[i];
            if B > 0 && i >= B {
                let xs: &mut [f64; B] = (&mut x[i - B..i]).try_into().expect("B entries");
                let l: &[f64; B] = self.lower[i * bw..i * bw + B]
                    .try_into()
                    .expect("B entries");
                for t in 0..B {
                    xs[t] -= l[t] * xi;
                }
            } else {
                let lo = i.saturating_sub(b);
                let row = &self.lower[i * bw + lo + b - i..i * bw + b];
                for (xk, l) in x[lo..i].iter_mut().zip(row) {
                    *xk -= l * xi;
                }
            }
        }
    }
}

/// A reusable factorization workspace: refactorizes a matrix without allocating.
#[derive(Debug, Clone, Default)]
pub struct BandSolver {
    lu: Option<BandMatrix>,
    pivots: Vec<usize>,
    ldlt: Ldlt,
    /// Whether the last factorization is the symmetric one.
    symmetric: bool,
}

impl BandSolver {
    /// Factorizes `a` (LDL^T if it is symmetric positive definite, else LU with pivoting);
    /// `false` if it is singular or not finite.
    pub fn factorize(&mut self, a: &BandMatrix) -> bool {
        let Some(scale) = a.scale() else {
            return false;
        };
        self.symmetric = a.is_symmetric() && self.ldlt.factorize(a, scale);
        if self.symmetric {
            return true;
        }
        match &mut self.lu {
            Some(m) if m.n == a.n && m.kl == a.kl && m.ku == a.ku => {
                m.data.copy_from_slice(&a.data)
            }
            _ => self.lu = Some(a.clone()),
        }
        let m = self.lu.as_mut().expect("set above");
        m.factorize_in_place(&mut self.pivots, scale)
    }

    /// Whether the last factorization used the symmetric (LDL^T) path.
    pub fn is_symmetric(&self) -> bool {
        self.symmetric
    }

    /// Solves `A x = b` in place with the last factorization.
    pub fn solve(&self, b: &mut [f64]) {
        if self.symmetric {
            return self.ldlt.solve(b);
        }
        let m = self.lu.as_ref().expect("factorize before solve");
        solve_factored(m, &self.pivots, b);
    }
}

fn solve_factored(a: &BandMatrix, pivots: &[usize], b: &mut [f64]) {
    match (a.kl, a.ku) {
        (7, 7) => solve_factored_fixed::<7, 14>(a, pivots, b),
        (11, 11) => solve_factored_fixed::<11, 22>(a, pivots, b),
        _ => solve_factored_fixed::<0, 0>(a, pivots, b),
    }
}

/// [`solve_factored`] with `L`'s columns (`KL = kl` entries) and `U`'s rows (`KU2 = kl + ku`
/// entries right of the diagonal) as fixed-size arrays where the band is full (0: no fixed
/// size); the same operations in the same order.
#[inline(always)]
fn solve_factored_fixed<const KL: usize, const KU2: usize>(
    a: &BandMatrix,
    pivots: &[usize],
    b: &mut [f64],
) {
    let (n, kl, ku) = (a.n, a.kl, a.ku);
    let w = a.width();
    // Forward: apply the row swaps and L.
    for k in 0..n {
        let p = pivots[k];
        if p != k {
            b.swap(k, p);
        }
        let bk = b[k];
        if bk != 0.0 {
            // Entry (i, k) of row i sits at offset k + kl - i: one row down is w - 1 further.
            let step = w - 1;
            let mut idx = a.index(k, k) + step;
            if KL > 0 && k + KL < n {
                let bs: &mut [f64; KL] = (&mut b[k + 1..=k + KL]).try_into().expect("KL");
                for bi in bs.iter_mut() {
                    *bi -= a.data[idx] * bk;
                    idx += step;
                }
                continue;
            }
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
        // Sequential subtraction (not a separate sum): the ill-conditioned statics of very
        // thin strands (EA L^2 / EI = 1e7) are sensitive to the rounding of this loop.
        let mut s = b[i];
        if KU2 > 0 && hi == i + KU2 {
            let upper: &[f64; KU2] = a.data[row + 1..=row + KU2].try_into().expect("KU2");
            let xs: &[f64; KU2] = b[i + 1..=hi].try_into().expect("KU2");
            for t in 0..KU2 {
                s -= upper[t] * xs[t];
            }
        } else {
            let upper = &a.data[row + 1..=row + (hi - i)];
            for (u, x) in upper.iter().zip(&b[i + 1..=hi]) {
                s -= u * x;
            }
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

    /// A random symmetric band matrix, made positive definite by a dominant diagonal when
    /// `shift` is large.
    fn symmetric(n: usize, b: usize, shift: f64, seed: &mut u64) -> BandMatrix {
        let mut a = BandMatrix::zeros(n, b, b);
        for i in 0..n {
            a.add(i, i, lcg(seed) + shift);
            for j in i + 1..(i + b + 1).min(n) {
                let v = lcg(seed);
                a.add(i, j, v);
                a.add(j, i, v);
            }
        }
        a
    }

    #[test]
    fn symmetric_positive_definite_matrices_use_ldlt() {
        let mut seed = 11u64;
        for (n, b) in [(1, 0), (2, 1), (5, 2), (40, 7), (123, 11), (9, 11)] {
            let a = symmetric(n, b, 2.0 * b as f64 + 1.0, &mut seed);
            assert!(a.is_symmetric());
            let mut solver = BandSolver::default();
            assert!(solver.factorize(&a));
            assert!(solver.is_symmetric(), "n {n} b {b}");
            let rhs: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
            let mut x = rhs.clone();
            solver.solve(&mut x);
            // Same solution as the LU of a copy made non-symmetric by an explicit zero.
            let mut lu = BandSolver::default();
            let mut a2 = BandMatrix::zeros(n, b, b + 1);
            for i in 0..n {
                for j in 0..n {
                    if a.in_band(i, j) {
                        a2.add(i, j, a.get(i, j));
                    }
                }
            }
            assert!(lu.factorize(&a2) && !lu.is_symmetric());
            let mut y = rhs.clone();
            lu.solve(&mut y);
            for i in 0..n {
                assert!(
                    (x[i] - y[i]).abs() < 1e-12 * (1.0 + y[i].abs()),
                    "n {n}: {i}"
                );
            }
        }
    }

    #[test]
    fn indefinite_or_non_symmetric_matrices_fall_back_to_lu() {
        let mut seed = 5u64;
        // Symmetric, indefinite (zero shift): LU with pivoting.
        let a = symmetric(30, 7, 0.0, &mut seed);
        let mut solver = BandSolver::default();
        assert!(solver.factorize(&a));
        assert!(!solver.is_symmetric());
        let rhs: Vec<f64> = (0..30).map(|_| lcg(&mut seed)).collect();
        let mut x = rhs.clone();
        solver.solve(&mut x);
        let mut ax = vec![0.0; 30];
        a.mul_vec(&x, &mut ax);
        for (p, q) in ax.iter().zip(&rhs) {
            assert!((p - q).abs() < 1e-9);
        }
        // One asymmetric entry.
        let mut b = symmetric(30, 7, 20.0, &mut seed);
        b.add(3, 5, 1e-14);
        assert!(!b.is_symmetric());
        assert!(solver.factorize(&b));
        assert!(!solver.is_symmetric());
        // The same solver goes back to LDL^T for a symmetric matrix.
        let c = symmetric(30, 7, 20.0, &mut seed);
        assert!(solver.factorize(&c) && solver.is_symmetric());
    }

    #[test]
    fn reports_singular_matrices() {
        let a = BandMatrix::zeros(4, 1, 1);
        assert!(!BandSolver::default().factorize(&a));
        let mut b = BandMatrix::zeros(2, 1, 1);
        b.add(0, 0, f64::NAN);
        assert!(!BandSolver::default().factorize(&b));
    }

    /// A dense block added in one pass lands where entry-by-entry adds put it; mirrored, only
    /// its lower triangle counts and the result is exactly symmetric.
    #[test]
    fn blocks_add_like_entries() {
        let mut seed = 7;
        let (n, m, i0) = (12, 8, 3);
        let block: Vec<f64> = (0..m * m).map(|_| lcg(&mut seed)).collect();
        for mirror in [false, true] {
            let mut a = BandMatrix::zeros(n, 7, 7);
            let mut b = a.clone();
            a.add_block(i0, m, &block, mirror);
            for c in 0..m {
                for r in 0..m {
                    let v = if mirror && c > r {
                        block[c + r * m]
                    } else {
                        block[r + c * m]
                    };
                    b.add(i0 + r, i0 + c, v);
                }
            }
            assert_eq!(a, b);
            assert_eq!(a.is_symmetric(), mirror);
        }
    }
}
