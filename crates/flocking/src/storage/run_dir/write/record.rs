//! A run directory as the run's [`Recorder`]: each record appended to `metrics.csv` and the
//! trajectory, and a checkpoint every `checkpoint_every` steps.

use std::fmt::Write as _;
use std::io::{self, Write};

use super::columns::{failed, metrics_header, write_state};
use super::directory::{RunDirectory, Trajectory};
use super::note::{running_note, write_incomplete};
use crate::run::{Record, Recorder, Start};
use crate::storage::fs::at;
use crate::storage::run_dir::checkpoint::{Counts, write_checkpoint};

impl RunDirectory {
    /// Writes the header of `metrics.csv` with the first record's diagnostic columns, or checks
    /// that a later record names the same columns.
    fn check_columns(&mut self, record: &Record<'_>) -> io::Result<()> {
        let names = record.diagnostics.iter().map(|(name, _)| *name);
        match &self.columns {
            Some(columns) if names.clone().eq(columns.iter().map(String::as_str)) => Ok(()),
            Some(columns) => Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!(
                    "the record at t = {} has the diagnostic columns {:?} where metrics.csv has {columns:?}",
                    record.t,
                    names.collect::<Vec<_>>()
                ),
            )),
            None => {
                let columns: Vec<String> = names.map(str::to_owned).collect();
                let header = metrics_header(&columns);
                self.metrics
                    .write_all(header.as_bytes())
                    .map_err(at(format_args!(
                        "write {}",
                        self.partial.join("metrics.csv").display()
                    )))?;
                self.metrics_bytes += header.len() as u64;
                self.columns = Some(columns);
                Ok(())
            }
        }
    }
}

impl Recorder for RunDirectory {
    type Error = io::Error;

    fn record(&mut self, record: &Record<'_>) -> io::Result<()> {
        self.check_columns(record)?;
        let m = &record.metrics;
        let mut line = record.t.to_string();
        for value in m.reals() {
            let _ = write!(line, ",{value}");
        }
        let _ = write!(line, ",{},{}", m.collisions, record.energy);
        for value in m.extras() {
            let _ = write!(line, ",{value}");
        }
        let _ = write!(line, ",{}", m.components);
        for (_, value) in record.diagnostics {
            let _ = write!(line, ",{value}");
        }
        line.push('\n');
        let state = &record.state;
        let dim = state.dim;
        let width = state.vehicle_columns.len();
        self.last_state.clear();
        for (i, (q, p)) in state
            .positions
            .chunks_exact(dim)
            .zip(state.velocities.chunks_exact(dim))
            .enumerate()
        {
            self.last_state.extend_from_slice(q);
            self.last_state.extend_from_slice(p);
            self.last_state
                .extend_from_slice(&state.vehicle[i * width..(i + 1) * width]);
            if self.marks_failed {
                self.last_state.push(f64::from(u8::from(failed(state, i))));
            }
        }
        let row = self.row_width();
        match &mut self.trajectory {
            Trajectory::Csv { file, bytes } => {
                self.buffer.clear();
                for (i, agent) in self.last_state.chunks_exact(row).enumerate() {
                    let _ = write!(self.buffer, "{},", record.t);
                    write_state(&mut self.buffer, i, agent);
                }
                file.write_all(&self.buffer).map_err(at(format_args!(
                    "write {}",
                    self.partial.join("trajectory.csv").display()
                )))?;
                *bytes += self.buffer.len() as u64;
            }
            Trajectory::Npy(file) => {
                self.buffer.clear();
                self.buffer.extend_from_slice(&record.t.to_le_bytes());
                for rows in [&state.positions, &state.velocities, &state.vehicle] {
                    for x in rows.iter() {
                        self.buffer.extend_from_slice(&x.to_le_bytes());
                    }
                }
                if self.marks_failed {
                    let agents = state.agents();
                    self.buffer
                        .extend((0..agents).map(|i| u8::from(failed(state, i))));
                }
                file.append(&self.buffer).map_err(at(format_args!(
                    "write {}",
                    self.partial.join("trajectory.npy").display()
                )))?;
            }
        }
        self.metrics
            .write_all(line.as_bytes())
            .map_err(at(format_args!(
                "write {}",
                self.partial.join("metrics.csv").display()
            )))?;
        self.metrics_bytes += line.len() as u64;
        self.records += 1;
        Ok(())
    }

    fn wants_checkpoint(&self, steps: u64) -> bool {
        self.checkpoint_every > 0 && steps.is_multiple_of(self.checkpoint_every)
    }

    fn checkpoint(&mut self, start: &Start) -> io::Result<()> {
        // the records the checkpoint counts are on the disk before it is
        self.sync_outputs()?;
        let trajectory_bytes = match &self.trajectory {
            Trajectory::Csv { bytes, .. } => *bytes,
            Trajectory::Npy(file) => file.rows(),
        };
        let counts = Counts {
            dim: self.dim,
            records: self.records,
            metrics_bytes: self.metrics_bytes,
            trajectory_bytes,
        };
        write_checkpoint(&self.partial, &counts, start, &self.scenario)?;
        let whole = format!(
            "{}Whole records, checkpointed after step {}: {} (the first {} bytes of metrics.csv; of the trajectory, {} {}).\n",
            running_note(&self.target, self.force),
            start.steps,
            self.records,
            self.metrics_bytes,
            trajectory_bytes,
            match self.trajectory {
                Trajectory::Csv { .. } => "bytes",
                Trajectory::Npy(_) => "records",
            }
        );
        write_incomplete(&self.partial, &whole)
    }
}
