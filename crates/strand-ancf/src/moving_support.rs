//! Moving supports over a dynamic run: the velocity jumps of the supports passed to the free
//! coordinates, and the work the supports do (the physics is described in `beam::supports`).
//!
//! At every step start the support velocities `V` take their table value; a change `dV` gives
//! the free velocities the jump `-M_ff^-1 M_fp dV` and the supports the work of the kinetic
//! energy it adds. Between jumps `V` is constant and the supports do the work of their
//! reaction `(M q'' + Q_e - Q)_p` on the held coordinates. Its inertial part is a time
//! derivative, `M_pf q_f'' . V = d/dt (v_f . M_fp V)`, so it is booked exactly as the change of
//! `v_f . M_fp V` over a step (the accelerations of an implicit integrator carry
//! high-frequency noise that a quadrature of the reaction would pick up); the rest,
//! `(Q_e - Q)_p`, by the trapezoidal rule on the held coordinates' displacement. Without
//! moving supports nothing is done.

use crate::band::BandSolver;
use crate::beam::Beam;

/// The state of the moving supports over a run.
#[derive(Debug, Clone)]
pub(crate) struct Drive {
    /// Current velocities of the held coordinates (m/s).
    velocity: Vec<f64>,
    /// `M_fp V` over the free coordinates for the current velocities (kg m/s).
    coupling: Vec<f64>,
    /// `v_f . M_fp V` at the last record (J).
    cross: f64,
    /// Elastic force minus dead load on the held coordinates at the last step's end (N).
    force: Vec<f64>,
    /// Held coordinates at the last step's end (m).
    position: Vec<f64>,
    /// Work the supports have done on the strand (J).
    pub(crate) work: f64,
    /// The table's velocities (m/s), then forces at a step's end (N).
    table: Vec<f64>,
    /// A jump of the held velocities (m/s).
    jump: Vec<f64>,
    /// Free-size scratch.
    scratch: Vec<f64>,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

impl Drive {
    /// The supports of `beam` with the initial velocities `v`, coordinates `q` and elastic
    /// forces `force` (all coordinates): before t = 0 the held coordinates move with the initial
    /// velocity field.
    pub(crate) fn new(beam: &Beam, q: &[f64], v: &[f64], force: &[f64]) -> Drive {
        let n = beam.moving_coords();
        let held = |x: &[f64]| {
            (0..n)
                .map(|k| x[beam.moving_coordinate(k)])
                .collect::<Vec<_>>()
        };
        let mut d = Drive {
            velocity: held(v),
            coupling: vec![0.0; beam.dofs()],
            cross: 0.0,
            force: vec![0.0; n],
            position: held(q),
            work: 0.0,
            table: vec![0.0; n],
            jump: vec![0.0; n],
            scratch: vec![0.0; beam.dofs()],
        };
        if n > 0 {
            beam.held_force(force, 1.0, &mut d.force);
            beam.held_coupling(&d.velocity, &mut d.coupling);
            let mut vf = vec![0.0; beam.dofs()];
            crate::statics::gather_free(beam, v, &mut vf);
            d.cross = dot(&vf, &d.coupling);
        }
        d
    }

    /// Velocities of the held coordinates (m/s), in their order.
    pub(crate) fn velocity(&self) -> &[f64] {
        &self.velocity
    }

    /// Whether the beam has moving supports.
    fn active(&self) -> bool {
        !self.velocity.is_empty()
    }

    /// At a step starting at time `t`: the support velocities take their table values and the
    /// free velocities `vf` the jump the change passes through the mass (`mass` factorizes
    /// `M_ff`; `mv` is scratch of the free size).
    pub(crate) fn kick(
        &mut self,
        beam: &Beam,
        t: f64,
        vf: &mut [f64],
        mass: &BandSolver,
        mv: &mut [f64],
    ) {
        if !self.active() {
            return;
        }
        beam.support_velocity(t, &mut self.table);
        if self.table == self.velocity {
            return;
        }
        let before = beam.kinetic_energy(vf, &self.velocity, mv);
        for (d, (a, b)) in self
            .jump
            .iter_mut()
            .zip(self.table.iter().zip(&self.velocity))
        {
            *d = a - b;
        }
        beam.held_coupling(&self.jump, &mut self.scratch);
        mass.solve(&mut self.scratch);
        for (v, d) in vf.iter_mut().zip(&self.scratch) {
            *v -= d;
        }
        self.velocity.copy_from_slice(&self.table);
        self.work += beam.kinetic_energy(vf, &self.velocity, mv) - before;
        beam.held_coupling(&self.velocity, &mut self.coupling);
        self.cross = dot(vf, &self.coupling);
    }

    /// At the end of a step at coordinates `q` with free velocities `vf` and elastic forces
    /// `force` (all coordinates): adds the supports' work over the step.
    pub(crate) fn end_step(&mut self, beam: &Beam, q: &[f64], vf: &[f64], force: &[f64]) {
        if !self.active() {
            return;
        }
        let cross = dot(vf, &self.coupling);
        self.work += cross - self.cross;
        self.cross = cross;
        beam.held_force(force, 1.0, &mut self.table);
        for k in 0..self.velocity.len() {
            let x = q[beam.moving_coordinate(k)];
            self.work += 0.5 * (self.force[k] + self.table[k]) * (x - self.position[k]);
            self.position[k] = x;
        }
        self.force.copy_from_slice(&self.table);
    }
}
