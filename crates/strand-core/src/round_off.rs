//! The round-off floor of an energy balance: the work that the round-off of the internal
//! forces can do on a strand over the distance it has travelled (J).
//!
//! A model's internal force at a node is a sum of section forces computed from the
//! coordinates, whose size is up to the strand length `L`. The strain of a division of length
//! `l = L / n` (an element, a segment) is a difference of such coordinates over `l`, so its
//! round-off is `eps L / l = n eps` (machine epsilon `eps`), whatever the strain itself; the
//! curvature's, a second difference, is `n^2 eps / L`. A node's force carries that round-off
//! times the stiffness, `EA n eps` axially and `EI n^3 eps / L^2` from the bending moment over
//! `l`, and [`OPERATIONS`] more for the shape-function sums, norms and products that make each
//! term. Over the `n + 1` nodes, whose speeds sum to at most `n + 1` times their root mean
//! square, the round-off forces do at most `(n + 1) F_node v_rms` of work per second, and over
//! the run at most `(n + 1) F_node s` with `s` the distance travelled at the root mean square
//! speed. An energy balance cannot be checked below that: a strand at rest is moved by the
//! round-off forces alone, and the energy the balance then measures is of their size (the
//! section-3 strand at rest on 8 elements, 0.01 s: a balance error of 1.1e-24 J with Verlet
//! against a floor of 3.0e-22 J). The bound is a worst case, every node's round-off force
//! along its velocity: over the section-3 pendulum's 1 s swing on 30 elements the floor is
//! 4.7e-7 J, 6e-7 of its largest kinetic energy (0.76 J).

/// Round-off operations counted per force term: the four-term shape-function sums of `r'` and
/// `r''` (their coefficients add up to about 3 / l and 12 / l^2 in absolute value), the norm
/// and the product with the gradient.
pub const OPERATIONS: f64 = 16.0;

/// The round-off of a strand model's internal forces, and the work it can do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BalanceFloor {
    /// The round-off of the internal forces summed over the nodes (N).
    force: f64,
    /// Nodes.
    nodes: f64,
    /// Axial stiffness times length (J) and the round-off of a strain (`n eps`).
    axial: (f64, f64),
    /// Bending stiffness times length (J m^2) and the round-off of a curvature
    /// (`n^2 eps / L`, 1/m).
    bending: (f64, f64),
}

impl BalanceFloor {
    /// The floor of a strand of `length` (m), axial stiffness `axial` (N) and bending
    /// stiffness `bending` (N m^2), divided into `divisions` elements or segments along its
    /// length.
    pub fn new(axial: f64, bending: f64, length: f64, divisions: usize) -> BalanceFloor {
        let n = divisions.max(1) as f64;
        let node = OPERATIONS
            * f64::EPSILON
            * (axial.abs() * n + bending.abs() * n.powi(3) / (length * length));
        BalanceFloor {
            force: (n + 1.0) * node,
            nodes: n + 1.0,
            axial: (axial.abs() * length, n * f64::EPSILON),
            bending: (bending.abs() * length, n * n * f64::EPSILON / length),
        }
    }

    /// The round-off of the internal force at one node (N).
    pub fn node_force(&self) -> f64 {
        self.force / (self.nodes)
    }

    /// The round-off of an evaluation of the elastic energy `elastic` (J): the stored energy
    /// `1/2 EA L eps_s^2` of a strain computed with the round-off `d = n eps` is off by
    /// `EA L |eps_s| d + 1/2 EA L d^2`, and `EA L |eps_s|` is `sqrt(2 EA L E)` for a uniform
    /// strain storing `E`; the same for the curvature, with EI. [`OPERATIONS`] times that:
    /// the energies a balance compares at two instants differ by that much with no motion to
    /// speak of (one Verlet step of 1e-10 s of a strand at rest: 2e-23 J).
    pub fn evaluation(&self, elastic: f64) -> f64 {
        let e = elastic.abs();
        let term = |(k, d): (f64, f64)| (2.0 * k * e).sqrt() * d + 0.5 * k * d * d;
        OPERATIONS * (term(self.axial) + term(self.bending))
    }

