//! Smooth primitives of flocking theory (Olfati-Saber, IEEE TAC 51(3) 2006; Caltech CDS 03-006 2003;
//! ACC 2004; Tanner, Jadbabaie & Pappas 2003).
//!
//! - [`Vector`]: the 2D/3D abstraction every crate of flock is generic over.

pub mod vector;

pub use vector::Vector;
