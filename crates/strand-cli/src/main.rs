//! `strand`: the strand calculator and scene runner.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};
use strand_core::{LawKind, SectionLaw, SectionPoint, StrandSummary};
use strand_scene::Scene;

#[derive(Parser)]
#[command(
    name = "strand",
    version,
    about = "Stranded wire rope statics and dynamics"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum)]
enum LawArg {
    Continuous,
    Paper,
    Hysteretic,
    Constant,
}

impl From<LawArg> for LawKind {
    fn from(l: LawArg) -> Self {
        match l {
            LawArg::Continuous => LawKind::Continuous,
            LawArg::Paper => LawKind::Paper,
            LawArg::Hysteretic => LawKind::Hysteretic,
            LawArg::Constant => LawKind::Constant,
        }
    }
}

#[derive(Subcommand)]
enum Command {
    /// Print the strand's derived quantities and, given strain and curvature, the section's
    /// moment, stiffness and per-wire stick/slip table (SPEC 6).
    Section {
        /// Scene file (only its `strand`, `law` and `section` are used).
        scene: PathBuf,
        /// Axial strain eps (-).
        #[arg(long, allow_hyphen_values = true)]
        strain: Option<f64>,
        /// Signed curvature kappa_z (1/m), as in centerline.csv: positive turns the strand
        /// counter-clockwise seen from +Z (toward +y for a strand along +x); the paper's
        /// hanging cantilever (convex side toward +y) has negative curvature.
        #[arg(long, allow_hyphen_values = true)]
        curvature: Option<f64>,
        /// Material coordinate x along the strand (m).
        #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
        at: f64,
        /// Section law (default: the scene's).
        #[arg(long, value_enum)]
        law: Option<LawArg>,
        /// Print one JSON object instead of tables.
        #[arg(long)]
        json: bool,
    },
    /// Run the models a scene names and write `DIR/<model>/` with summary.json,
    /// centerline.csv, wires.csv and, for dynamics, tip.csv and energy.csv (SPEC 6).
    Run {
        /// Scene file.
        scene: PathBuf,
        /// Output folder.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Also write the centreline of every output frame as VTK files (`DIR/<model>/vtk/`),
        /// a time series that ParaView opens, with curvature, tension and moment (and the
        /// beams' bending stiffness) as point data.
        #[arg(long)]
        vtk: bool,
        /// Also draw the results as PNG and SVG in `DIR/plots/`: shape (sag exaggerated by a
        /// stated factor where small), curvature and bending stiffness along the strand (with
        /// K_min and K_max), each wire's stick/slip state along it; for dynamics the motion
        /// and moment-curvature loop at each probe (the tip's path without probes), the range
        /// envelopes of moment, curvature and tension, and the energies; and an overview.
        #[arg(long)]
        plot: bool,
        /// Run only this model of the scene (`equivalent`, `traditional` or `fine`);
        /// repeat for several. Default: every model the scene names.
        #[arg(long = "model", value_name = "MODEL")]
        models: Vec<String>,
        /// Most time steps a model's run may take, instead of the scene's
        /// `analysis.max_steps` (default 10,000,000): a run that needs more is refused before
        /// it starts, with the count and an estimate of its time.
        #[arg(long, value_name = "N")]
        max_steps: Option<usize>,
    },
    /// Virtual bending test of the scene's strand with the fine model: pulled to a tension,
    /// then bent along arcs of growing curvature; writes `DIR/bending.csv` (measured moment
    /// and stiffness beside the scene's section law at the same strain and curvature),
    /// `DIR/summary.json` and the two moment-curvature curves, `DIR/bending.png`/`.svg`.
    Bend {
        /// Scene file: its `strand` and `law` are used, and `models.fine.penetration`, which on
        /// a `1+m` strand sets the contacts' normal penalty (the wire sinks by that fraction of
        /// its diameter at the reference pressure) and on a strand of several layers only
        /// decides where a wire-to-wire contact counts as a crossing or as a line (the normal
        /// penalty then follows from the strain relief, `strand_fine::penalty`).
        scene: PathBuf,
        /// Axial tension T (N).
        #[arg(long)]
        tension: f64,
        /// Curvatures (1/m), comma separated, each reached from the one before (a sequence
        /// that turns back reverses the load); default: 10 increasing values from 0.2 to 20
        /// times the law's smallest critical curvature at this tension.
        #[arg(long, value_delimiter = ',')]
        curvatures: Vec<f64>,
        /// Strand length in pitches.
        #[arg(long, default_value_t = 6)]
        pitches: usize,
        /// Segments per pitch of every wire.
        #[arg(long, default_value_t = 12)]
        segments_per_pitch: usize,
        /// Output folder.
        #[arg(long, default_value = "out/bending")]
        out: PathBuf,
        /// `fine` (default): the fine model's virtual bending test against the section law;
        /// `equivalent`: the section law's moment-curvature curve with one load reversal (a
        /// hysteresis loop), for a strand of any number of layers, drawn as
        /// `law-bending.png`/`.svg`.
        #[arg(long, default_value = "fine")]
        model: String,
        /// `--model equivalent`: the loop's largest curvature (1/m); default three times the
        /// largest critical curvature of the wires.
        #[arg(long)]
        amplitude: Option<f64>,
        /// `--model equivalent`: curvature steps from 0 to the amplitude.
        #[arg(long, default_value_t = 100)]
        steps: usize,
    },
}

