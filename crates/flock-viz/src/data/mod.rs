//! A run directory read back for drawing: its frames ([`run_data`]) and its metric time series
//! ([`metric_series`]).

pub mod metric_series;
pub mod run_data;
