//! Stable step of the explicit Stoermer-Verlet scheme, `h < 2 / omega_max`, with
//! `omega_max^2` the largest eigenvalue of `K x = lambda M x` of the assembled beam (free
//! coordinates) at the reference configuration, all wires sticking (the stiffest state).
//!
//! The largest eigenvalue comes from Lanczos iterations on `M^-1 K`, which is self-adjoint in
//! the `M` inner product: the band mass is factored once, and a few dozen products with the
//! band tangent give the top of the spectrum to a few digits even on fine meshes, where it is
//! clustered. The estimate adds the Lanczos residual bound to the largest Ritz value, so it
//! errs toward a smaller step. (A bound from the largest single-element eigenvalue is cheaper
//! but grows loose with refinement: the slope coordinates shared by neighbouring elements
//! stiffen the free element's highest modes, by a factor near 4 in step at 256 elements.)

use nalgebra::{DMatrix, SymmetricEigen};

use crate::band::{BandMatrix, BandSolver};
use crate::beam::{Beam, BeamError, Tangent};

/// Lanczos steps: the largest Ritz value is then converged to about 1e-4 on a 256-element
/// beam, whose top eigenvalues are spaced about 1/n apart.
const LANCZOS_STEPS: usize = 80;

/// Estimated stable step of Stoermer-Verlet (s): `2 / omega_max` at the reference
/// configuration with all wires sticking.
pub fn stable_step(beam: &Beam) -> Result<f64, BeamError> {
    let lambda = largest_eigenvalue(beam)?;
    if !(lambda.is_finite() && lambda > 0.0) {
        return Err(BeamError::Setup(format!(
            "largest eigenvalue of the stiffness over the mass is {lambda:e} 1/s^2"
        )));
    }
    Ok(2.0 / lambda.sqrt())
}

