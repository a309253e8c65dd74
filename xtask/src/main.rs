//! Project tasks, run as `cargo xtask <task>`.

use std::process::Command;

use anyhow::{Context, bail};
use clap::{Parser, Subcommand};

mod bench_peers;
mod bonded;
mod hard;
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
    /// Speed against error of the models on a static and a dynamic scene: table, log-log plot
    /// with the Pareto front, speed-up at equal distance to the reference; target/pareto/.
    Pareto(pareto::ParetoArgs),
    /// The section-3 pendulum in strand and in Exudyn (pip install exudyn), timed side by side
    /// in interleaved runs, with the trajectories checked against each other;
    /// target/bench-peers/.
    BenchPeers(bench_peers::BenchPeersArgs),
    /// The section laws' K_min (Costello's wire stiffness) against the fine model: the
    /// frictionless bending test over lay angles and frictionless cantilevers on strands that
    /// are not the paper's, each converged in segments per pitch; target/stiffness/. Fails on
    /// any failed check.
    Stiffness(stiffness::StiffnessArgs),
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
    }
}

/// Runs the base-stiffness study, prints the table and exits with status 1 on a failed check.
fn stiffness_and_exit(args: &stiffness::StiffnessArgs) -> anyhow::Result<()> {
    let report = stiffness::run(args)?;
    print!("{}", report.table());
    if report.failed() {
        let names: Vec<String> = report
            .failures()
            .map(|r| format!("{} {} {}", r.scene, r.check, r.metric))
            .collect();
        eprintln!("stiffness study failed: {}", names.join("; "));
        std::process::exit(1);
    }
    Ok(())
}

/// Runs the hard cases, prints the table and exits with status 1 when a criterion failed.
fn hard_and_exit(args: &hard::HardArgs) -> anyhow::Result<()> {
    let report = hard::run(args)?;
    print!("{}", report.table());
    if report.failed() {
        let names: Vec<String> = report
            .failures()
            .map(|r| format!("{} {}", r.scene, r.check))
            .collect();
        eprintln!("hard cases failed: {}", names.join("; "));
        std::process::exit(1);
    }
    Ok(())
}

/// Runs the bonded-stiffness study, prints the table and exits with status 1 when a criterion
/// failed.
fn bonded_and_exit(args: &bonded::BondedArgs) -> anyhow::Result<()> {
    let report = bonded::run(args)?;
    print!("{}", report.table());
    if report.failed() {
        let names: Vec<String> = report
            .failures()
            .map(|r| format!("{} {} {}", r.scene, r.check, r.metric))
            .collect();
        eprintln!("bonded study failed: {}", names.join("; "));
        std::process::exit(1);
    }
    Ok(())
}

/// Runs the validation, prints the table and exits with status 1 when a check failed.
fn validate_and_exit(args: &validate::ValidateArgs) -> anyhow::Result<()> {
    let report = validate::run(args)?;
    print!("{}", report.table());
    if report.failed() {
        let names: Vec<String> = report
            .failures()
            .map(|r| format!("{} {} {}", r.scene, r.check, r.metric))
            .collect();
        eprintln!("validation failed: {}", names.join("; "));
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
    println!("== cargo xtask validate --quick");
    validate_and_exit(&validate::ValidateArgs {
        quick: true,
        ..Default::default()
    })
}
