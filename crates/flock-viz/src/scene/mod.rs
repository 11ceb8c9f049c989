//! What the figures draw, independent of files: a run's frames and range ([`frames`]), its
//! obstacles ([`drawable`]), the part of the plane shown ([`framing`]) and the projection onto the
//! page ([`projection`]).

pub mod drawable;
pub mod frames;
pub mod framing;
pub mod projection;
