//! Where results come from: the machine, the commit, the build profile, the command and the
//! date.

use std::path::Path;
use std::process::Command;

use serde::{Deserialize, Serialize};

/// The machine a validation ran on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Machine {
    /// `uname -a`, or the OS and architecture where `uname` is missing.
    pub system: String,
    /// CPU model name.
    pub cpu: String,
    /// Logical cores available to this process.
    pub cores: usize,
}

impl Machine {
    /// Describes this machine.
    pub fn detect() -> Machine {
        let system = Command::new("uname")
            .arg("-a")
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
            .unwrap_or_else(|| format!("{} {}", std::env::consts::OS, std::env::consts::ARCH));
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|t| {
                t.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split(':').nth(1))
                    .map(|s| s.trim().to_string())
            })
            .unwrap_or_else(|| std::env::consts::ARCH.to_string());
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        Machine { system, cpu, cores }
    }

    /// One line: CPU, cores, system.
    pub fn description(&self) -> String {
        format!("{}, {} cores; {}", self.cpu, self.cores, self.system)
    }
}

/// Provenance of a report or a golden file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    /// The command that produced it.
    pub command: String,
    /// `git rev-parse HEAD`, with `-dirty` when the work tree has uncommitted changes.
    pub commit: String,
    /// UTC date and time.
    pub date: String,
    /// `release` or `debug`.
    pub profile: String,
    /// The machine.
    pub machine: Machine,
}

impl Provenance {
    /// Provenance of this process run in the repository at `root`.
    pub fn detect(root: &Path) -> Provenance {
        let args: Vec<String> = std::env::args().skip(1).collect();
        Provenance {
            command: format!("cargo xtask {}", args.join(" ")),
            commit: commit(root),
            date: utc_now(),
            profile: if cfg!(debug_assertions) {
                "debug"
            } else {
                "release"
            }
            .into(),
            machine: Machine::detect(),
        }
    }
}

fn git(root: &Path, args: &[&str]) -> Option<String> {
    Command::new("git")
        .args(args)
        .current_dir(root)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
}

/// The commit of the work tree at `root`, `-dirty` when it has uncommitted changes, or
/// `unknown` outside a git repository.
pub fn commit(root: &Path) -> String {
    match git(root, &["rev-parse", "HEAD"]) {
        Some(head) => {
            let dirty = git(root, &["status", "--porcelain", "--untracked-files=no"])
                .is_some_and(|s| !s.is_empty());
            if dirty { format!("{head}-dirty") } else { head }
        }
        None => "unknown".into(),
    }
}

/// The current UTC time as `YYYY-MM-DDTHH:MM:SSZ`.
pub fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    utc(secs)
}

/// `secs` since the Unix epoch as `YYYY-MM-DDTHH:MM:SSZ` (proleptic Gregorian calendar).
fn utc(secs: u64) -> String {
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    // Days to civil date (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utc_dates() {
        assert_eq!(utc(0), "1970-01-01T00:00:00Z");
        assert_eq!(utc(951_782_400), "2000-02-29T00:00:00Z");
        assert_eq!(utc(1_795_323_661), "2026-11-22T05:01:01Z");
    }
}
