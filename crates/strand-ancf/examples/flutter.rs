//! Why the `continuous` law is unfit for resolved dynamics: its bending moment depends on the
//! tension (`dM/d eps != 0`) while the axial force does not depend on the curvature, so the
//! tangent `K` is not symmetric, and along the section-3 pendulum's swing `M^-1 K` has a
//! complex pair of eigenvalues: an axial-bending vibration that grows by itself (flutter).
//! The symmetric part of the same `K` has real eigenvalues only. The `hysteretic` and
//! `constant` laws are shown beside it.
//!
//! ```text
//! cargo run --release -p strand-ancf --example flutter
//! ```
//!
//! The states come from generalized-alpha at 1 ms with spectral radius 0.9 (which damps the
//! mode); a run at 0.1 ms without numerical damping then shows the mode grown. The printed
//! growth rate is `Re sqrt(-mu)` of the eigenvalue `mu` of `M^-1 K` with the
//! largest one (1/s), with its frequency.
//!
//! Since the section law reads the tension recovered from the element means (module
//! `beam::strain_recovery`), the mode that grew at 250-770 1/s along the swing (and reached a
//! strain of -1.6e-3 at 0.1 ms within 0.2 s) shows only at t = 0.05 s, at 39 1/s, and the
//! 0.1 ms run stays within -2.9e-8: it fed on the sawtooth the line through each element's
//! two axial points put into the tension. `K` here is the analytic tangent, which leaves out
//! the coupling through the neighbouring elements' strains.

use nalgebra::DMatrix;
use strand_ancf::band::BandMatrix;
use strand_ancf::beam::{Beam, BeamSpec, ElementKind, Support};
use strand_ancf::dynamics::{DynamicOptions, Scheme, run_dynamic};
use strand_core::{LawKind, SectionLaw, Strand, StrandSpec};

const TIMES: [f64; 4] = [0.05, 0.1, 0.3, 0.6];

fn main() {
    let s = Strand::new(StrandSpec::paper(1.0, 2.0e9, 5747.0)).unwrap();
    for kind in [LawKind::Continuous, LawKind::Hysteretic, LawKind::Constant] {
        let beam = Beam::new(
            BeamSpec {
                elements: 30,
                bending_points: None,
                mass_per_length: s.mass_per_length(),
                element: ElementKind::Planar,
                direction: [1.0, 0.0, 0.0],
                gravity: [0.0, -9.8, 0.0],
                start: Some(Support::Pinned),
                end: None,
                ..Default::default()
            },
            SectionLaw::new(&s, kind),
        )
        .unwrap();
        println!("law {}:", kind.name());
        let scheme = Scheme::GeneralizedAlpha {
            step: 1e-3,
            spectral_radius: 0.9,
        };
        let n = beam.dofs();
        let m = DMatrix::from_fn(n, n, |i, j| beam.mass().get(i, j));
        let m_inv = m
            .try_inverse()
            .expect("the mass matrix is positive definite");
        for t in TIMES {
            // The state at t, with the law's committed slip state.
            let opts = DynamicOptions::new(t, scheme, t);
            let end = run_dynamic(&beam, &opts, &mut |_| {}).unwrap();
            let b = beam.bandwidth();
            let mut k = BandMatrix::zeros(n, b, b);
            let mut force = vec![0.0; beam.coords()];
            let mut trial = end.slip.clone();
            beam.internal(
                &end.q,
                &end.slip,
                &mut trial,
                &mut force,
                Some(&mut k),
                None,
            )
            .unwrap();
            let k = DMatrix::from_fn(n, n, |i, j| k.get(i, j));
            let sym = (&k + k.transpose()) * 0.5;
            let (g, f) = fastest_growth(&(&m_inv * &k));
            let (gs, _) = fastest_growth(&(&m_inv * &sym));
            let full = if g > 0.0 {
                format!("growth {g:6.1} 1/s at {f:6.1} Hz")
            } else {
                "no growing mode".to_string()
            };
            println!("  t = {t:.2} s: {full}; symmetric part of K: growth {gs:.1} 1/s");
        }
        // Resolved (0.1 ms, no numerical damping), the mode grows: the largest compression
        // at a bending point over 0.2 s (the strand's own weight stretches it by about 1e-8).
        let resolved = Scheme::GeneralizedAlpha {
            step: 1e-4,
            spectral_radius: 1.0,
        };
        let mut worst: f64 = 0.0;
        let run = run_dynamic(&beam, &DynamicOptions::new(0.2, resolved, 1e-3), &mut |f| {
            worst = f.points.iter().fold(worst, |w, p| w.max(-p.eps));
        })
        .unwrap();
        println!(
            "  0.1 ms steps, spectral radius 1, 0.2 s: largest compression {worst:.1e} (axial force \
             {:.2e} N; the strand weighs {:.2} N), energy balance error {:.1e} J",
            worst * beam.law().axial_stiffness(),
            s.mass_per_length() * s.length() * 9.8,
            run.balance_error
        );
    }
}

/// Largest growth rate `Re sqrt(-mu)` over the eigenvalues `mu` of `a` (1/s; the motion
/// `x'' = -a x` grows like `exp(Re sqrt(-mu) t)`), and the frequency of that mode (Hz).
fn fastest_growth(a: &DMatrix<f64>) -> (f64, f64) {
    a.complex_eigenvalues()
        .iter()
        .map(|mu| {
            let l = (-mu).sqrt();
            (l.re.abs(), l.im.abs() / (2.0 * std::f64::consts::PI))
        })
        .fold((0.0, 0.0), |best, x| if x.0 > best.0 { x } else { best })
}
