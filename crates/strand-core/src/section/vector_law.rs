//! The section law for a curvature vector `kappa = (kappa_y, kappa_z)` in the section frame
//! (3D bending, the spatial element): the moment and tangent of every wire's slider acting
//! through its lever vector, the friction limits turning with the bending direction, and the
//! slip work of an accepted step (module docs of `section`).

use super::direction::{BendingDirection, DIRECTION_STATE};
use super::layer_law::LayerLaw;
use super::slider::WireState;
use super::{LawKind, STATION_TAIL, SectionLaw, SectionResponse, Station, slip_work};

impl SectionLaw {
    /// Evaluates the law for a curvature vector `kappa = (kappa_y, kappa_z)` (1/m) in the
    /// section frame at strain `eps`; `slip` and `trial` as for [`Self::planar`].
    ///
    /// Each wire's slider works on its bending strain `e_i = l_i . kappa` and its force acts
    /// through its lever vector: `M = K_min kappa + sum_i F_i l_i` (module docs). The tangent
    /// is `K_min I + sum_i l_i (dF_i/de_i l_i + dF_i/dcap_i dcap_i/dkappa)`: the stick part
    /// is symmetric and positive definite, the second term is the friction limit of a
    /// slipping wire turning with the bending direction (for the `hysteretic` law beyond the
    /// still curvature only; below it the limits keep the stored direction, module docs).
    /// With `kappa_y = 0` the z components of the moment, its tangent `dM_z/dkappa_z` and
    /// `dM_z/deps`, and the energy are those of [`Self::planar`] bit for bit.
    pub fn vector(
        &self,
        st: &Station,
        eps: f64,
        kappa: [f64; 2],
        slip: &[f64],
        trial: &mut [f64],
    ) -> SectionResponse {
        self.vector_with::<true>(st, eps, kappa, slip, trial)
    }

    /// [`Self::vector`] without the slip work (`slip_work` zero), every other value and the
    /// trial state bit for bit: what a Newton iteration of the spatial element reads. The
    /// slip work's trapezoid (module `slip_work`) takes each slipping wire's friction limit
    /// at the step's start, its capstan gains at the committed bending direction, a second
    /// evaluation of them per slipping wire that only the books of the accepted iterate need:
    /// [`Self::vector`] there gives it.
    pub fn vector_unbooked(
        &self,
        st: &Station,
        eps: f64,
        kappa: [f64; 2],
        slip: &[f64],
        trial: &mut [f64],
    ) -> SectionResponse {
        self.vector_with::<false>(st, eps, kappa, slip, trial)
    }

    /// The slip work (J/m) of [`Self::vector`] at `eps`, `kappa` from the committed state
    /// `slip` to the trial state `trial` that [`Self::vector_unbooked`] (or [`Self::vector`])
    /// wrote for the same arguments, bit for bit: the books of the accepted iterate that
    /// the iterations left out. Both states are the station's whole state
    /// ([`Self::state_len`] values); 0 for the laws without slip work.
    ///
    /// Only the wires whose slip changed book work, and only their friction limits are
    /// evaluated, at the step's end and at its start (module `slip_work`). A wire that
    /// sticks keeps its slip; one that slips books the trapezoid of the limit on the side its
    /// trial force `k (e - s_old)` is on (the stretched side for a non-negative one, as the
    /// slider decides), and a slip that did not change books nothing.
    pub fn vector_slip_work(
        &self,
        st: &Station,
        eps: f64,
        kappa: [f64; 2],
        slip: &[f64],
        trial: &[f64],
    ) -> f64 {
        let n = st.wires.len();
        if self.kind != LawKind::Hysteretic || self.layers.is_empty() {
            return 0.0;
        }
        debug_assert!(slip.len() == self.state_len() && trial.len() == slip.len());
        // The directions and the strain of `vector_with`'s full state.
        let dir = BendingDirection::select(kappa, self.still(eps), &slip[n..], None);
        let eps_old = self.committed_strain(n, slip, eps);
        let dir_old = BendingDirection::stored(&slip[n..]).unwrap_or(dir);
        let mut work = 0.0;
        for (i, w) in st.wires.iter().enumerate() {
            let ds = trial[i] - slip[i];
            if ds == 0.0 {
                continue;
            }
            let law = self.layers[w.layer];
            let l = w.lever;
            let stretched = law.k * (l[0] * kappa[0] + l[1] * kappa[1] - slip[i]) >= 0.0;
            let side = usize::from(!stretched);
            let gains = self.turning_gains(&law, dir.wire_angle(w.phase)).0;
            let old = if dir_old.beta == dir.beta {
                gains
            } else {
                self.turning_gains(&law, dir_old.wire_angle(w.phase)).0
            };
            let cap = law.cap_scale(eps).0 * gains[side];
            work += slip_work::trapezoid(cap, law.cap_scale(eps_old).0 * old[side], ds);
        }
        work
    }

