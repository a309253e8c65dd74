//! What the settle examples share: the Fig. 7 fine model, the line that reports a settled
//! solve and the CPU time of the process.
// Each example uses a part of it.
#![allow(dead_code)]

use nalgebra::Vector3;
use strand_core::{Strand, StrandSpec};
use strand_fine::{ContactOptions, Discretisation, FineModel, SettledReport, Support};

/// The Fig. 7 fine model: the Table 1 strand, 0.4 m, clamped at its start and free at its
/// end, `segments` segments a wire (77: the figure's), gravity `g` (m/s^2) along -y, and the
/// default contacts.
pub fn fig7_model(g: f64, segments: usize) -> FineModel {
    paper_model(g, segments, 0.4, &ContactOptions::default())
}

/// [`fig7_model`] with the strand's length and contacts from the environment: `LENGTH` (m,
/// default 0.4), `FRICTION=0` for frictionless contacts.
pub fn fig7_model_from_env(g: f64, segments: usize) -> FineModel {
    let length = std::env::var("LENGTH").map_or(0.4, |v| v.parse().unwrap());
    let mut contact = ContactOptions::default();
    if std::env::var("FRICTION").is_ok_and(|v| v == "0") {
        contact.friction = Some(0.0);
    }
    paper_model(g, segments, length, &contact)
}

/// The Table 1 strand `length` (m) long as [`fig7_model`] builds it, with `contact`.
fn paper_model(g: f64, segments: usize, length: f64, contact: &ContactOptions) -> FineModel {
    let strand = Strand::new(StrandSpec::paper(length, 2.0e8, 7801.0)).unwrap();
    let mut m = FineModel::from_strand(
        &strand,
        Discretisation {
            core_segments: segments,
            wire_segments: segments,
        },
        Support::Clamped,
        Support::Free,
    );
    m.gravity = Vector3::new(0.0, -g, 0.0);
    m.add_contacts(&strand, contact);
    m
}

/// The motion's steps and time and Newton's polish of a settled solve `r`, as the settle
/// examples print them.
#[allow(dead_code)]
pub fn settled_line(r: &SettledReport) -> String {
    format!(
        "{} steps of {:.4e} s, {:.3} s, Newton {} it in {} attempts, residual {:.2e}",
        r.settle.steps, r.settle.time_step, r.settle.time, r.iterations, r.attempts, r.residual,
    )
}

/// CPU time (s) of this process so far, user + system, all threads (fields 14 and 15 of
/// `/proc/self/stat`; 0 where there is none).
pub fn cpu_seconds() -> f64 {
    // utime + stime, in clock ticks of 1/100 s.
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat
        .rsplit(')')
        .next()
        .unwrap_or("")
        .split_whitespace()
        .collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|f| f.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    (ticks(11) + ticks(12)) / 100.0
}

/// Writes `state` to `path` as text, every number in its shortest round-trip form, so that
/// [`load_state`] gives it back bit for bit (a stalled motion saved once, studied many times).
pub fn save_state(state: &strand_fine::ModelState, path: &str) {
    use std::fmt::Write as _;
    let mut s = String::new();
    let v = |s: &mut String, x: &Vector3<f64>| {
        write!(s, " {:?} {:?} {:?}", x.x, x.y, x.z).unwrap();
    };
    writeln!(s, "{} {:?}", state.wires.len(), state.friction_work).unwrap();
    for w in &state.wires {
        writeln!(s, "{}", w.poses.len()).unwrap();
        for (k, p) in w.poses.iter().enumerate() {
            let q = p.rotation.quaternion();
            v(&mut s, &p.position);
            write!(s, " {:?} {:?} {:?} {:?}", q.w, q.i, q.j, q.k).unwrap();
            v(&mut s, &w.velocities[k]);
            v(&mut s, &w.angular_momenta[k]);
            s.push('\n');
        }
    }
    for h in &state.contacts {
        writeln!(s, "{}", h.len()).unwrap();
        for c in h {
            write!(s, "{} {}", c.core_segment, u8::from(c.closed)).unwrap();
            v(&mut s, &c.displacement);
            v(&mut s, &c.on_wire);
            v(&mut s, &c.on_core);
            s.push('\n');
        }
    }
    std::fs::write(path, s).unwrap();
}

/// Reads a state written by [`save_state`] into `state` (of the same model; holds free).
pub fn load_state(state: &mut strand_fine::ModelState, path: &str) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut t = text.split_ascii_whitespace();
    let mut f = || -> f64 { t.next().unwrap().parse().unwrap() };
    let nw = f() as usize;
    assert_eq!(nw, state.wires.len());
    state.friction_work = f();
    let v3 = |f: &mut dyn FnMut() -> f64| Vector3::new(f(), f(), f());
    for w in &mut state.wires {
        let n = f() as usize;
        assert_eq!(n, w.poses.len());
        for k in 0..n {
            w.poses[k].position = v3(&mut f);
            let (qw, qi, qj, qk) = (f(), f(), f(), f());
            w.poses[k].rotation =
                nalgebra::UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(qw, qi, qj, qk));
            w.velocities[k] = v3(&mut f);
            w.angular_momenta[k] = v3(&mut f);
        }
    }
    for h in &mut state.contacts {
        let n = f() as usize;
        assert_eq!(n, h.len());
        for c in h.iter_mut() {
            c.core_segment = f() as usize;
            c.closed = f() != 0.0;
            c.displacement = v3(&mut f);
            c.on_wire = v3(&mut f);
            c.on_core = v3(&mut f);
        }
    }
}
