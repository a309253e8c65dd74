//! The section law evaluated over arrays of points: what a parameter study of the section
//! (`strand.section` in Python, a curve of moment against curvature) calls once instead of a
//! loop of [`SectionLaw::planar`] calls.

use strand_core::SectionLaw;

/// The responses of [`evaluate_planar`], one entry per point (units: N, N m, N m^2, J/m).
#[derive(Debug)]
pub struct PlanarArrays<'a> {
    /// Axial force N (N).
    pub axial_force: &'a mut [f64],
    /// Bending moment M_z (N m), same sign as the curvature.
    pub moment: &'a mut [f64],
    /// Tangent stiffness dM/dkappa (N m^2).
    pub tangent: &'a mut [f64],
    /// Stored energy density (J/m).
    pub energy: &'a mut [f64],
    /// Slip work from the given state to this trial (J/m; hysteretic law, else 0).
    pub slip_work: &'a mut [f64],
    /// Number of slipping wires.
    pub slipping: &'a mut [f64],
    /// Trial state of every point, [`SectionLaw::state_len`] values each, point after point.
    pub state: &'a mut [f64],
}

/// Owned buffers for the responses of [`evaluate_planar`] at `points` points: what a caller
/// that keeps the results (Python's arrays, a test, a timing loop reusing them) allocates once.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanarOutputs {
    /// Axial force N (N).
    pub axial_force: Vec<f64>,
    /// Bending moment M_z (N m).
    pub moment: Vec<f64>,
    /// Tangent stiffness dM/dkappa (N m^2).
    pub tangent: Vec<f64>,
    /// Stored energy density (J/m).
    pub energy: Vec<f64>,
    /// Slip work (J/m).
    pub slip_work: Vec<f64>,
    /// Number of slipping wires.
    pub slipping: Vec<f64>,
    /// Trial state, `state_len` values per point.
    pub state: Vec<f64>,
}

impl PlanarOutputs {
    /// Zeroed buffers for `points` points of a law with `state_len` state values per point.
    pub fn zeros(points: usize, state_len: usize) -> Self {
        let v = || vec![0.0; points];
        PlanarOutputs {
            axial_force: v(),
            moment: v(),
            tangent: v(),
            energy: v(),
            slip_work: v(),
            slipping: v(),
            state: vec![0.0; points * state_len],
        }
    }

    /// The buffers as the output of [`evaluate_planar`].
    pub fn arrays(&mut self) -> PlanarArrays<'_> {
        PlanarArrays {
            axial_force: &mut self.axial_force,
            moment: &mut self.moment,
            tangent: &mut self.tangent,
            energy: &mut self.energy,
            slip_work: &mut self.slip_work,
            slipping: &mut self.slipping,
            state: &mut self.state,
        }
    }
}

/// A batch whose arrays do not fit together.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct BatchError(pub String);

