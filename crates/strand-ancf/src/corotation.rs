//! Co-rotation of a kept Newton iteration matrix.
//!
//! The elastic forces are objective: a rigid rotation `R` of every node's position and slope
//! turns the forces with it, so the tangent at the rotated configuration is `R K R^T`, and the
//! mass matrix (`m_ij I` per node pair, eq. (44)) is unchanged. A strand swinging as a
//! pendulum turns by `omega h` per step, which is enough to spoil a kept iteration matrix
//! `S = beta' M + K`: its stiff axial part (`EA / l`, about a hundred times `beta' M` at
//! 1e-3 s steps) points along the old tangent, and its projection onto the soft transverse
//! directions slows modified Newton to a contraction of 0.3-0.5 per iteration.
//!
//! [`Corotation`] turns the kept matrix with the strand: each node gets the rotation that takes
//! its slope direction at factorization time to its current one, and a correction is solved
//! as `dq = R S^-1 R^T r` with `R` block diagonal over the nodes' position and slope vectors.
//! Neighbouring nodes turn by nearly the same angle (their difference is the change of the
//! element's bending), so the rotated matrix stays close to the current tangent over many
//! steps. Only the iteration matrix changes: the residual is exact, so the converged state is
//! the same.

use crate::beam::Beam;

/// Slopes shorter than this have no direction to turn with (the element checks reject far
/// larger compressions, so this only guards the division).
const MIN_SLOPE: f64 = 1e-12;

/// Node-wise rotations from the slopes of a reference configuration to the current ones,
/// applied to vectors of free coordinates.
///
/// Supports fix whole position or slope vectors, so the free coordinates are a sequence of
/// whole vectors: free vector `k` is free coordinates `dim k .. dim (k + 1)`.
#[derive(Debug, Clone)]
pub(crate) struct Corotation {
    /// Coordinates per node (4 planar, 6 spatial).
    nd: usize,
    /// Components of a position or slope (2 or 3).
    dim: usize,
    /// Node of each free vector.
    node: Vec<usize>,
    /// Unit slope directions of the reference configuration, `dim` per free vector.
    slopes: Vec<f64>,
    /// Current rotation of each free vector, `dim x dim` row-major.
    rot: Vec<f64>,
    /// Whether every rotation is the identity.
    identity: bool,
}

impl Corotation {
    /// The co-rotation of `beam`, with the reference configuration `q` (all coordinates).
    pub(crate) fn new(beam: &Beam, q: &[f64]) -> Corotation {
        let nd = beam.node_coords();
        let dim = nd / 2;
        let mut node = Vec::new();
        for g in (0..beam.coords()).step_by(dim) {
            if let Some(i) = beam.free_index(g) {
                debug_assert_eq!(i, dim * node.len());
                debug_assert!((1..dim).all(|c| beam.free_index(g + c) == Some(i + c)));
                node.push(g / nd);
            }
        }
        debug_assert_eq!(dim * node.len(), beam.dofs());
        let mut c = Corotation {
            nd,
            dim,
            slopes: vec![0.0; node.len() * dim],
            rot: vec![0.0; node.len() * dim * dim],
            node,
            identity: true,
        };
        c.reset(q);
        c
    }

