//! The section law of a scene against a fine bending test already run: reads the test's
//! `bending.csv` (columns `curvature`, the measured one, and `moment`), follows the scene's
//! law along those curvatures from straight at the test's nominal tension (as the test's own
//! `law_moment` column does, `strand_scene::law_path_moments`) and prints, per point, the
//! curvature, the fine moment, the law's and their ratio. The scene may differ from the one
//! the test ran in its `section` options only (they do not enter the fine model), so one fine
//! run serves every variant of the law.
//!
//! `cargo run --release -p strand-scene --example law_path -- SCENE T DIR/bending.csv [PITCHES]`
//! (`PITCHES`: the test's `--pitches`, default 3; on several layers the law is averaged over
//! the test's window of whole pitches of every layer).

use strand_scene::Scene;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let scene = Scene::load(args[1].as_ref()).expect("scene");
    let t: f64 = args[2].parse().expect("tension");
    let text = std::fs::read_to_string(&args[3]).expect("bending.csv");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).expect(name);
    let (ck, cm) = (col("curvature"), col("moment"));
    let rows: Vec<(f64, f64)> = lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().expect("number")).collect();
            (v[ck], v[cm])
        })
        .collect();
    let pitches: usize = args.get(4).map_or(3, |p| p.parse().expect("pitches"));
    let kappas: Vec<f64> = rows.iter().map(|r| r.0).collect();
    let law = strand_scene::law_path_moments(&scene, t, pitches, &kappas);
    println!(
        "{} (section.stick_stiffness {}, slip_pressure {:?}), T = {t} N",
        scene.name, scene.section.stick_stiffness, scene.section.slip_pressure
    );
    println!("curvature (1/m)  fine M (N m)  law M (N m)  fine/law");
    for ((k, m), l) in rows.iter().zip(&law) {
        println!("{k:.5e}  {m:.5e}  {l:.5e}  {:.4}", m / l);
    }
}