/// Evaluates `law` in planar bending at the points `(strain[i], curvature[i], x[i])` (-, 1/m,
/// m), each from the committed state `state[i * n..(i + 1) * n]` (`n` =
/// [`SectionLaw::state_len`]; zeros are the straight, unslipped state), writing the responses
/// and trial states into `out`. Each point is [`SectionLaw::planar`] at its station, the same
/// values bit for bit; the station is rebuilt only where `x` changes from one point to the
/// next. A non-finite input is an error naming the point: a response never holds a NaN that
/// the input did not ask for.
pub fn evaluate_planar(
    law: &SectionLaw,
    strain: &[f64],
    curvature: &[f64],
    x: &[f64],
    state: &[f64],
    out: PlanarArrays<'_>,
) -> Result<(), BatchError> {
    let len = strain.len();
    let n = law.state_len();
    let lengths = [
        ("curvature", curvature.len()),
        ("x", x.len()),
        ("axial_force", out.axial_force.len()),
        ("moment", out.moment.len()),
        ("tangent", out.tangent.len()),
        ("energy", out.energy.len()),
        ("slip_work", out.slip_work.len()),
        ("slipping", out.slipping.len()),
    ];
    for (name, l) in lengths {
        if l != len {
            return Err(BatchError(format!(
                "{name} has {l} points, strain has {len}"
            )));
        }
    }
    for (name, l) in [("state", state.len()), ("trial state", out.state.len())] {
        if l != len * n {
            return Err(BatchError(format!(
                "{name} has {l} values, expected {len} points x {n}"
            )));
        }
    }
    let length = law.strand().length();
    for i in 0..len {
        let (e, k, at) = (strain[i], curvature[i], x[i]);
        if !(e.is_finite() && k.is_finite()) {
            return Err(BatchError(format!(
                "point {i}: strain {e} and curvature {k} must be finite"
            )));
        }
        if !(at.is_finite() && (0.0..=length).contains(&at)) {
            return Err(BatchError(format!(
                "point {i}: x = {at} must lie on the strand, in [0, {length}] m"
            )));
        }
        if let Some(bad) = state[i * n..(i + 1) * n].iter().find(|v| !v.is_finite()) {
            return Err(BatchError(format!("point {i}: state holds {bad}")));
        }
    }
    let mut station = None;
    for i in 0..len {
        let at = x[i];
        let st = match &station {
            Some((x0, st)) if *x0 == at => st,
            _ => &station.insert((at, law.station(at))).1,
        };
        let r = law.planar(
            st,
            strain[i],
            curvature[i],
            &state[i * n..(i + 1) * n],
            &mut out.state[i * n..(i + 1) * n],
        );
        out.axial_force[i] = r.axial_force;
        out.moment[i] = r.moment;
        out.tangent[i] = r.moment_curvature;
        out.energy[i] = r.energy;
        out.slip_work[i] = r.slip_work;
        out.slipping[i] = r.slipping as f64;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use strand_core::{LawKind, Strand};

    fn strand() -> Strand {
        let s = crate::Scene::parse(include_str!("../../../examples/nylon-1x8-hanging.json"))
            .expect("the example scene is valid");
        s.strand
    }

    fn try_run(
        law: &SectionLaw,
        e: &[f64],
        k: &[f64],
        x: &[f64],
        s: &[f64],
        len: usize,
    ) -> Result<PlanarOutputs, BatchError> {
        let mut out = PlanarOutputs::zeros(len, law.state_len());
        evaluate_planar(law, e, k, x, s, out.arrays())?;
        Ok(out)
    }

    fn run(law: &SectionLaw, e: &[f64], k: &[f64], x: &[f64], s: &[f64]) -> PlanarOutputs {
        try_run(law, e, k, x, s, e.len()).unwrap()
    }

    /// Each point is the scalar law from its own state, bit for bit, whether or not the
    /// station is shared with the point before.
    #[test]
    fn matches_the_scalar_law_point_by_point() {
        let strand = strand();
        for kind in [LawKind::Continuous, LawKind::Hysteretic, LawKind::Paper] {
            let law = SectionLaw::new(&strand, kind);
            let n = law.state_len();
            let k: Vec<f64> = (0..40).map(|i| (i as f64 - 20.0) * 0.37).collect();
            let e: Vec<f64> = (0..40).map(|i| 1e-4 * (i % 7) as f64).collect();
            let x: Vec<f64> = (0..40).map(|i| 0.01 * (i / 3) as f64).collect();
            let s: Vec<f64> = (0..40 * n).map(|j| 1e-6 * ((j % 5) as f64 - 2.0)).collect();
            let got = run(&law, &e, &k, &x, &s);
            for i in 0..40 {
                let st = law.station(x[i]);
                let mut trial = vec![0.0; n];
                let r = law.planar(&st, e[i], k[i], &s[i * n..(i + 1) * n], &mut trial);
                assert_eq!(
                    got.moment[i].to_bits(),
                    r.moment.to_bits(),
                    "{kind} point {i}"
                );
                assert_eq!(got.tangent[i].to_bits(), r.moment_curvature.to_bits());
                assert_eq!(got.energy[i].to_bits(), r.energy.to_bits());
                assert_eq!(&got.state[i * n..(i + 1) * n], &trial[..]);
            }
        }
    }

    proptest::proptest! {
        /// Any batch, any law: every point is the scalar law from its own state, bit for bit
        /// (runs of equal x share a station, as in a sweep over curvature at one station).
        #[test]
        fn any_batch_is_the_scalar_law(
            kind in proptest::sample::select(vec![
                LawKind::Continuous, LawKind::Paper, LawKind::Hysteretic, LawKind::Constant,
            ]),
            points in proptest::collection::vec(
                (-2e-3f64..4e-3, -2.0f64..2.0, 0usize..4, -1e-4f64..1e-4), 1..40),
        ) {
            let strand = strand();
            let law = SectionLaw::new(&strand, kind);
            let n = law.state_len();
            let e: Vec<f64> = points.iter().map(|p| p.0).collect();
            let k: Vec<f64> = points.iter().map(|p| p.1).collect();
            let x: Vec<f64> = points.iter().map(|p| p.2 as f64 * 0.7).collect();
            let s: Vec<f64> = points
                .iter()
                .flat_map(|p| (0..n).map(move |j| if j < n.saturating_sub(2) { p.3 } else { 0.0 }))
                .collect();
            let got = run(&law, &e, &k, &x, &s);
            for i in 0..points.len() {
                let st = law.station(x[i]);
                let mut trial = vec![0.0; n];
                let r = law.planar(&st, e[i], k[i], &s[i * n..(i + 1) * n], &mut trial);
                proptest::prop_assert_eq!(got.moment[i].to_bits(), r.moment.to_bits());
                proptest::prop_assert_eq!(got.tangent[i].to_bits(), r.moment_curvature.to_bits());
                proptest::prop_assert_eq!(got.energy[i].to_bits(), r.energy.to_bits());
                proptest::prop_assert_eq!(got.slip_work[i].to_bits(), r.slip_work.to_bits());
                proptest::prop_assert_eq!(&got.state[i * n..(i + 1) * n], &trial[..]);
            }
        }
    }

    #[test]
    fn rejects_mismatched_and_non_finite_inputs() {
        let law = SectionLaw::new(&strand(), LawKind::Continuous);
        let err = |e: &[f64], k: &[f64], x: &[f64]| {
            try_run(&law, e, k, x, &[], 2).expect_err("rejected").0
        };
        assert!(err(&[0.0, 0.0], &[1.0], &[0.0, 0.0]).starts_with("curvature has 1 points"));
        assert!(err(&[0.0, 0.0], &[1.0, f64::NAN], &[0.0; 2]).starts_with("point 1:"));
        assert!(err(&[0.0; 2], &[1.0; 2], &[0.0, 99.0]).contains("x = 99"));
    }
}
