//! Finite-difference helpers shared by the integration tests.
#![allow(dead_code)]

use nalgebra::{SMatrix, SVector};

/// Central-difference gradient of `f` at `y` (step `h` scaled by `max(1, |y_i|)`).
pub fn fd_gradient<const N: usize>(
    f: impl Fn(&SVector<f64, N>) -> f64,
    y: &SVector<f64, N>,
    h: f64,
) -> SVector<f64, N> {
    SVector::<f64, N>::from_fn(|i, _| {
        let s = h * y[i].abs().max(1.0);
        let mut p = *y;
        let mut m = *y;
        p[i] += s;
        m[i] -= s;
        (f(&p) - f(&m)) / (2.0 * s)
    })
}

/// Central-difference Jacobian of the vector function `g` at `y` (column j = d g / d y_j).
pub fn fd_jacobian<const N: usize>(
    g: impl Fn(&SVector<f64, N>) -> SVector<f64, N>,
    y: &SVector<f64, N>,
    h: f64,
) -> SMatrix<f64, N, N> {
    let mut out = SMatrix::<f64, N, N>::zeros();
    for j in 0..N {
        let s = h * y[j].abs().max(1.0);
        let mut p = *y;
        let mut m = *y;
        p[j] += s;
        m[j] -= s;
        let col = (g(&p) - g(&m)) / (2.0 * s);
        out.set_column(j, &col);
    }
    out
}

/// Max-norm error of `approx` against `exact`, relative to `max(|exact|_max, floor)`.
pub fn rel_err<const R: usize, const C: usize>(
    approx: &SMatrix<f64, R, C>,
    exact: &SMatrix<f64, R, C>,
    floor: f64,
) -> f64 {
    (approx - exact).amax() / exact.amax().max(floor)
}

/// Small deterministic generator (xorshift64*) for seeded loops.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed.max(1))
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let v = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D);
        (v >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [a, b).
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit()
    }
}
