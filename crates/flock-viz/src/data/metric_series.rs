//! [`Metrics`]: the metric time series of a run, column by column, as `metrics.csv` holds them
//! (TAC 2006 Section VIII; the columns are listed in docs/outputs.md).

use crate::error::VizError;

/// The name of the time column, which every [`Metrics`] has.
pub const TIME: &str = "t";

/// The metric time series of a run: named columns of equal length, one of them [`TIME`].
///
/// The columns flocking writes (docs/outputs.md, "metrics.csv"): `t`, `connectivity` (C),
/// `giant_component` (C*), `cohesion_radius` (R), `deviation_energy` (Ẽ), `velocity_mismatch`
/// (K̃), `min_distance`, `collisions`, `energy` (H), and with obstacles `obstacle_clearance`,
/// `inside_obstacles`. Columns the figures do not know are kept and ignored.
///
/// # Example
/// ```
/// use flock_viz::Metrics;
///
/// let m = Metrics::from_columns(vec![
///     ("t".into(), vec![0.0, 1.0]),
///     ("connectivity".into(), vec![0.5, 1.0]),
/// ])
/// .unwrap();
/// assert_eq!(m.len(), 2);
/// assert_eq!(m.column("connectivity"), Some(&[0.5, 1.0][..]));
/// assert_eq!(m.time(), &[0.0, 1.0]);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Metrics {
    names: Vec<String>,
    columns: Vec<Vec<f64>>,
}

impl Metrics {
    /// Metrics from named columns, in order.
    ///
    /// # Errors
    /// [`VizError::Invalid`] when there is no [`TIME`] column, a name repeats, or the columns
    /// differ in length.
    pub fn from_columns(columns: Vec<(String, Vec<f64>)>) -> Result<Self, VizError> {
        let (names, columns): (Vec<String>, Vec<Vec<f64>>) = columns.into_iter().unzip();
        if !names.iter().any(|n| n == TIME) {
            return Err(VizError::invalid(format!(
                "metrics need a {TIME:?} column, got {names:?}"
            )));
        }
        for (k, name) in names.iter().enumerate() {
            if names[..k].contains(name) {
                return Err(VizError::invalid(format!(
                    "metric column {name:?} appears twice"
                )));
            }
        }
        if let Some(k) = columns.iter().position(|c| c.len() != columns[0].len()) {
            return Err(VizError::invalid(format!(
                "metric column {:?} has {} values, column {:?} has {}",
                names[k],
                columns[k].len(),
                names[0],
                columns[0].len()
            )));
        }
        Ok(Self { names, columns })
    }

    /// The column names, in order.
    #[must_use]
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The values of column `name`, if there is one.
    #[must_use]
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        let k = self.names.iter().position(|n| n == name)?;
        Some(&self.columns[k])
    }

    /// The times t (s) of the rows.
    #[must_use]
    pub fn time(&self) -> &[f64] {
        self.column(TIME).unwrap_or_default()
    }

    /// The number of rows.
    #[must_use]
    pub fn len(&self) -> usize {
        self.columns.first().map_or(0, Vec::len)
    }

    /// Whether there are no rows.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}