    /// The work (J) the round-off forces can do over a path of `path` (m) at the strand's
    /// root mean square speed.
    pub fn work(&self, path: f64) -> f64 {
        self.force * path
    }
}

/// The distance a strand travels at the root mean square speed of its mass (m): the path
/// [`BalanceFloor::work`] takes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Travel {
    /// Distance so far (m).
    pub distance: f64,
    /// Time of the last sample (s).
    t: f64,
    /// Root mean square speed at the last sample (m/s).
    speed: f64,
}

impl Travel {
    /// A path starting at time `t` (s) with kinetic energy `kinetic` (J) of a strand of mass
    /// `mass` (kg).
    pub fn start(t: f64, kinetic: f64, mass: f64) -> Travel {
        Travel {
            distance: 0.0,
            t,
            speed: rms_speed(kinetic, mass),
        }
    }

    /// Adds the stretch up to time `t` (s), at which the kinetic energy is `kinetic` (J), at
    /// the larger of the speeds at its ends (a bound on the mean over a step).
    pub fn advance(&mut self, t: f64, kinetic: f64, mass: f64) {
        let speed = rms_speed(kinetic, mass);
        self.distance += (t - self.t).abs() * speed.max(self.speed);
        self.t = t;
        self.speed = speed;
    }
}

/// Root mean square speed of a mass `mass` (kg) with kinetic energy `kinetic` (J).
fn rms_speed(kinetic: f64, mass: f64) -> f64 {
    if mass > 0.0 {
        (2.0 * kinetic.max(0.0) / mass).sqrt()
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_floor_grows_with_stiffness_divisions_and_path() {
        let f = BalanceFloor::new(5.2e4, 0.0, 1.0, 8);
        // 9 nodes of 16 eps EA 8.
        let want = 9.0 * 16.0 * f64::EPSILON * 5.2e4 * 8.0;
        assert!((f.work(1.0) - want).abs() < 1e-12 * want);
        assert_eq!(f.work(0.0), 0.0);
        // Twice the divisions: 17 nodes of 16 eps EA 16.
        let finer = BalanceFloor::new(5.2e4, 0.0, 1.0, 16).work(1.0);
        assert!((finer - want * (17.0 * 16.0) / (9.0 * 8.0)).abs() < 1e-12 * want);
        // Bending adds EI n^3 / L^2 to EA n: EI = EA L^2 / n^2 doubles the node's term.
        let b = BalanceFloor::new(5.2e4, 5.2e4 / 64.0, 1.0, 8);
        assert!((b.work(1.0) - 2.0 * want).abs() < 1e-12 * want);
    }

    #[test]
    fn the_evaluation_floor_is_the_energy_of_a_round_off_strain() {
        // No bending: 16 x 1/2 EA L (n eps)^2 with nothing stored, and the cross term
        // sqrt(2 EA L E) n eps with E stored.
        let f = BalanceFloor::new(5.2e4, 0.0, 1.0, 8);
        let d = 8.0 * f64::EPSILON;
        let rest = 16.0 * 0.5 * 5.2e4 * d * d;
        assert!((f.evaluation(0.0) - rest).abs() < 1e-12 * rest);
        let loaded = 16.0 * ((2.0 * 5.2e4 * 1e-3f64).sqrt() * d) + rest;
        assert!((f.evaluation(1e-3) - loaded).abs() < 1e-12 * loaded);
        // A stored energy of 1 mJ is known to about 3e-10 of itself.
        assert!(f.evaluation(1e-3) < 1e-9 * 1e-3);
    }

    #[test]
    fn the_path_is_the_rms_distance() {
        // Kinetic 1 J on 2 kg: 1 m/s.
        let mut p = Travel::start(0.0, 0.0, 2.0);
        p.advance(0.5, 1.0, 2.0);
        // The larger end speed over the stretch: 1 m/s for 0.5 s.
        assert!((p.distance - 0.5).abs() < 1e-15);
        p.advance(1.5, 4.0, 2.0);
        assert!((p.distance - 2.5).abs() < 1e-15);
        // No mass, no speed.
        let mut q = Travel::start(0.0, 1.0, 0.0);
        q.advance(1.0, 1.0, 0.0);
        assert_eq!(q.distance, 0.0);
    }
}
