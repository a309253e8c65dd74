//! Project tasks, run as `cargo xtask <task>`.

use std::process::Command;

use anyhow::{Context, bail};
use clap::{Parser, Subcommand};
use validate::report::{Report, Row};

mod bench_peers;
mod bonded;
mod book;
mod conductor;
mod hard;
mod multilayer_curve;
mod paper;
mod pareto;
mod stiffness;
mod validate;

#[derive(Parser)]
#[command(name = "cargo xtask", about = "strand project tasks")]
struct Cli {
    #[command(subcommand)]
    task: Task,
}

#[derive(Subcommand)]
enum Task {
    /// Everything CI checks: formatting, clippy, docs, the test suite (release) and
    /// `validate --quick`.
    Check,
    /// Runs the validation scenes and their checks (validation/tolerances.json), prints the
    /// table, writes target/validation/report.{md,json}; fails on any failed check.
    Validate(validate::ValidateArgs),
    /// Runs the hard cases of SPEC 10 (validation/hard/, criteria in
    /// validation/hard/criteria.json), prints the table, writes target/hard/report.{md,json};
    /// fails on any failed criterion.
    Hard(hard::HardArgs),
    /// Reproduces the paper's Figs. 7-15 (PNG, SVG) and writes target/paper/report.{md,json}
    /// with our numbers beside the paper's statements.
    Paper(paper::PaperArgs),
    /// The bonded (all-stick) stiffness study: the fine model's virtual bending test with
    /// each compliance that K_max ignores removed in turn, refined in the segment length,
    /// against the rod model of the bonded strand; target/bonded/. Fails on any failed
    /// criterion (validation/bonded/criteria.json).
    Bonded(bonded::BondedArgs),
    /// Speed against error of the models on a static and a dynamic scene: each run against the
    /// converged fine model and against its own converged discretisation, log-log plots, and
    /// the CPU time of each model to come within a stated distance X; target/pareto/.
    Pareto(pareto::ParetoArgs),
    /// The section-3 pendulum in strand and in Exudyn (pip install exudyn), timed side by side
    /// in interleaved runs, with the trajectories checked against each other;
    /// target/bench-peers/.
    BenchPeers(bench_peers::BenchPeersArgs),
    /// Checks the manual's internal links and anchors (docs/book/) and README.md's relative
    /// links and anchors, then builds the manual with
    /// mdBook (installed into target/tools/ when no mdBook 0.5 is on the PATH) into
    /// target/book/; fails naming the file and line of a broken link.
    Book(book::BookArgs),
    /// The section laws' K_min (Costello's wire stiffness) against the fine model: the
    /// frictionless bending test over lay angles and frictionless cantilevers on strands that
    /// are not the paper's, each converged in segments per pitch; target/stiffness/. Fails on
    /// any failed check.
    Stiffness(stiffness::StiffnessArgs),
    /// The equivalent section law of Cardinal ACSR 54/7 against its measured moment-curvature
    /// curve at 40 kN (validation/conductor/), beside the classical analytic models, at the
    /// literature friction coefficient and at the best-fitting one; target/conductor/.
    Conductor(conductor::ConductorArgs),
    /// The equivalent section law of the 1+6+12 strand against the fine virtual bending test
    /// with friction (examples/steel-1x19-swing.json): moment against curvature with load
    /// reversals at 100 and 1000 N, 12, 16 and 20 segments per pitch, each point judged within
    /// 5 % with the fine model's mesh change added; target/multilayer-curve/. Fails on a point
    /// that misses it.
    MultilayerCurve(multilayer_curve::MultilayerCurveArgs),
}

fn main() -> anyhow::Result<()> {
    match Cli::parse().task {
        Task::Check => check(),
        Task::Validate(args) => validate_and_exit(&args),
        Task::Hard(args) => hard_and_exit(&args),
        Task::Paper(args) => paper::run(&args),
        Task::Pareto(args) => pareto::run(&args),
        Task::BenchPeers(args) => bench_peers::run(&args),
        Task::Stiffness(args) => stiffness_and_exit(&args),
        Task::Bonded(args) => bonded_and_exit(&args),
        Task::Book(args) => book::run(&args),
        Task::Conductor(args) => conductor::run(&args),
        Task::MultilayerCurve(args) => {
            if !multilayer_curve::run(&args)? {
                std::process::exit(1);
            }
            Ok(())
        }
    }
}

/// Runs the base-stiffness study, prints the table and exits with status 1 on a failed check.
fn stiffness_and_exit(args: &stiffness::StiffnessArgs) -> anyhow::Result<()> {
    print_and_exit_on_failure(&stiffness::run(args)?, "stiffness study", Row::name)
}

/// Runs the hard cases, prints the table and exits with status 1 when a criterion failed.
/// A hard case's row names no metric, so a failure is named by case and criterion.
fn hard_and_exit(args: &hard::HardArgs) -> anyhow::Result<()> {
    print_and_exit_on_failure(&hard::run(args)?, "hard cases", |r| {
        format!("{} {}", r.scene, r.check)
    })
}

/// Runs the bonded-stiffness study, prints the table and exits with status 1 when a criterion
/// failed.
fn bonded_and_exit(args: &bonded::BondedArgs) -> anyhow::Result<()> {
    print_and_exit_on_failure(&bonded::run(args)?, "bonded study", Row::name)
}

/// Runs the validation, prints the table and exits with status 1 when a check failed.
fn validate_and_exit(args: &validate::ValidateArgs) -> anyhow::Result<()> {
    print_and_exit_on_failure(&validate::run(args)?, "validation", Row::name)
}

/// Prints `report`'s table; when a row failed, prints `"{task} failed: "` and the failing
/// rows as `name` gives them to stderr and exits with status 1.
fn print_and_exit_on_failure(
    report: &Report,
    task: &str,
    name: impl Fn(&Row) -> String,
) -> anyhow::Result<()> {
    print!("{}", report.table());
    if report.failed() {
        let names: Vec<String> = report.failures().map(name).collect();
        eprintln!("{task} failed: {}", names.join("; "));
        std::process::exit(1);
    }
    Ok(())
}

/// Runs `cargo` with `args` in the workspace root, failing on a non-zero exit.
fn cargo(args: &[&str], env: &[(&str, &str)]) -> anyhow::Result<()> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    println!("== cargo {}", args.join(" "));
    let status = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
        .args(args)
        .envs(env.iter().copied())
        .current_dir(root)
        .status()
        .context("running cargo")?;
    if !status.success() {
        bail!("cargo {} failed", args.join(" "));
    }
    Ok(())
}

fn check() -> anyhow::Result<()> {
    cargo(&["fmt", "--all", "--", "--check"], &[])?;
    cargo(
        &[
            "clippy",
            "--workspace",
            "--all-targets",
            "--",
            "-D",
            "warnings",
        ],
        &[],
    )?;
    cargo(
        &["doc", "--workspace", "--no-deps", "--quiet"],
        &[("RUSTDOCFLAGS", "-D warnings")],
    )?;
    cargo(&["test", "--workspace", "--release"], &[])?;
    println!("== cargo xtask book");
    book::run(&book::BookArgs::default())?;
    println!("== cargo xtask validate --quick");
    validate_and_exit(&validate::ValidateArgs {
        quick: true,
        ..Default::default()
    })
}
