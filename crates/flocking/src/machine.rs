//! What this machine has for a run: its cores ([`cores`], the bound of `--threads`), the memory
//! available to this process and the free space where a run writes ([`Resources`]).

use std::path::Path;

/// The most threads (or sweep workers) per available core: more only adds switching.
pub const THREADS_PER_CORE: usize = 4;

/// The cores this process may use.
#[must_use]
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZero::get)
}

/// `threads` when it is from 1 to [`THREADS_PER_CORE`] × the available cores.
///
/// # Errors
/// Outside that range, with the range and the fix.
pub fn check_threads(threads: usize) -> Result<usize, String> {
    let most = THREADS_PER_CORE * cores();
    if (1..=most).contains(&threads) {
        Ok(threads)
    } else {
        Err(format!(
            "give a whole number from 1 to {most} ({THREADS_PER_CORE} × the {} available cores)",
            cores()
        ))
    }
}

/// What this machine offers: memory for a run and disk for its outputs (`None`: unknown).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Resources {
    /// Memory available, in bytes.
    pub memory_bytes: Option<f64>,
    /// Free space where the outputs go, in bytes.
    pub disk_bytes: Option<f64>,
    /// Where the outputs go, named by the message of a disk too small (issue 27: "0 B is free
    /// there" named no path).
    pub disk_path: Option<std::path::PathBuf>,
}

impl Resources {
    /// The memory available to this process (`MemAvailable`, or the cgroup's `memory.max` less
    /// its `memory.current` when lower) and the free space of the disk holding `out` (or its
    /// nearest existing ancestor).
    #[must_use]
    pub fn of_machine(out: &Path) -> Self {
        Self {
            memory_bytes: available_memory(),
            disk_bytes: free_space(out),
            disk_path: Some(out.to_owned()),
        }
    }
}

pub(crate) fn available_memory() -> Option<f64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok();
    let available = meminfo
        .as_deref()
        .and_then(|text| kilobytes(text, "MemAvailable:"));
    let read = |name: &str| -> Option<f64> {
        std::fs::read_to_string(Path::new("/sys/fs/cgroup").join(name))
            .ok()?
            .trim()
            .parse()
            .ok()
    };
    let cgroup = read("memory.max").map(|max| max - read("memory.current").unwrap_or(0.0));
    [available, cgroup, address_space_left()]
        .into_iter()
        .flatten()
        .reduce(f64::min)
}

/// The bytes of the line `name  N kB` of a `/proc` file's `text`.
fn kilobytes(text: &str, name: &str) -> Option<f64> {
    let rest = text.lines().find_map(|line| line.strip_prefix(name))?;
    let kb = rest
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse::<f64>()
        .ok()?;
    Some(kb * 1024.0)
}

/// The address space this process may still map when it is limited (`ulimit -v`, `RLIMIT_AS`
/// of `/proc/self/limits`, less the `VmSize` of `/proc/self/status`): beyond it an allocation
/// fails and the process aborts (issue 27).
fn address_space_left() -> Option<f64> {
    let limits = std::fs::read_to_string("/proc/self/limits").ok()?;
    let soft = limits
        .lines()
        .find_map(|line| line.strip_prefix("Max address space"))?
        .split_whitespace()
        .next()?
        .parse::<f64>()
        .ok()?;
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let used = kilobytes(&status, "VmSize:").unwrap_or(0.0);
    Some((soft - used).max(0.0))
}

#[cfg(unix)]
fn free_space(out: &Path) -> Option<f64> {
    let existing = out
        .ancestors()
        .find(|p| p.exists())
        .unwrap_or(Path::new("."));
    let existing = if existing.as_os_str().is_empty() {
        Path::new(".")
    } else {
        existing
    };
    let stat = rustix::fs::statvfs(existing).ok()?;
    Some(stat.f_bavail as f64 * stat.f_frsize as f64)
}

#[cfg(not(unix))]
fn free_space(_out: &Path) -> Option<f64> {
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn this_machine_reports_memory_and_disk() {
        let resources = Resources::of_machine(Path::new("no/such/dir"));
        assert!(resources.memory_bytes.is_some_and(|m| m > 0.0));
        assert!(resources.disk_bytes.is_some_and(|d| d > 0.0));
    }
}