/// Upper estimate of the largest eigenvalue of `K x = lambda M x` (1/s^2).
fn largest_eigenvalue(beam: &Beam) -> Result<f64, BeamError> {
    let n = beam.dofs();
    if n == 0 {
        return Err(BeamError::Setup("the beam has no free coordinates".into()));
    }
    let b = beam.bandwidth();
    let mut k = BandMatrix::zeros(n, b, b);
    let slip = beam.initial_state();
    let mut trial = slip.clone();
    let mut force = vec![0.0; beam.coords()];
    beam.internal_with(
        beam.reference(),
        &slip,
        &mut trial,
        &mut force,
        Some((&mut k, Tangent::AllStick)),
        None,
    )?;
    let mut mass = BandSolver::default();
    if !mass.factorize(beam.mass()) {
        return Err(BeamError::Setup("mass matrix not invertible".into()));
    }
    let m_steps = LANCZOS_STEPS.min(n);
    // Lanczos basis `v_j` (M-orthonormal) and `M v_j`, column by column.
    let mut v: Vec<Vec<f64>> = Vec::with_capacity(m_steps + 1);
    let mut mv: Vec<Vec<f64>> = Vec::with_capacity(m_steps + 1);
    let mut alpha = Vec::with_capacity(m_steps);
    let mut beta: Vec<f64> = Vec::with_capacity(m_steps);
    // Deterministic start with every component present (a small linear congruential
    // sequence): the result does not depend on the run.
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut x: Vec<f64> = (0..n)
        .map(|_| {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect();
    let mut mx = vec![0.0; n];
    let mut w = vec![0.0; n];
    let m_norm = |x: &[f64], mx: &mut [f64]| -> f64 {
        beam.vector_mass().mul_vec(x, mx);
        dot(x, mx).max(0.0).sqrt()
    };
    let norm = m_norm(&x, &mut mx);
    scale(&mut x, 1.0 / norm);
    scale(&mut mx, 1.0 / norm);
    v.push(x);
    mv.push(mx);
    for j in 0..m_steps {
        // w = M^-1 K v_j.
        k.mul_vec(&v[j], &mut w);
        let a = dot(&w, &v[j]);
        mass.solve(&mut w);
        alpha.push(a);
        // Full reorthogonalization (twice) in the M inner product keeps the Ritz values
        // free of spurious copies.
        for _ in 0..2 {
            for (vi, mvi) in v.iter().zip(&mv) {
                let c = dot(&w, mvi);
                for (wk, vk) in w.iter_mut().zip(vi) {
                    *wk -= c * vk;
                }
            }
        }
        let mut mw = vec![0.0; n];
        let bnorm = m_norm(&w, &mut mw);
        let breakdown = bnorm.is_nan() || bnorm <= 1e-12 * a.abs().max(f64::MIN_POSITIVE);
        if j + 1 == m_steps || breakdown {
            beta.push(bnorm);
            break;
        }
        beta.push(bnorm);
        scale(&mut w, 1.0 / bnorm);
        scale(&mut mw, 1.0 / bnorm);
        v.push(std::mem::replace(&mut w, vec![0.0; n]));
        mv.push(mw);
    }
    let m = alpha.len();
    let t = DMatrix::from_fn(m, m, |i, j| {
        if i == j {
            alpha[i]
        } else if i + 1 == j {
            beta[i]
        } else if j + 1 == i {
            beta[j]
        } else {
            0.0
        }
    });
    let eig = SymmetricEigen::new(t);
    let (top, theta) =
        eig.eigenvalues
            .iter()
            .copied()
            .enumerate()
            .fold(
                (0, f64::NEG_INFINITY),
                |acc, (i, l)| {
                    if l > acc.1 { (i, l) } else { acc }
                },
            );
    // Some eigenvalue lies within beta_m |s_m| of the Ritz value theta.
    let residual = beta[m - 1] * eig.eigenvectors[(m - 1, top)].abs();
    Ok(theta + residual)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn scale(x: &mut [f64], s: f64) {
    for v in x {
        *v *= s;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::{BeamSpec, ElementKind, Support};
    use strand_core::section::{LawKind, SectionLaw};
    use strand_core::{Strand, StrandSpec};

    fn beam(elements: usize, element: ElementKind, end: Option<Support>) -> Beam {
        let s = Strand::new(StrandSpec::paper(1.0, 2.0e9, 5747.0)).unwrap();
        Beam::new(
            BeamSpec {
                elements,
                bending_points: None,
                mass_per_length: s.mass_per_length(),
                element,
                direction: [1.0, 0.0, 0.0],
                gravity: [0.0, -9.8065, 0.0],
                start: Some(Support::Pinned),
                end,
                ..Default::default()
            },
            SectionLaw::new(&s, LawKind::Hysteretic),
        )
        .unwrap()
    }

    /// Largest eigenvalue of the dense generalized problem, from `L^-1 K L^-T`.
    fn dense_largest(b: &Beam) -> f64 {
        let n = b.dofs();
        let w = b.bandwidth();
        let mut k = BandMatrix::zeros(n, w, w);
        let slip = b.initial_state();
        let mut trial = slip.clone();
        let mut force = vec![0.0; b.coords()];
        b.internal(
            b.reference(),
            &slip,
            &mut trial,
            &mut force,
            Some(&mut k),
            None,
        )
        .unwrap();
        let kd = DMatrix::from_fn(n, n, |i, j| 0.5 * (k.get(i, j) + k.get(j, i)));
        let md = DMatrix::from_fn(n, n, |i, j| b.mass().get(i, j));
        let linv = md.cholesky().unwrap().l().try_inverse().unwrap();
        let a = &linv * kd * linv.transpose();
        SymmetricEigen::new(a).eigenvalues.max()
    }

    /// The old bound: the largest eigenvalue of any single element (free-free), which is at
    /// least the assembly's.
    fn element_bound(b: &Beam) -> f64 {
        let me = b.element_mass();
        let linv = me.cholesky().unwrap().l().try_inverse().unwrap();
        (0..b.spec().elements)
            .map(|e| {
                let k = b.element_tangent(e, b.reference()).unwrap();
                let sym = (&k + k.transpose()) * 0.5;
                SymmetricEigen::new(&linv * sym * linv.transpose())
                    .eigenvalues
                    .max()
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn matches_the_dense_eigenvalue_on_small_and_larger_beams() {
        for (elements, kind, end) in [
            (6, ElementKind::Planar, None),
            (10, ElementKind::Spatial, Some(Support::Clamped)),
            (40, ElementKind::Planar, None),
            (32, ElementKind::Spatial, None),
        ] {
            let b = beam(elements, kind, end);
            let exact = dense_largest(&b);
            let est = largest_eigenvalue(&b).unwrap();
            let rel = (est - exact) / exact;
            assert!(
                (-1e-9..1e-3).contains(&rel),
                "{elements} {kind:?}: Lanczos {est:e}, dense {exact:e} ({rel:e})"
            );
        }
    }

    #[test]
    fn lies_below_the_element_bound() {
        for elements in [8, 64, 256] {
            let b = beam(elements, ElementKind::Planar, None);
            let est = largest_eigenvalue(&b).unwrap();
            let bound = element_bound(&b);
            assert!(
                est <= bound * (1.0 + 1e-9),
                "{elements}: {est:e} above the element bound {bound:e}"
            );
        }
    }
}
