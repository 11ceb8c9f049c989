//! Curves: a run's metrics against t (TAC 2006 Fig. 18) and the report's functions (CDS 03-006
//! Figs. 2, 4, 5).

pub mod functions;
pub mod metric_curves;
