//! `cargo xtask bench-peers`: the section-3 pendulum in strand and in Exudyn, timed side by
//! side. The benchmark itself is `benchmarks/exudyn/bench_peers.py`; this task builds the strand
//! binaries it calls (`strand`, the `peer_pendulum` example), checks that Python can import
//! Exudyn and runs it. Results: `target/bench-peers/report.{md,json}`.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{Context, bail};
use clap::Args;

/// The Exudyn release the benchmark was written and checked against.
const EXUDYN: &str = "exudyn==1.13.6";

/// Options of `cargo xtask bench-peers`.
#[derive(Args, Debug, Clone)]
pub struct BenchPeersArgs {
    /// Interleaved timing rounds (strand, Exudyn, strand, ...).
    #[arg(long, default_value_t = 3)]
    pub rounds: usize,
    /// Laws to compare, comma-separated (`constant`, `continuous`).
    #[arg(long, default_value = "constant,continuous")]
    pub laws: String,
    /// Python interpreter with Exudyn installed (default: $PYTHON, else python3).
    #[arg(long)]
    pub python: Option<String>,
    /// Output folder.
    #[arg(long, default_value = "target/bench-peers")]
    pub out: PathBuf,
    /// Multiply Exudyn's bending stiffness: a deliberately wrong peer model, to see the
    /// agreement check fail.
    #[arg(long, default_value_t = 1.0, hide = true)]
    pub scale_ei: f64,
    /// Also write the table into its page of the manual (docs/book/src/performance.md, between the
    /// `bench-peers` markers); only for a full run.
    #[arg(long)]
    pub update_docs: bool,
}

/// Builds the strand side, checks for Exudyn and runs the benchmark; exits with its status.
pub fn run(args: &BenchPeersArgs) -> anyhow::Result<()> {
    if args.update_docs && args.scale_ei != 1.0 {
        bail!("--update-docs writes the manual's table: drop --scale-ei");
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let python = args
        .python
        .clone()
        .or_else(|| std::env::var("PYTHON").ok())
        .unwrap_or_else(|| "python3".into());
    let probe = Command::new(&python)
        .args(["-c", "import exudyn; print(exudyn.config.Version())"])
        .output();
    match probe {
        Ok(out) if out.status.success() => {
            let version = String::from_utf8_lossy(&out.stdout);
            println!("== Exudyn {} ({python})", version.trim());
        }
        Ok(_) => {
            eprintln!(
                "bench-peers: `{python}` cannot import exudyn. Install it with\n\n    \
                 {python} -m pip install -r benchmarks/exudyn/requirements.txt\n\n\
                 ({EXUDYN}, from PyPI), or name another interpreter with --python or \
                 $PYTHON. Nothing was timed."
            );
            std::process::exit(2);
        }
        Err(e) => {
            eprintln!(
                "bench-peers: cannot run `{python}` ({e}). The benchmark needs Python 3 with \
                 {EXUDYN} (`{python} -m pip install -r benchmarks/exudyn/requirements.txt`); \
                 name the interpreter with --python or $PYTHON. Nothing was timed."
            );
            std::process::exit(2);
        }
    }
    crate::cargo(&["build", "--release", "-p", "strand-cli"], &[])?;
    crate::cargo(
        &[
            "build",
            "--release",
            "-p",
            "strand-scene",
            "--example",
            "peer_pendulum",
        ],
        &[],
    )?;
    let target = std::env::var_os("CARGO_TARGET_DIR").map_or(root.join("target"), PathBuf::from);
    let exe = |p: &str| target.join("release").join(p);
    let status = Command::new(&python)
        .arg(root.join("benchmarks/exudyn/bench_peers.py"))
        .arg("--strand-bin")
        .arg(exe("examples/peer_pendulum"))
        .arg("--strand-cli")
        .arg(exe("strand"))
        .args(["--scene", "validation/paper-fig14-pendulum.json"])
        .arg("--out")
        .arg(&args.out)
        .args(["--rounds", &args.rounds.to_string()])
        .args(["--laws", &args.laws])
        .args(["--scale-ei", &args.scale_ei.to_string()])
        .args(["--python", &python])
        .current_dir(&root)
        .status()
        .context("running benchmarks/exudyn/bench_peers.py")?;
    match status.code() {
        Some(0) if args.update_docs => {
            let path = args.out.join("report.md");
            let md = std::fs::read_to_string(&path)
                .with_context(|| format!("reading {}", path.display()))?;
            let table = crate::book::pages::first_table(&md)
                .with_context(|| format!("{} has no table", path.display()))?;
            crate::book::pages::update(crate::book::pages::Page::Performance, "bench-peers", &table)
        }
        Some(0) => Ok(()),
        Some(code) => std::process::exit(code),
        None => bail!("bench_peers.py was stopped by a signal"),
    }
}
