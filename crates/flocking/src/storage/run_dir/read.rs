//! Reading a run directory back: `metrics.csv` as named columns, the trajectory (`trajectory.csv`
//! or `trajectory.npy`) as arrays of times, positions and velocities, and the resolved
//! `scenario.ron` ([`read_run`]). Errors name the file and, for a malformed line, the line.

use std::io;
use std::path::Path;

pub use super::read_error::ReadError;
use super::table::Table;
use crate::scenario::Scenario;

/// The name of the time column of `metrics.csv`.
pub const TIME: &str = "t";

/// The last column of a trajectory row when the scenario has `faults`: 1 when the agent has
/// failed (in any mode, `docs/conditions.md`), else 0.
pub const FAILED_COLUMN: &str = "failed";

/// The columns of a `metrics.csv`, by name, in file order (`t` first).
pub type Columns = Vec<(String, Vec<f64>)>;

/// A recorded trajectory: frame k at time `times[k]` holds agent i's position at
/// `positions[(k * agents + i) * dim..][..dim]`, its velocity likewise.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trajectory {
    /// The dimension, 2 or 3.
    pub dim: usize,
    /// The number of agents.
    pub agents: usize,
    /// The recorded times.
    pub times: Vec<f64>,
    /// The positions, frame by frame, agent by agent.
    pub positions: Vec<f64>,
    /// The velocities, as the positions.
    pub velocities: Vec<f64>,
    /// The names of each agent's vehicle state (empty for point masses).
    pub vehicle_columns: Vec<String>,
    /// The vehicles' states, frame by frame, agent by agent, `vehicle_columns.len()` each.
    pub vehicle: Vec<f64>,
    /// Whether each agent has failed, frame by frame, agent by agent, when the trajectory
    /// marks it (the scenario has `faults`); empty otherwise.
    pub failed: Vec<bool>,
}

impl Trajectory {
    /// The number of recorded frames.
    #[must_use]
    pub fn frames(&self) -> usize {
        self.times.len()
    }

    /// The positions of frame `k`: `agents` rows of `dim` coordinates.
    #[must_use]
    pub fn positions_at(&self, k: usize) -> &[f64] {
        let size = self.agents * self.dim;
        &self.positions[k * size..(k + 1) * size]
    }

    /// The velocities of frame `k`.
    #[must_use]
    pub fn velocities_at(&self, k: usize) -> &[f64] {
        let size = self.agents * self.dim;
        &self.velocities[k * size..(k + 1) * size]
    }

    /// The vehicles' states of frame `k`: `agents` rows of `vehicle_columns.len()` values.
    #[must_use]
    pub fn vehicle_at(&self, k: usize) -> &[f64] {
        let size = self.agents * self.vehicle_columns.len();
        &self.vehicle[k * size..(k + 1) * size]
    }

    /// Which agents of frame `k` have failed, when the trajectory marks it.
    #[must_use]
    pub fn failed_at(&self, k: usize) -> Option<&[bool]> {
        (!self.failed.is_empty()).then(|| &self.failed[k * self.agents..(k + 1) * self.agents])
    }
}

/// What a run directory holds.
#[derive(Clone, Debug, PartialEq)]
pub struct RunFiles {
    /// The resolved scenario of the run (`scenario.ron`).
    pub scenario: Scenario,
    /// The rows of `metrics.csv`, by column.
    pub metrics: Columns,
    /// The recorded trajectory.
    pub trajectory: Trajectory,
}

