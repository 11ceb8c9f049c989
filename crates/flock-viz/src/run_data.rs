//! [`RunData`]: what `flock run --out DIR` wrote, read back: `metrics.csv` as [`Metrics`] and
//! `trajectory.csv` as [`Frame`]s (formats in the workspace README, "What a run prints and
//! writes").

use std::path::Path;

use glam::DVec3;

use crate::error::VizError;
use crate::metrics::{Metrics, TIME};
use crate::scene::{Frame, Scene};
use crate::table::Table;

/// The header of a 2D `trajectory.csv`.
const TRAJECTORY_2D: [&str; 6] = ["t", "id", "x", "y", "vx", "vy"];
/// The header of a 3D `trajectory.csv`.
const TRAJECTORY_3D: [&str; 8] = ["t", "id", "x", "y", "z", "vx", "vy", "vz"];

/// A run's outputs: its dimension, metric time series and recorded frames.
#[derive(Clone, Debug, PartialEq)]
pub struct RunData {
    /// The dimension, 2 or 3 (from the columns of `trajectory.csv`).
    pub dim: usize,
    /// The rows of `metrics.csv`.
    pub metrics: Metrics,
    /// The frames of `trajectory.csv`, in time order, agents in id order.
    pub frames: Vec<Frame>,
}

impl RunData {
    /// Reads `dir/metrics.csv` and `dir/trajectory.csv` (or `dir/trajectory.npy` when the run
    /// wrote that instead).
    ///
    /// # Errors
    /// [`VizError::Io`] naming a file that cannot be read, [`VizError::Parse`] naming the file
    /// and line of a malformed row (wrong field count, a field that is not a number, an id out of
    /// range or repeated, an agent missing from a frame, time going backwards).
    pub fn load(dir: &Path) -> Result<Self, VizError> {
        let metrics = load_metrics(&dir.join("metrics.csv"))?;
        let npy = dir.join("trajectory.npy");
        let csv = dir.join("trajectory.csv");
        let (dim, frames) = if !csv.exists() && npy.exists() {
            load_trajectory_npy(&npy)?
        } else {
            load_trajectory(&csv)?
        };
        Ok(Self {
            dim,
            metrics,
            frames,
        })
    }

    /// The scene of this run with interaction range `range` (for the net's edges), no obstacles
    /// and no γ-agent: add them with [`Scene::with_obstacle`] and [`Scene::with_gamma`].
    #[must_use]
    pub fn scene(&self, range: f64) -> Scene {
        let mut scene = Scene::new(self.dim, range);
        scene.frames.clone_from(&self.frames);
        scene
    }
}

/// Reads a `metrics.csv`: a header with a `t` column, then rows of numbers.
///
/// # Errors
/// As [`RunData::load`].
pub fn load_metrics(path: &Path) -> Result<Metrics, VizError> {
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
    let columns = table
        .header
        .iter()
        .enumerate()
        .map(|(k, name)| {
            (
                name.clone(),
                table.rows.iter().map(|(_, row)| row[k]).collect(),
            )
        })
        .collect();
    Metrics::from_columns(columns).map_err(|e| table.error_at(1, e.to_string()))
}

/// Reads a `trajectory.csv` (`t,id,x,y,vx,vy` or `t,id,x,y,z,vx,vy,vz`): the dimension and the
/// frames, rows grouped by t, agents ordered by id.
///
/// # Errors
/// As [`RunData::load`].
pub fn load_trajectory(path: &Path) -> Result<(usize, Vec<Frame>), VizError> {
    let table = Table::read(path)?;
    let dim = if table.header == TRAJECTORY_2D {
        2
    } else if table.header == TRAJECTORY_3D {
        3
    } else {
        return Err(table.error_at(
            1,
            format!(
                "expected the header {:?} (2D) or {:?} (3D), found {:?}",
                TRAJECTORY_2D.join(","),
                TRAJECTORY_3D.join(","),
                table.header.join(",")
            ),
        ));
    };
    let mut frames = Vec::new();
    let mut start = 0;
    while start < table.rows.len() {
        let t = table.rows[start].1[0];
        let end = start
            + table.rows[start..]
                .iter()
                .take_while(|(_, row)| row[0].to_bits() == t.to_bits())
                .count();
        if let Some((line, row)) = table.rows.get(end) {
            if row[0].partial_cmp(&t) != Some(std::cmp::Ordering::Greater) {
                return Err(table.error_at(
                    *line,
                    format!("t = {} after t = {t}: rows must be in time order", row[0]),
                ));
            }
        }
        if let Some(first) = frames.first().map(|f: &Frame| f.positions.len()) {
            if end - start != first {
                return Err(table.error_at(
                    table.rows[start].0,
                    format!(
                        "the frame at t = {t} has {} rows, the first frame has {first}: \
                         every frame lists every agent",
                        end - start
                    ),
                ));
            }
        }
        frames.push(frame_of(&table, &table.rows[start..end], dim)?);
        start = end;
    }
    Ok((dim, frames))
}

/// Reads a `trajectory.npy` as `flock run --trajectory-format npy` writes it: a NumPy 1.0 file of
/// records `[('t', '<f8'), ('q', '<f8', (n, dim)), ('p', '<f8', (n, dim))]`, one per frame.
///
/// # Errors
/// [`VizError::Io`] when it cannot be read, [`VizError::Parse`] (line 1: the header) when it is
/// not such a file.
pub fn load_trajectory_npy(path: &Path) -> Result<(usize, Vec<Frame>), VizError> {
    let bytes = std::fs::read(path).map_err(|source| VizError::Io {
        path: path.to_owned(),
        source,
    })?;
    let bad = |message: String| VizError::Parse {
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
    let record = 1 + 2 * agents * dim;
    let data: Vec<f64> = bytes[header_end..]
        .chunks_exact(8)
        .take(records * record)
        .map(|b| f64::from_le_bytes(b.try_into().unwrap_or_default()))
        .collect();
    if data.len() < records * record {
        return Err(bad(format!(
            "the header counts {records} records but the file holds {}",
            data.len() / record
        )));
    }
    let vector = |v: &[f64]| DVec3::new(v[0], v[1], if dim == 3 { v[2] } else { 0.0 });
    let frames = data
        .chunks_exact(record)
        .map(|r| {
            let (q, p) = r[1..].split_at(agents * dim);
            Frame::new(
                r[0],
                q.chunks_exact(dim).map(vector).collect(),
                p.chunks_exact(dim).map(vector).collect(),
            )
        })
        .collect();
    Ok((dim, frames))
}

/// The frame of the rows of one time.
fn frame_of(table: &Table, rows: &[(usize, Vec<f64>)], dim: usize) -> Result<Frame, VizError> {
    let n = rows.len();
    let mut slots: Vec<Option<(DVec3, DVec3)>> = vec![None; n];
    for (line, row) in rows {
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
        let vector = |offset: usize| {
            DVec3::new(
                row[offset],
                row[offset + 1],
                if dim == 3 { row[offset + 2] } else { 0.0 },
            )
        };
        let slot = &mut slots[id as usize];
        if slot.is_some() {
            return Err(table.error_at(*line, format!("id {id} appears twice at t = {}", row[0])));
        }
        *slot = Some((vector(2), vector(2 + dim)));
    }
    // n rows, ids in 0..n, none twice: every slot is filled.
    let (positions, velocities) = slots.into_iter().flatten().unzip();
    Ok(Frame::new(rows[0].1[0], positions, velocities))
}