    /// Coordinates of the node of free vector `k` in `q`.
    fn node<'q>(&self, q: &'q [f64], k: usize) -> &'q [f64] {
        &q[self.node[k] * self.nd..(self.node[k] + 1) * self.nd]
    }

    /// Makes `q` the reference configuration (the iteration matrix was built there).
    pub(crate) fn reset(&mut self, q: &[f64]) {
        for k in 0..self.node.len() {
            if self.dim == 2 {
                let s = slope_direction::<2>(self.node(q, k));
                self.slopes[2 * k..2 * k + 2].copy_from_slice(&s);
            } else {
                let s = slope_direction::<3>(self.node(q, k));
                self.slopes[3 * k..3 * k + 3].copy_from_slice(&s);
            }
        }
        self.identity = true;
    }

    /// Updates the rotations to the configuration `q`.
    pub(crate) fn update(&mut self, q: &[f64]) {
        self.identity = false;
        let Corotation {
            nd,
            node,
            slopes,
            rot,
            ..
        } = self;
        let at = |k: usize| &q[node[k] * *nd..(node[k] + 1) * *nd];
        // A node's position and slope turn together: one rotation per node.
        let first = |k: usize| k == 0 || node[k] != node[k - 1];
        if self.dim == 2 {
            let mut turn = [0.0; 4];
            for (k, r) in rot.as_chunks_mut::<4>().0.iter_mut().enumerate() {
                if first(k) {
                    turn = planar_turn(&slopes[2 * k..2 * k + 2], &slope_direction(at(k)));
                }
                *r = turn;
            }
        } else {
            let mut turn = [0.0; 9];
            for (k, r) in rot.as_chunks_mut::<9>().0.iter_mut().enumerate() {
                if first(k) {
                    turn = minimal_turn(&slopes[3 * k..3 * k + 3], &slope_direction(at(k)));
                }
                *r = turn;
            }
        }
    }

    /// Whether the nodes turn together: the mean of their rotation vectors (each rotation's
    /// skew part, the sine of its angle times its axis) is longer than the nodes' spread
    /// about it. A swinging strand turns as a whole; a strand that bends or chatters under a
    /// kept matrix turns its nodes apart, and turning each node's block of the matrix then
    /// carries the stiff axial coupling of neighbouring nodes into the soft transverse
    /// directions.
    pub(crate) fn turns_together(&self) -> bool {
        if self.identity {
            return true;
        }
        let (mut sum, mut squares, mut n) = ([0.0; 3], 0.0, 0.0);
        let mut add = |v: [f64; 3]| {
            for (s, x) in sum.iter_mut().zip(v) {
                *s += x;
            }
            squares += v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            n += 1.0;
        };
        if self.dim == 2 {
            for r in self.rot.as_chunks::<4>().0 {
                add([0.0, 0.0, r[2]]);
            }
        } else {
            for r in self.rot.as_chunks::<9>().0 {
                add([
                    0.5 * (r[7] - r[5]),
                    0.5 * (r[2] - r[6]),
                    0.5 * (r[3] - r[1]),
                ]);
            }
        }
        if n == 0.0 {
            return true;
        }
        let mean = sum.iter().map(|s| (s / n) * (s / n)).sum::<f64>();
        mean > squares / n - mean
    }

    /// Turns nothing until the next [`Self::update`]: the kept matrix is used as built.
    pub(crate) fn clear(&mut self) {
        self.identity = true;
    }

    /// `x <- R^T x` (`transpose`) or `x <- R x`, for a vector of free coordinates.
    pub(crate) fn apply(&self, x: &mut [f64], transpose: bool) {
        if self.identity {
            return;
        }
        if self.dim == 2 {
            let sign = if transpose { -1.0 } else { 1.0 };
            for (v, r) in x
                .as_chunks_mut::<2>()
                .0
                .iter_mut()
                .zip(self.rot.as_chunks::<4>().0)
            {
                let (c, s) = (r[0], sign * r[2]);
                *v = [c * v[0] - s * v[1], s * v[0] + c * v[1]];
            }
            return;
        }
        for (v, r) in x
            .as_chunks_mut::<3>()
            .0
            .iter_mut()
            .zip(self.rot.as_chunks::<9>().0)
        {
            let m = |i: usize, j: usize| {
                if transpose {
                    r[3 * j + i]
                } else {
                    r[3 * i + j]
                }
            };
            *v = std::array::from_fn(|i| m(i, 0) * v[0] + m(i, 1) * v[1] + m(i, 2) * v[2]);
        }
    }
}

/// The unit direction of the slope of a node with coordinates `node` (position, slope); NaN
/// where the slope is too short to have one (that node then keeps the identity).
fn slope_direction<const D: usize>(node: &[f64]) -> [f64; D] {
    let d = &node[D..2 * D];
    let n = d.iter().map(|x| x * x).sum::<f64>().sqrt();
    if n > MIN_SLOPE {
        std::array::from_fn(|c| d[c] / n)
    } else {
        [f64::NAN; D]
    }
}

/// The plane rotation (row-major) taking the unit direction `a` to `b`; the identity where
/// a direction is missing.
fn planar_turn(a: &[f64], b: &[f64; 2]) -> [f64; 4] {
    let (c, s) = (a[0] * b[0] + a[1] * b[1], a[0] * b[1] - a[1] * b[0]);
    if c.is_finite() && s.is_finite() {
        [c, -s, s, c]
    } else {
        [1.0, 0.0, 0.0, 1.0]
    }
}