/// Reads the run in `dir` (written by [`RunDirectory`](super::RunDirectory), complete or
/// `DIR.partial`): its scenario, metrics and trajectory (`trajectory.npy` when there is no
/// `trajectory.csv`).
///
/// # Errors
/// A file that is missing or malformed, named with its line, or a scenario that does not load.
pub fn read_run(dir: &Path) -> Result<RunFiles, ReadError> {
    if !dir.join("scenario.ron").is_file() {
        let why = if dir.is_dir() {
            "not a run directory: it holds no scenario.ron, which every directory `flocking run \
             --out` writes holds (and its DIR.partial while it runs); give one of those"
        } else {
            "no such directory: give a directory `flocking run --out` wrote"
        };
        return Err(ReadError::io(
            dir,
            io::Error::new(io::ErrorKind::NotFound, why),
        ));
    }
    let scenario = Scenario::load(dir.join("scenario.ron")).map_err(ReadError::Scenario)?;
    let metrics = read_metrics(&dir.join("metrics.csv"))?;
    let csv = dir.join("trajectory.csv");
    let npy = dir.join("trajectory.npy");
    let trajectory = if !csv.exists() && npy.exists() {
        named_vehicle_columns(read_trajectory_npy(&npy)?, &scenario, &npy)?
    } else {
        read_trajectory_csv(&csv)?
    };
    Ok(RunFiles {
        scenario,
        metrics,
        trajectory,
    })
}

/// `trajectory` of a `.npy` file, whose vehicle states are one unnamed field `s`, with its
/// columns named as the scenario's vehicle names them (as `trajectory.csv` writes them; issue 49:
/// they read back as `s1`, `s2`, …).
///
/// # Errors
/// A trajectory of another number of vehicle state values than the scenario's vehicle has.
fn named_vehicle_columns(
    mut trajectory: Trajectory,
    scenario: &Scenario,
    path: &Path,
) -> Result<Trajectory, ReadError> {
    let names = scenario.vehicle.state_columns(scenario.dim);
    if names.len() != trajectory.vehicle_columns.len() {
        return Err(ReadError::Parse {
            path: path.to_owned(),
            line: 1,
            message: format!(
                "it holds {} vehicle state values per agent where the scenario's vehicle {} has {}: it is not the trajectory of this run",
                trajectory.vehicle_columns.len(),
                scenario.vehicle.name(),
                names.len()
            ),
        });
    }
    trajectory.vehicle_columns = names.iter().map(|&name| name.to_owned()).collect();
    Ok(trajectory)
}

/// Reads a `metrics.csv`: a header with a `t` column, then rows of numbers.
///
/// # Errors
/// As [`read_run`].
pub fn read_metrics(path: &Path) -> Result<Columns, ReadError> {
    let table = Table::read(path)?;
    if table.column_index(TIME).is_none() {
        return Err(table.error_at(
            1,
            format!(
                "the header has no {TIME:?} column: {:?}",
                table.header.join(",")
            ),
        ));
    }
    Ok(table
        .header
        .iter()
        .enumerate()
        .map(|(k, name)| {
            (
                name.clone(),
                table.rows.iter().map(|(_, row)| row[k]).collect(),
            )
        })
        .collect())
}

/// The header of a `trajectory.csv` in `dim` dimensions: `t,id,x,y[,z],vx,vy[,vz]`.
#[must_use]
pub fn trajectory_header(dim: usize) -> Vec<String> {
    let axes = &["x", "y", "z"][..dim];
    ["t", "id"]
        .iter()
        .map(|s| (*s).to_owned())
        .chain(axes.iter().map(|a| (*a).to_owned()))
        .chain(axes.iter().map(|a| format!("v{a}")))
        .collect()
}

/// The header of a `trajectory.csv` in `dim` dimensions of agents whose vehicles have the
/// state columns `vehicle` (after the velocity; none for point masses).
#[must_use]
pub fn trajectory_header_with(dim: usize, vehicle: &[&str]) -> Vec<String> {
    let mut header = trajectory_header(dim);
    header.extend(vehicle.iter().map(|c| (*c).to_owned()));
    header
}