    /// [`Self::vector`], with the slip work where `SLIP_WORK`, else without it
    /// ([`Self::vector_unbooked`]).
    #[inline(always)]
    fn vector_with<const SLIP_WORK: bool>(
        &self,
        st: &Station,
        eps: f64,
        kappa: [f64; 2],
        slip: &[f64],
        trial: &mut [f64],
    ) -> SectionResponse {
        let (kb, dkb) = self.base_bending_at(eps);
        let mut r = SectionResponse {
            axial_force: self.axial_stiffness * eps,
            axial_stiffness: self.axial_stiffness,
            moment: [kb * kappa[0], kb * kappa[1]],
            moment_curvature: [[kb, 0.0], [0.0, kb]],
            moment_strain: if self.softening.is_some() {
                [dkb * kappa[0], dkb * kappa[1]]
            } else {
                [0.0; 2]
            },
            // Summed as in `planar_linear`, the out-of-plane term last.
            energy: 0.5 * self.axial_stiffness * eps * eps
                + 0.5 * kb * kappa[1] * kappa[1]
                + 0.5 * kb * kappa[0] * kappa[0],
            energy_strain: if self.softening.is_some() {
                0.5 * dkb * (kappa[1] * kappa[1] + kappa[0] * kappa[0])
            } else {
                0.0
            },
            energy_turn: [0.0; 2],
            slip_work: 0.0,
            slipping: 0,
        };
        if self.layers.is_empty() {
            return r;
        }
        let n = st.wires.len();
        let still = self.still(eps);
        let full = slip.len() == self.state_len() && slip.len() > n;
        let dir = if full && trial.len() == slip.len() {
            // No closed-form layer states in 3D: the next planar evaluation visits the wires.
            trial[n + STATION_TAIL..].fill(0.0);
            trial[n + DIRECTION_STATE] = eps;
            BendingDirection::select(kappa, still, &slip[n..], Some(&mut trial[n..]))
        } else {
            BendingDirection::of(kappa)
        };
        // The step's start: the committed strain and the committed bending direction (the
        // present one where none is stored: no wire has slipped yet), for the slip work's
        // trapezoid (module `slip_work`).
        let (eps_old, dir_old) = match (SLIP_WORK, full) {
            (false, _) => (eps, dir),
            (true, true) => (
                self.committed_strain(n, slip, eps),
                BendingDirection::stored(&slip[n..]).unwrap_or(dir),
            ),
            (true, false) => (self.committed_strain(n, slip, eps), dir),
        };
        for (i, w) in st.wires.iter().enumerate() {
            let law = self.layers[w.layer];
            let (scale, dscale) = law.cap_scale(eps);
            let l = w.lever;
            let theta = dir.wire_angle(w.phase);
            let (gains, dtheta_n, slopes) = self.turning_gains(&law, theta);
            let old = |pos: bool| {
                if !SLIP_WORK {
                    return 0.0;
                }
                let g = if dir_old.beta == dir.beta {
                    gains
                } else {
                    self.turning_gains(&law, dir_old.wire_angle(w.phase)).0
                };
                law.cap_scale(eps_old).0 * g[usize::from(!pos)]
            };
            let f = self.slide(
                law,
                i,
                l[0] * kappa[0] + l[1] * kappa[1],
                scale,
                gains,
                slip,
                trial,
                old,
            );
            // The friction limit of the active side turns with the bending direction:
            // d cap/d theta through the slip limit's angle theta_n(theta) (non-zero only while
            // slipping) ...
            let (dg_pos, dg_neg) = match slopes {
                Some(d) => (scale * d[0] * dtheta_n, scale * d[1] * dtheta_n),
                None => {
                    let dgain = scale * law.capstan * dtheta_n;
                    (dgain * (gains[0] + 1.0), dgain * (1.0 - gains[1]))
                }
            };
            let cap_theta = f.d_cap_pos * dg_pos + f.d_cap_neg * dg_neg;
            // ... times d theta/d kappa: theta = phi - beta (wrapped), so d|theta|/d kappa =
            // -sign(theta) d beta/d kappa.
            let sign = if theta < 0.0 { -1.0 } else { 1.0 };
            let dtheta = [-sign * dir.dbeta[0], -sign * dir.dbeta[1]];
            // The stored energy's dependence on the active limit, d E/d cap d cap/d kappa.
            let cap_energy = f.d_energy_cap * (f.d_cap_pos * dg_pos - f.d_cap_neg * dg_neg);
            let ms = (f.d_cap_pos * gains[0] + f.d_cap_neg * gains[1]) * dscale;
            for a in 0..2 {
                r.moment[a] += f.force * l[a];
                r.moment_strain[a] += ms * l[a];
                r.energy_turn[a] += cap_energy * dtheta[a];
                for j in 0..2 {
                    // The stick part summed symmetrically (and as in `planar` for a = j = z).
                    let stick = if a == j {
                        f.d_strain * l[a] * l[a]
                    } else {
                        f.d_strain * (l[0] * l[1])
                    };
                    r.moment_curvature[a][j] += stick + l[a] * (cap_theta * dtheta[j]);
                }
            }
            let cap_strain = (f.d_cap_pos * gains[0] - f.d_cap_neg * gains[1]) * dscale;
            r.energy += f.energy;
            r.energy_strain += f.d_energy_cap * cap_strain;
            if SLIP_WORK {
                r.slip_work += f.slip_work;
            }
            r.slipping += usize::from(f.state == WireState::Slip);
        }
        r
    }

    /// The gains (stretched, shortened) of layer `law` for a wire at the signed angle `theta`
    /// (rad) from the reference half of the neutral axis, d theta_n / d theta of the slip
    /// limit's angle, and the accumulated pressure's gain slopes d gain / d theta_n where the
    /// layer has it (the capstan gains' slopes follow from the gains).
    #[inline(always)]
    fn turning_gains(&self, law: &LayerLaw, theta: f64) -> ([f64; 2], f64, Option<[f64; 2]>) {
        if law.accumulated {
            let (t, dt) = law.slip_limit.angle(theta.abs());
            let (g, d) = self.capstan_gains(law, t);
            (g, dt, Some(d))
        } else {
            let (g, dt) = law.gains(theta.abs());
            (g, dt, None)
        }
    }
}