/// `println!` that ignores a closed standard output (e.g. piped into `head`): the results are
/// in the files, and a failed print is no reason to stop.
macro_rules! say {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout(), $($t)*);
    }};
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Section {
            scene,
            strain,
            curvature,
            at,
            law,
            json,
        } => section(&scene, strain, curvature, at, law.map(Into::into), json),
        Command::Run {
            scene,
            out,
            vtk,
            models,
            max_steps,
            plot,
        } => run_scene(&scene, out, vtk, plot, &models, max_steps),
        Command::Bend {
            scene,
            tension,
            out,
            model,
            amplitude,
            steps,
            ..
        } if model == "equivalent" => law_bend(
            &scene,
            strand_scene::LawBendingOptions {
                tension,
                amplitude,
                steps,
                out,
            },
        ),
        Command::Bend { model, .. } if model != "fine" => {
            anyhow::bail!("--model must be `fine` or `equivalent`, got `{model}`")
        }
        Command::Bend {
            scene,
            tension,
            curvatures,
            pitches,
            segments_per_pitch,
            out,
            ..
        } => bend(
            &scene,
            strand_scene::BendingOptions {
                tension,
                curvatures,
                pitches,
                segments_per_pitch,
                out,
            },
        ),
    }
}

/// `strand bend --model equivalent`: the section law's curve with one load reversal.
fn law_bend(path: &std::path::Path, opts: strand_scene::LawBendingOptions) -> anyhow::Result<()> {
    let scene = Scene::load(path).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let s = strand_scene::run_law_bending(&scene, &opts)?;
    say!(
        "section law `{}` of `{}` ({} layer(s)): T = {} N (strain {:.3e}), K_min = {:.4e}, K_max = \
         {:.4e} N m^2",
        s.law,
        s.scene,
        s.layers,
        s.tension,
        s.strain,
        s.k_min,
        s.k_max
    );
    say!(
        "loop 0 -> {a:.4e} -> {m:.4e} -> {a:.4e} 1/m: slip work {:.4e} J/m, loop area {:.4e} J/m",
        s.dissipated,
        s.loop_area,
        a = s.amplitude,
        m = -s.amplitude
    );
    let (x, y): (Vec<f64>, Vec<f64>) = s.points.iter().map(|p| (p[0], p[1])).unzip();
    let n = x.len();
    let first = n / 5 + 1;
    let chart = strand_plot::Chart {
        title: format!(
            "{}: section law `{}` at T = {} N",
            s.scene, s.law, s.tension
        ),
        x_label: "curvature (1/m)".into(),
        y_label: "moment (N m)".into(),
        series: vec![
            strand_plot::Series::xy(
                "loading",
                &x[..first],
                &y[..first],
                strand_plot::Mark::Line,
                0,
            ),
            strand_plot::Series::xy(
                "reversals",
                &x[first - 1..],
                &y[first - 1..],
                strand_plot::Mark::Line,
                1,
            ),
        ],
        ..Default::default()
    };
    strand_plot::register_fonts();
    let files = strand_plot::save(&chart, &opts.out, "law-bending")?;
    say!(
        "wrote {} and {}",
        opts.out.join("law-bending.csv").display(),
        files
            .iter()
            .map(|f| f.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}

fn bend(path: &std::path::Path, opts: strand_scene::BendingOptions) -> anyhow::Result<()> {
    let scene = Scene::load(path).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let mut progress = Progress::new();
    let result =
        strand_scene::run_bending(&scene, &opts, &mut |_, f| progress.update("bending", f));
    progress.bar.finish_and_clear();
    let s = result?;
    say!(
        "virtual bending test of `{}`: T = {} N (strain {:.3e}), {} pitches, {} segments per pitch, {:.1} s",
        s.scene,
        s.tension,
        s.strain,
        s.pitches,
        s.segments_per_pitch,
        s.wall_time
    );
    say!(
        "K_min = {:.4e} N m^2, K_max = {:.4e} N m^2 (stick stiffness `{}`); law `{}`",
        s.k_min,
        s.k_max,
        s.stick_stiffness,
        s.law
    );
    say!(
        "{:>12} {:>12} {:>12} {:>10} {:>10}",
        "kappa 1/m",
        "M fine N m",
        "M law N m",
        "K/K_max",
        "law/K_max"
    );
    for [k, m, ml] in &s.points {
        say!(
            "{k:>12.4e} {m:>12.4e} {ml:>12.4e} {:>10.4} {:>10.4}",
            m / k / s.k_max,
            ml / k / s.k_max
        );
    }
    // The fine curve and the law's at the fine model's measured curvatures, from straight.
    let from_zero = |i: usize| -> Vec<f64> {
        std::iter::once(0.0)
            .chain(s.points.iter().map(|p| p[i]))
            .collect()
    };
    let (x, fine, law) = (from_zero(0), from_zero(1), from_zero(2));
    let chart = strand_plot::Chart {
        title: format!(
            "{}: virtual bending test at T = {} N, {} segments per pitch",
            s.scene, s.tension, s.segments_per_pitch
        ),
        x_label: "curvature (1/m)".into(),
        y_label: "moment (N m)".into(),
        series: vec![
            strand_plot::Series::xy("fine model", &x, &fine, strand_plot::Mark::Front, 0),
            strand_plot::Series::xy(
                format!("section law `{}`", s.law),
                &x,
                &law,
                strand_plot::Mark::Dashed,
                1,
            ),
        ],
        ..Default::default()
    };
    strand_plot::register_fonts();
    let files = strand_plot::save(&chart, &opts.out, "bending")?;
    say!(
        "wrote {} and {}",
        opts.out.join("bending.csv").display(),
        files
            .iter()
            .map(|f| f.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}

/// A progress bar that shows itself on a terminal once a run has taken more than a second.
struct Progress {
    bar: indicatif::ProgressBar,
    start: std::time::Instant,
    shown: bool,
    model: String,
}

impl Progress {
    fn new() -> Self {
        let bar = indicatif::ProgressBar::with_draw_target(
            Some(1000),
            indicatif::ProgressDrawTarget::hidden(),
        );
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{prefix:>12} [{bar:40}] {percent:>3}% {elapsed} (eta {eta})",
            )
            .expect("valid template")
            .progress_chars("=> "),
        );
        Progress {
            bar,
            start: std::time::Instant::now(),
            shown: false,
            model: String::new(),
        }
    }

    fn update(&mut self, model: &str, fraction: f64) {
        if model != self.model {
            self.model = model.to_string();
            self.bar.set_prefix(model.to_string());
            self.bar.reset();
            self.start = std::time::Instant::now();
        }
        if !self.shown && self.start.elapsed().as_secs_f64() > 1.0 {
            self.bar
                .set_draw_target(indicatif::ProgressDrawTarget::stderr());
            self.shown = true;
        }
        self.bar
            .set_position((fraction.clamp(0.0, 1.0) * 1000.0) as u64);
    }
}

fn run_scene(
    path: &std::path::Path,
    out: PathBuf,
    vtk: bool,
    plot: bool,
    only: &[String],
    max_steps: Option<usize>,
) -> anyhow::Result<()> {
    let mut scene = Scene::load(path).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    if let Some(n) = max_steps {
        anyhow::ensure!(n >= 1, "--max-steps must be at least 1");
        scene.max_steps = n;
    }
    scene.models.keep_only(only).map_err(|e| match e {
        strand_scene::ModelSelectionError::Unknown(_) => anyhow::anyhow!("--model {e}"),
        strand_scene::ModelSelectionError::Absent(m) => {
            anyhow::anyhow!(
                "--model {m}: the scene {} has no models.{m}",
                path.display()
            )
        }
    })?;
    let mut progress = Progress::new();
    let opts = strand_scene::RunOptions {
        out: out.clone(),
        vtk,
    };
    let result = strand_scene::run_scene(&scene, &opts, &mut |m, f| progress.update(m, f));
    progress.bar.finish_and_clear();
    let summaries = result?;
    for s in &summaries {
        let tip = s.tip.map_or(String::new(), |t| {
            format!("; tip ({:.6}, {:.6}, {:.6}) m", t[0], t[1], t[2])
        });
        say!(
            "{:<12} {} law, {} dofs, {} steps, {} Newton iterations, {:.3} s{tip}{}",
            s.model,
            s.law,
            s.dofs,
            s.steps,
            s.newton_iterations,
            s.wall_time_s,
            s.energy_balance_error.map_or(String::new(), |e| format!(
                "; energy balance error {e:.3e} J"
            )),
        );
        for w in &s.warnings {
            say!("{:<12} warning: {w}", "");
        }
        if let (Some(reason), Some(error)) = (s.reason, &s.error) {
            say!(
                "{:<12} FAILED ({reason}): {error}; files in {}",
                "",
                out.join(&s.model).display()
            );
        }
    }
    say!("results in {}", out.display());
    if plot {
        let files = strand_plot::plot_run(&scene, &out, &summaries)?;
        say!(
            "{} charts (PNG and SVG) in {}",
            files.len() / 2,
            out.join("plots").display()
        );
    }
    let failed: Vec<&str> = summaries
        .iter()
        .filter(|s| s.failed())
        .map(|s| s.model.as_str())
        .collect();
    anyhow::ensure!(
        failed.is_empty(),
        "{} of {} models failed: {}",
        failed.len(),
        summaries.len(),
        failed.join(", ")
    );
    Ok(())
}

fn section(
    path: &std::path::Path,
    strain: Option<f64>,
    curvature: Option<f64>,
    at: f64,
    law: Option<LawKind>,
    json: bool,
) -> anyhow::Result<()> {
    let scene = Scene::load(path).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let strand = &scene.strand;
    let law = law.unwrap_or(scene.law);
    for (name, v) in [("--strain", strain), ("--curvature", curvature)] {
        if let Some(v) = v {
            anyhow::ensure!(v.is_finite(), "{name} must be a finite number, got {v}");
        }
    }
    anyhow::ensure!(
        at.is_finite() && (0.0..=strand.length()).contains(&at),
        "--at must lie on the strand, in [0, {}] m, got {at}",
        strand.length()
    );
    SectionLaw::check(strand, law).map_err(|e| anyhow::anyhow!("{}", e.within("strand")))?;
    let summary = StrandSummary::new(strand, &scene.section);
    let point = match (strain, curvature) {
        (Some(e), Some(k)) => Some(SectionPoint::new(strand, law, &scene.section, e, k, at)),
        (None, None) => None,
        _ => anyhow::bail!("give both --strain and --curvature, or neither"),
    };
    if json {
        let mut v = serde_json::to_value(&summary)?;
        if let Some(p) = &point {
            let obj = v.as_object_mut().expect("summary is an object");
            for (k, x) in serde_json::to_value(p)?.as_object().expect("object") {
                obj.insert(k.clone(), x.clone());
            }
        }
        say!("{}", serde_json::to_string_pretty(&v)?);
        return Ok(());
    }
    print_summary(&scene, &summary);
    if let Some(p) = &point {
        print_point(p);
    }
    Ok(())
}

fn opt(v: Option<f64>, unit: &str) -> String {
    v.map_or("-".to_string(), |v| format!("{v:.6e} {unit}"))
}

fn print_summary(scene: &Scene, s: &StrandSummary) {
    let strand = &scene.strand;
    let m: String = strand
        .layers()
        .iter()
        .map(|l| format!("+{}", l.wires()))
        .collect();
    say!(
        "strand `{}`: 1{m}, L = {} m, friction {}",
        scene.name,
        strand.length(),
        strand.friction()
    );
    let rows: [(&str, String); 16] = [
        ("helix radius R_w", opt(s.r_w, "m")),
        ("pitch P", opt(s.pitch, "m")),
        ("lay angle", opt(s.lay_angle_deg, "deg")),
        ("loss factor eta = cos^3(alpha)", opt(s.eta, "")),
        ("gap between layer wires", opt(s.wire_gap, "m")),
        ("mass per length", format!("{:.6e} kg/m", s.mass_per_length)),
        ("axial stiffness EA_eq", format!("{:.6e} N", s.ea)),
        (
            "wire bending stiffness in K_min",
            format!("{} (section.base_stiffness)", s.base_stiffness),
        ),
        (
            "bending stiffness K_min (all slip)",
            format!("{:.6e} N m^2 (used)", s.k_min),
        ),
        (
            "K_min of the paper (eta = cos^3)",
            format!("{:.6e} N m^2", s.k_min_paper),
        ),
        (
            "wire stick stiffness",
            format!(
                "{} (section.stick_stiffness), factor {}",
                s.stick_stiffness,
                match (s.stick_factor, s.layers.len()) {
                    (None, _) => "- on eq. (22a)".into(),
                    (Some(f), 1) => format!("{f:.4} on eq. (22a)"),
                    _ => "on eq. (22a) per layer in the table below".into(),
                }
            ),
        ),
        (
            "wire friction limit",
            format!("{} (section.slip_limit)", s.slip_limit),
        ),
        (
            "bending stiffness K_max (all stick)",
            format!("{:.6e} N m^2 (used)", s.k_max),
        ),
        (
            "K_max, plane section (eq. (22a))",
            format!("{:.6e} N m^2", s.k_max_plane_section),
        ),
        ("traditional EI", format!("{:.6e} N m^2", s.ei_traditional)),
        ("traditional EA", format!("{:.6e} N", s.ea_traditional)),
    ];
    for (k, v) in rows {
        say!("  {k:<36} {v}");
    }
    print_layers(s);
}

/// Each layer's geometry, its interface with the layer beneath and its shares of K_min and of
/// the stick stiffness; the strand totals below.
fn print_layers(s: &StrandSummary) {
    if s.layers.is_empty() {
        return;
    }
    say!(
        "\n  friction pressure: {} (section.slip_pressure)",
        s.slip_pressure
    );
    say!(
        "  {:>5} {:>5} {:>11} {:>11} {:>11} {:>8} {:>5} {:>8} {:>8} {:>12} {:>12} {:>7} {:>12} {:>12}",
        "layer",
        "wires",
        "d/m",
        "R_w/m",
        "pitch/m",
        "lay/deg",
        "dir",
        "cross/deg",
        "contact",
        "lift/m",
        "K_min/N m^2",
        "factor",
        "K_stick/N m^2",
        "slip/N"
    );
    for l in &s.layers {
        say!(
            "  {:>5} {:>5} {:>11.5e} {:>11.5e} {:>11.5e} {:>8.4} {:>5} {:>9.4} {:>8} {:>12.4e} {:>12.5e} {:>7.4} {:>12.5e} {:>12.5e}",
            l.layer,
            l.wires,
            l.diameter,
            l.r_w,
            l.pitch,
            l.lay_angle_deg,
            l.lay_direction,
            l.crossing_angle_deg,
            l.contact.name(),
            l.lift,
            l.k_min,
            l.stick_factor,
            l.k_stick,
            l.slip_force_per_strain
        );
    }
    let k_min_layers: f64 = s.layers.iter().map(|l| l.k_min).sum();
    let k_stick: f64 = s.layers.iter().map(|l| l.k_stick).sum();
    say!(
        "  {:>5} {:>5} {:>84} {:>12.5e} {:>7} {:>12.5e}",
        "all",
        s.layers.iter().map(|l| l.wires).sum::<usize>(),
        "",
        k_min_layers,
        "",
        k_stick
    );
    say!(
        "  (K_min = core {:.5e} + layers {:.5e} = {:.5e} N m^2; K_max = K_min + {:.5e} = {:.5e} \
         N m^2; slip/N: friction limit per unit strand strain of a wire at the extreme fibre)",
        s.k_min - k_min_layers,
        k_min_layers,
        s.k_min,
        k_stick,
        s.k_max
    );
}

fn print_point(p: &SectionPoint) {
    say!(
        "\n{} law at x = {} m, strain {:e}, curvature {:e} 1/m{}",
        p.law,
        p.at,
        p.strain,
        p.curvature,
        if p.curvature > 0.0 {
            " (turning toward +y: convex side -y)"
        } else if p.curvature < 0.0 {
            " (turning toward -y: convex side +y, the hanging cantilever's)"
        } else {
            ""
        }
    );
    let rows: [(&str, String); 6] = [
        ("axial force", format!("{:.6e} N", p.axial_force)),
        ("bending moment", format!("{:.6e} N m", p.moment)),
        (
            "secant stiffness M/kappa",
            format!("{:.6e} N m^2", p.secant_stiffness),
        ),
        (
            "tangent stiffness dM/dkappa",
            format!("{:.6e} N m^2", p.tangent_stiffness),
        ),
        (
            "first slip at curvature",
            opt(p.first_slip_curvature, "1/m"),
        ),
        ("full slip at curvature", opt(p.full_slip_curvature, "1/m")),
    ];
    for (k, v) in rows {
        say!("  {k:<36} {v}");
    }
    if p.wires.is_empty() {
        return;
    }
    say!(
        "\n  {:>4} {:>10} {:>14} {:>14} {:>14} {:>6} {:>5}",
        "wire",
        "phase/deg",
        "K_stick/N m^2",
        "M_slip/N m",
        "kappa_c/(1/m)",
        "state",
        "layer"
    );
    for w in &p.wires {
        let kc = w
            .critical_curvature
            .map_or("never".to_string(), |c| format!("{c:.6e}"));
        let state = match w.state {
            strand_core::WireState::Stick => "stick",
            strand_core::WireState::Slip => "slip",
        };
        say!(
            "  {:>4} {:>10.3} {:>14.6e} {:>14.6e} {:>14} {:>6} {:>5}",
            w.wire,
            w.phase.to_degrees(),
            w.k_stick,
            w.m_slip,
            kc,
            state,
            w.layer
        );
    }
}