/// Reads a `trajectory.csv` (`t,id,x,y,vx,vy` or `t,id,x,y,z,vx,vy,vz`, then the vehicle's
/// state columns if any, then [`FAILED_COLUMN`] if the run has faults): rows grouped by t, each
/// frame listing every agent once (in any order).
///
/// # Errors
/// As [`read_run`]: a wrong header, an id out of range or repeated, an agent missing from a
/// frame, time going backwards.
pub fn read_trajectory_csv(path: &Path) -> Result<Trajectory, ReadError> {
    let table = Table::read(path)?;
    let Some(dim) = [2, 3]
        .into_iter()
        .find(|&dim| table.header.starts_with(&trajectory_header(dim)))
    else {
        return Err(table.error_at(
            1,
            format!(
                "expected the header {:?} (2D) or {:?} (3D), found {:?}",
                trajectory_header(2).join(","),
                trajectory_header(3).join(","),
                table.header.join(",")
            ),
        ));
    };
    let rest = &table.header[2 + 2 * dim..];
    let marks_failed = rest.last().is_some_and(|c| c == FAILED_COLUMN);
    let mut trajectory = Trajectory {
        dim,
        vehicle_columns: rest[..rest.len() - usize::from(marks_failed)].to_vec(),
        ..Trajectory::default()
    };
    let mut start = 0;
    while start < table.rows.len() {
        let t = table.rows[start].1[0];
        let end = start
            + table.rows[start..]
                .iter()
                .take_while(|(_, row)| row[0].to_bits() == t.to_bits())
                .count();
        if let Some((line, row)) = table.rows.get(end)
            && row[0].partial_cmp(&t) != Some(std::cmp::Ordering::Greater)
        {
            return Err(table.error_at(
                *line,
                format!("t = {} after t = {t}: rows must be in time order", row[0]),
            ));
        }
        if trajectory.times.is_empty() {
            trajectory.agents = end - start;
        } else if end - start != trajectory.agents {
            return Err(table.error_at(
                table.rows[start].0,
                format!(
                    "the frame at t = {t} has {} rows, the first frame has {}: \
                     every frame lists every agent",
                    end - start,
                    trajectory.agents
                ),
            ));
        }
        push_frame(
            &table,
            &table.rows[start..end],
            marks_failed,
            &mut trajectory,
        )?;
        start = end;
    }
    Ok(trajectory)
}

/// Appends the frame of the rows of one time, agents in id order; with `marks_failed`, each
/// row ends with [`FAILED_COLUMN`], 0 or 1.
fn push_frame(
    table: &Table,
    rows: &[(usize, Vec<f64>)],
    marks_failed: bool,
    trajectory: &mut Trajectory,
) -> Result<(), ReadError> {
    let (n, dim) = (rows.len(), trajectory.dim);
    let mut slots: Vec<Option<&[f64]>> = vec![None; n];
    for (line, row) in rows {
        if let Some(&flag) = row.last().filter(|_| marks_failed)
            && flag != 0.0
            && flag != 1.0
        {
            return Err(table.error_at(
                *line,
                format!("{FAILED_COLUMN} is {flag}: it is 1 for an agent that has failed, else 0"),
            ));
        }
        let id = row[1];
        if !(id >= 0.0 && id < n as f64 && id.fract() == 0.0) {
            return Err(table.error_at(
                *line,
                format!(
                    "id {id} is not an agent index: the frame at t = {} has {n} rows, ids 0 to {}",
                    row[0],
                    n - 1
                ),
            ));
        }
        let slot = &mut slots[id as usize];
        if slot.is_some() {
            return Err(table.error_at(*line, format!("id {id} appears twice at t = {}", row[0])));
        }
        *slot = Some(&row[2..]);
    }
    trajectory.times.push(rows[0].1[0]);
    // n rows, ids in 0..n, none twice: every slot is filled
    for state in slots.into_iter().flatten() {
        let (state, flag) = state.split_at(state.len() - usize::from(marks_failed));
        trajectory.positions.extend_from_slice(&state[..dim]);
        trajectory
            .velocities
            .extend_from_slice(&state[dim..2 * dim]);
        trajectory.vehicle.extend_from_slice(&state[2 * dim..]);
        trajectory.failed.extend(flag.iter().map(|&f| f == 1.0));
    }
    Ok(())
}

