//! Figures of chosen frames of a run: snapshots (TAC 2006 Figs. 10–17), a 3D frame in four views,
//! a frame read as Reynolds's rules (ACC 2004 § 4), and one frame as an RGB pixel buffer.

pub mod four_views;
pub mod reynolds;
pub mod rgb;
pub mod snapshot;