/// The minimal rotation (row-major) taking the unit direction `a` to `b`,
/// `I + [v]x + [v]x^2 / (1 + c)` with `v = a x b` and `c = a . b`; the identity where a
/// direction is missing or `b` has turned nearly around (no unique axis).
fn minimal_turn(a: &[f64], b: &[f64; 3]) -> [f64; 9] {
    let v = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    if c.is_nan() || c <= -0.5 {
        return [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    }
    let f = 1.0 / (1.0 + c);
    let vx = [[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]];
    std::array::from_fn(|ij| {
        let (i, j) = (ij / 3, ij % 3);
        let vv: f64 = (0..3).map(|m| vx[i][m] * vx[m][j]).sum();
        f64::from(u8::from(i == j)) + vx[i][j] + f * vv
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::band::BandMatrix;
    use crate::beam::{BeamSpec, ElementKind, Support};
    use strand_core::{LawKind, SectionLaw, Strand, StrandSpec};

    fn beam(element: ElementKind, start: Option<Support>) -> Beam {
        let s = Strand::new(StrandSpec::paper(0.2, 2.0e9, 5747.0)).unwrap();
        Beam::new(
            BeamSpec {
                elements: 4,
                bending_points: None,
                mass_per_length: s.mass_per_length(),
                element,
                direction: [1.0, 0.0, 0.0],
                gravity: [0.0, -9.81, 0.0],
                start,
                end: None,
                ..Default::default()
            },
            SectionLaw::new(&s, LawKind::Continuous),
        )
        .unwrap()
    }

    /// The beam's nodes on an arc in the XY plane (curvature `k`, strain `eps`), turned by
    /// `phi` about the Z axis through the origin.
    fn arc(beam: &Beam, k: f64, eps: f64, phi: f64) -> Vec<f64> {
        let nd = beam.node_coords();
        let mut q = beam.reference().to_vec();
        let turn = |x: f64, y: f64| (x * phi.cos() - y * phi.sin(), x * phi.sin() + y * phi.cos());
        for j in 0..q.len() / nd {
            let s = j as f64 * beam.element_length();
            let (x, y) = ((k * s).sin() / k, (1.0 - (k * s).cos()) / k);
            let (tx, ty) = ((k * s).cos(), (k * s).sin());
            let (x, y) = turn(x * (1.0 + eps), y * (1.0 + eps));
            let (tx, ty) = turn(tx * (1.0 + eps), ty * (1.0 + eps));
            let dim = nd / 2;
            q[j * nd] = x;
            q[j * nd + 1] = y;
            q[j * nd + dim] = tx;
            q[j * nd + dim + 1] = ty;
        }
        q
    }

    fn tangent(beam: &Beam, q: &[f64]) -> BandMatrix {
        let b = beam.bandwidth();
        let mut k = BandMatrix::zeros(beam.dofs(), b, b);
        let slip = beam.initial_state();
        let mut trial = slip.clone();
        let mut force = vec![0.0; beam.coords()];
        beam.internal(q, &slip, &mut trial, &mut force, Some(&mut k), None)
            .unwrap();
        k
    }

    /// The spatial element's section frame is carried by the minimal rotation from the
    /// straight strand's direction, so the second derivatives of its curvature components
    /// depend slightly on the absolute orientation: its tangent is objective only to about
    /// 2e-7 of the largest stiffness for the turns tested here (the planar one to rounding).
    const TOL_SPATIAL: f64 = 1e-6;

    /// Turning the strand rigidly turns its tangent: `K(R q) = R K(q) R^T` with the node-wise
    /// rotations taken from the slopes, so a co-rotated kept matrix is the current one.
    #[test]
    fn a_rigid_turn_turns_the_tangent() {
        for element in [ElementKind::Planar, ElementKind::Spatial] {
            for start in [None, Some(Support::Pinned), Some(Support::Clamped)] {
                let beam = beam(element, start);
                let (q0, q1) = (arc(&beam, 4.0, 1e-3, 0.0), arc(&beam, 4.0, 1e-3, 0.7));
                let (k0, k1) = (tangent(&beam, &q0), tangent(&beam, &q1));
                let mut rot = Corotation::new(&beam, &q0);
                rot.update(&q1);
                let n = beam.dofs();
                let scale = (0..n).map(|i| k1.get(i, i).abs()).fold(0.0, f64::max);
                let tol = if element == ElementKind::Planar {
                    1e-9
                } else {
                    TOL_SPATIAL
                };
                for j in 0..n {
                    // Column j of R K(q0) R^T against column j of K(q1).
                    let mut x = vec![0.0; n];
                    x[j] = 1.0;
                    rot.apply(&mut x, true);
                    let mut y = vec![0.0; n];
                    k0.mul_vec(&x, &mut y);
                    rot.apply(&mut y, false);
                    for (i, yi) in y.iter().enumerate() {
                        let d = (yi - k1.get(i, j)).abs();
                        assert!(
                            d <= tol * scale,
                            "{element:?} {start:?}: entry ({i}, {j}) off by {d:e} of {scale:e}"
                        );
                    }
                }
                // Unturned, the kept matrix is itself.
                rot.update(&q0);
                let mut x: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
                let x0 = x.clone();
                rot.apply(&mut x, false);
                for (a, b) in x.iter().zip(&x0) {
                    assert!((a - b).abs() <= 1e-15);
                }
            }
        }
    }

    /// A rigid turn turns the nodes together; bending the arc the other way about its middle
    /// turns them apart (by +0.8 to -0.8 rad along the strand), and a kept matrix is then
    /// left unturned.
    #[test]
    fn turns_together_tells_a_swing_from_bending() {
        for element in [ElementKind::Planar, ElementKind::Spatial] {
            let beam = beam(element, None);
            let q0 = arc(&beam, 4.0, 0.0, 0.0);
            let mut rot = Corotation::new(&beam, &q0);
            assert!(rot.turns_together(), "{element:?}: unturned");
            rot.update(&arc(&beam, 4.0, 1e-3, 0.3));
            assert!(rot.turns_together(), "{element:?}: rigid turn");
            rot.update(&arc(&beam, -4.0, 0.0, 0.8));
            assert!(!rot.turns_together(), "{element:?}: bent");
            rot.clear();
            let mut x: Vec<f64> = (0..beam.dofs()).map(|i| (i as f64).cos()).collect();
            let x0 = x.clone();
            rot.apply(&mut x, false);
            assert_eq!(x, x0, "{element:?}: cleared");
        }
    }

    /// A node whose slope has no direction (zero length), or whose slope has turned nearly
    /// around in space, keeps the identity instead of spreading NaN or a huge rotation.
    #[test]
    fn degenerate_slopes_keep_the_identity() {
        for element in [ElementKind::Planar, ElementKind::Spatial] {
            let beam = beam(element, Some(Support::Pinned));
            let nd = beam.node_coords();
            let dim = nd / 2;
            let q0 = arc(&beam, 4.0, 0.0, 0.0);
            let mut q1 = arc(&beam, 4.0, 0.0, 0.3);
            // Node 2: no slope; node 3: slope reversed.
            q1[2 * nd + dim..2 * nd + 2 * dim].fill(0.0);
            for c in 0..dim {
                q1[3 * nd + dim + c] = -q0[3 * nd + dim + c];
            }
            let mut rot = Corotation::new(&beam, &q0);
            rot.update(&q1);
            let n = beam.dofs();
            let x0: Vec<f64> = (0..n).map(|i| 1.0 + (i as f64).sin()).collect();
            let mut x = x0.clone();
            rot.apply(&mut x, false);
            assert!(x.iter().all(|v| v.is_finite()), "{element:?}");
            // Free vectors of node 2 (position, slope) are 2 * 2 - 1 and 2 * 2 (the pinned
            // node 0 has only its slope free).
            for g in [3, 4] {
                let r = dim * g..dim * (g + 1);
                assert_eq!(x[r.clone()], x0[r], "{element:?}: free vector {g}");
            }
            if element == ElementKind::Spatial {
                let r = 3 * 5..3 * 7;
                assert_eq!(x[r.clone()], x0[r], "reversed slope");
            }
        }
    }
}