/// Reads a `trajectory.npy` as [`RunDirectory`](super::RunDirectory) writes it: a NumPy 1.0 file of
/// records `[('t', '<f8'), ('q', '<f8', (n, dim)), ('p', '<f8', (n, dim))]`, then the vehicles'
/// `('s', '<f8', (n, k))` and the marks `('failed', '|u1', (n,))` when the run has them, one
/// record per frame (only the records its header counts). The file does not name the vehicle's
/// k state values: they are `s1` to `sk` here, and [`read_run`] names them as the run's scenario
/// does.
///
/// # Errors
/// As [`read_run`] (line 1: the header) when it is not such a file.
pub fn read_trajectory_npy(path: &Path) -> Result<Trajectory, ReadError> {
    let bytes = std::fs::read(path).map_err(|e| ReadError::io(path, e))?;
    let bad = |message: String| ReadError::Parse {
        path: path.to_owned(),
        line: 1,
        message,
    };
    let header_end = bytes
        .get(8..10)
        .filter(|_| bytes.starts_with(b"\x93NUMPY\x01\x00"))
        .map(|len| 10 + usize::from(u16::from_le_bytes([len[0], len[1]])))
        .ok_or_else(|| bad("not a NumPy 1.0 .npy file".to_owned()))?;
    let header = bytes
        .get(10..header_end)
        .and_then(|h| std::str::from_utf8(h).ok())
        .ok_or_else(|| bad("the header is cut or not ASCII".to_owned()))?;
    let numbers_after = |key: &str| -> Option<Vec<usize>> {
        let rest = &header[header.find(key)? + key.len()..];
        let inner = &rest[..rest.find(')')?];
        inner
            .split(',')
            .map(str::trim)
            .filter(|x| !x.is_empty())
            .map(|x| x.parse().ok())
            .collect()
    };
    let (agents, dim, records) = match (
        numbers_after("('q', '<f8', ("),
        numbers_after("'shape': ("),
    ) {
        (Some(q), Some(shape))
            if q.len() == 2
                && (q[1] == 2 || q[1] == 3)
                && shape.len() == 1
                && header.contains("[('t', '<f8'), ('q', '<f8', ")
                && header.contains("('p', '<f8', ") =>
        {
            (q[0], q[1], shape[0])
        }
        _ => {
            return Err(bad(format!(
                "expected records [('t', '<f8'), ('q', '<f8', (n, dim)), ('p', '<f8', (n, dim))], found {}",
                header.trim_end()
            )));
        }
    };
    let vehicle = match numbers_after("('s', '<f8', (") {
        Some(s) if s.len() == 2 && s[0] == agents => s[1],
        _ => 0,
    };
    let flags = match numbers_after(&format!("('{FAILED_COLUMN}', '|u1', (")) {
        Some(s) if s == [agents] => agents,
        _ => 0,
    };
    let reals = 1 + agents * (2 * dim + vehicle);
    let record = 8 * reals + flags;
    let data = &bytes[header_end..];
    if data.len() / record.max(1) < records {
        return Err(bad(format!(
            "the header counts {records} records but the file holds {}",
            data.len() / record.max(1)
        )));
    }
    let mut trajectory = Trajectory {
        dim,
        agents,
        vehicle_columns: (1..=vehicle).map(|k| format!("s{k}")).collect(),
        ..Trajectory::default()
    };
    for r in data.chunks_exact(record).take(records) {
        let (values, failed) = r.split_at(8 * reals);
        if let Some(flag) = failed.iter().find(|&&f| f > 1) {
            return Err(bad(format!(
                "record {} has {FAILED_COLUMN} = {flag}: it is 1 for an agent that has failed, else 0",
                trajectory.times.len()
            )));
        }
        let values: Vec<f64> = values
            .chunks_exact(8)
            .map(|b| f64::from_le_bytes(b.try_into().unwrap_or_default()))
            .collect();
        let (q, rest) = values[1..].split_at(agents * dim);
        let (p, s) = rest.split_at(agents * dim);
        trajectory.times.push(values[0]);
        trajectory.positions.extend_from_slice(q);
        trajectory.velocities.extend_from_slice(p);
        trajectory.vehicle.extend_from_slice(s);
        trajectory.failed.extend(failed.iter().map(|&f| f == 1));
    }
    Ok(trajectory)
}
