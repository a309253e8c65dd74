//! A search for static scenes that must solve (`must_solve` of `tests/common/must_solve.rs`,
//! the predicate `tests/runner_property.rs` asserts) and do not: a held strand (clamped at one
//! end, pinned at the other) of the equivalent model with the `continuous` law, near the case
//! the property test once failed on (a 4.24 m strand, a core and 4 wires at 32 deg, friction
//! 0.997, 10 elements: "no equilibrium found beyond load fraction 0.83"). Gravity and point
//! forces in random directions are scaled so that the linear cantilever estimate of the
//! property test bends the strand by 2 % to 10 % of its length (the top of its must-solve
//! range). Every failure is printed and written as a scene file to the temporary directory.
//!
//! ```text
//! cargo build --release -p strand-scene --example must_solve_search
//! nice target/release/examples/must_solve_search SEED CASES
//! ```

#[path = "../tests/common/must_solve.rs"]
mod must_solve;

use must_solve::{cantilever_deflection, must_solve, wire_fit};
use serde_json::{Value, json};
use strand_scene::{RunOptions, Scene, run_scene};

/// xorshift64: reproducible draws from a seed without a dependency.
struct Draws(u64);

impl Draws {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit()
    }

    fn direction(&mut self) -> [f64; 3] {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(0.0, std::f64::consts::TAU);
        let r = (1.0 - z * z).sqrt();
        [r * phi.cos(), r * phi.sin(), z]
    }
}

/// A random scene of the family (loads not yet scaled).
fn draw(d: &mut Draws) -> Value {
    let length = d.range(4.0, 4.5);
    let core_d = 10f64.powf(d.range(-3.3, -2.3));
    let young = 10f64.powf(d.range(8.0, 11.3));
    let density = d.range(900.0, 8000.0);
    let (wires, lay) = (4, d.range(31.0, 33.0));
    let layer_d = core_d * d.range(0.05, 1.0) * wire_fit(wires, lay);
    let area = std::f64::consts::FRAC_PI_4 * (core_d.powi(2) + wires as f64 * layer_d.powi(2));
    let weight = density * area * length * 9.81;
    let g = if d.unit() < 0.4 {
        0.0
    } else {
        9.81 * 10f64.powf(d.range(-4.0, -1.0))
    };
    let gravity = d.direction().map(|x| x * g);
    let points = if g > 0.0 && d.unit() < 0.5 {
        0
    } else {
        1 + (d.unit() * 2.0) as usize
    };
    let points: Vec<Value> = (0..points)
        .map(|_| {
            let s = d.unit() * length;
            let f = 10f64.powf(d.range(-4.0, -1.0)) * weight;
            json!({ "s": s, "force": d.direction().map(|x| x * f) })
        })
        .collect();
    let mut initial = json!({});
    if d.unit() < 0.5 {
        initial["direction"] = json!(d.direction());
    }
    let (clamped, pinned) = if d.unit() < 0.5 {
        ("start", "end")
    } else {
        ("end", "start")
    };
    let wire = |dia: f64| {
        json!({ "diameter": dia, "youngs_modulus": young, "poisson_ratio": 0.3,
                "density": density })
    };
    let mut layer = wire(layer_d);
    layer["wires"] = json!(wires);
    layer["lay_angle_deg"] = json!(lay);
    json!({
        "name": "must-solve-search",
        "strand": { "length": length, "core": wire(core_d), "layers": [layer],
                    "friction": d.range(0.97, 1.0) },
        "law": "continuous",
        "initial": initial,
        "supports": [{ "at": clamped, "kind": "clamped" }, { "at": pinned, "kind": "pinned" }],
        "loads": { "gravity": gravity, "points": points },
        "analysis": { "kind": "static", "load_steps": 1 + (d.unit() * 7.0) as u32,
                      "max_steps": 2000 },
        "models": { "equivalent": { "elements": 10 } }
    })
}

/// `v`'s loads times `k`.
fn scale_loads(v: &mut Value, k: f64) {
    let times = |x: &Value| json!(x.as_f64().unwrap_or(0.0) * k);
    let loads = &mut v["loads"];
    let g: Vec<Value> = loads["gravity"]
        .as_array()
        .unwrap()
        .iter()
        .map(times)
        .collect();
    loads["gravity"] = json!(g);
    for p in loads["points"].as_array_mut().unwrap() {
        let f: Vec<Value> = p["force"].as_array().unwrap().iter().map(times).collect();
        p["force"] = json!(f);
    }
}

fn main() {
    let arg = |i: usize, default: u64| {
        std::env::args()
            .nth(i)
            .map_or(default, |s| s.parse().expect("a number"))
    };
    let (seed, cases) = (arg(1, 1), arg(2, 1000));
    let mut d = Draws(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let dir = std::env::temp_dir();
    let out = dir.join(format!("must-solve-search-{seed}"));
    let (mut must, mut failed) = (0, 0);
    for case in 0..cases {
        let mut v = draw(&mut d);
        let Ok(scene) = Scene::parse(&v.to_string()) else {
            continue;
        };
        let length = scene.strand.length();
        let w = cantilever_deflection(&scene);
        if length < 10.0 * scene.strand.outer_diameter() || w.is_nan() || w <= 0.0 {
            continue;
        }
        scale_loads(&mut v, d.range(0.02, 0.1) * length / w);
        let Ok(scene) = Scene::parse(&v.to_string()) else {
            continue;
        };
        if must_solve(&scene, "equivalent").is_err() {
            continue;
        }
        must += 1;
        let opts = RunOptions {
            out: out.clone(),
            vtk: false,
        };
        let summaries = run_scene(&scene, &opts, &mut |_, _| {}).expect("a run");
        for s in summaries.iter().filter(|s| s.status != "ok") {
            failed += 1;
            let file = dir.join(format!("must-solve-search-{seed}-{case}.json"));
            std::fs::write(&file, v.to_string()).expect("scene written");
            println!("case {case} ({}): {:?}", file.display(), s.error);
        }
    }
    let _ = std::fs::remove_dir_all(&out);
    println!("seed {seed}: {must} scenes that must solve, {failed} failed");
}
