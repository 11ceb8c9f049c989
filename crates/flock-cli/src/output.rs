//! The output directory of `flock run`: `metrics.csv`, `trajectory.csv`, `final.csv` and the
//! resolved `scenario.ron`, written into a sibling `DIR.partial` that is renamed to `DIR` only when
//! the run completes, so a failed run leaves nothing partial behind.

use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use flock_math::Vector;

use crate::run::{Record, Recorder};
use crate::scenario::Scenario;

/// The header of `metrics.csv`.
pub const METRICS_HEADER: &str = "t,connectivity,giant_component,cohesion_radius,deviation_energy,velocity_mismatch,min_distance,collisions,energy";

/// An output directory being written.
#[derive(Debug)]
pub struct RunDirectory {
    target: PathBuf,
    partial: PathBuf,
    metrics: BufWriter<File>,
    trajectory: BufWriter<File>,
    dim: usize,
    last_state: Vec<u8>,
}

impl RunDirectory {
    /// Starts writing the run of `scenario` to `target`; refuses an existing non-empty `target`
    /// unless `force`.
    ///
    /// # Errors
    /// When `target` holds files and `force` is false, or on any I/O error.
    pub fn create(target: &Path, scenario: &Scenario, force: bool) -> io::Result<Self> {
        let non_empty = fs::read_dir(target).is_ok_and(|mut entries| entries.next().is_some());
        if non_empty && !force {
            return Err(io::Error::new(
                io::ErrorKind::AlreadyExists,
                format!(
                    "output directory {} already holds files; choose another --out or pass --force to replace it",
                    target.display()
                ),
            ));
        }
        let mut partial = target.as_os_str().to_owned();
        partial.push(".partial");
        let partial = PathBuf::from(partial);
        if partial.exists() {
            fs::remove_dir_all(&partial)?;
        }
        fs::create_dir_all(&partial)?;
        let text = scenario.to_ron().map_err(io::Error::other)?;
        fs::write(partial.join("scenario.ron"), text + "\n")?;
        let mut metrics = BufWriter::new(File::create(partial.join("metrics.csv"))?);
        write!(metrics, "{METRICS_HEADER}")?;
        for column in scenario.extra_columns() {
            write!(metrics, ",{column}")?;
        }
        writeln!(metrics)?;
        let mut trajectory = BufWriter::new(File::create(partial.join("trajectory.csv"))?);
        writeln!(trajectory, "t,{}", state_header(scenario.dim))?;
        Ok(Self {
            target: target.to_owned(),
            partial,
            metrics,
            trajectory,
            dim: scenario.dim,
            last_state: Vec::new(),
        })
    }

    /// Writes `final.csv` and moves the directory into place.
    ///
    /// # Errors
    /// On any I/O error (the partial directory is then removed).
    pub fn finish(mut self) -> io::Result<PathBuf> {
        let result = self.complete();
        if result.is_err() {
            let _ = fs::remove_dir_all(&self.partial);
        }
        result.map(|()| self.target)
    }

    fn complete(&mut self) -> io::Result<()> {
        self.metrics.flush()?;
        self.trajectory.flush()?;
        let mut last = format!("{}\n", state_header(self.dim)).into_bytes();
        last.extend_from_slice(&self.last_state);
        fs::write(self.partial.join("final.csv"), last)?;
        if self.target.exists() {
            fs::remove_dir_all(&self.target)?;
        }
        fs::rename(&self.partial, &self.target)
    }

    /// Abandons the run: removes the partial directory.
    pub fn abandon(self) {
        let _ = fs::remove_dir_all(&self.partial);
    }
}

/// `id,x,y[,z],vx,vy[,vz]`.
fn state_header(dim: usize) -> String {
    let axes = &["x", "y", "z"][..dim];
    let velocities: Vec<String> = axes.iter().map(|a| format!("v{a}")).collect();
    format!("id,{},{}", axes.join(","), velocities.join(","))
}

/// Appends `id,x,y[,z],vx,vy[,vz]` of agent `i` (shortest round-trip decimal forms).
fn write_state<V: Vector>(out: &mut impl Write, i: usize, q: V, p: V) -> io::Result<()> {
    write!(out, "{i}")?;
    for v in [q, p] {
        for k in 0..V::DIM {
            write!(out, ",{}", v.coord(k))?;
        }
    }
    writeln!(out)
}

impl Recorder for RunDirectory {
    type Error = io::Error;

    fn record<V: Vector>(&mut self, record: &Record<'_, V>) -> io::Result<()> {
        let m = &record.metrics;
        write!(
            self.metrics,
            "{},{},{},{},{},{},{},{},{}",
            record.t,
            m.connectivity,
            m.giant_component,
            m.cohesion_radius,
            m.deviation_energy,
            m.velocity_mismatch,
            m.min_distance,
            m.collisions,
            record.energy
        )?;
        for value in record.extra {
            write!(self.metrics, ",{value}")?;
        }
        writeln!(self.metrics)?;
        self.last_state.clear();
        let swarm = record.swarm;
        for (i, (&q, &p)) in swarm.positions.iter().zip(&swarm.velocities).enumerate() {
            write!(self.trajectory, "{},", record.t)?;
            write_state(&mut self.trajectory, i, q, p)?;
            write_state(&mut self.last_state, i, q, p)?;
        }
        Ok(())
    }
}
