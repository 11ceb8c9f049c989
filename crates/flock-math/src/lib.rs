//! Smooth primitives of flocking theory: the σ-norm, bump functions, action functions and pairwise
//! potentials of Olfati-Saber (IEEE TAC 51(3) 2006; Caltech CDS 03-006, 2003; ACC 2004) and of
//! Tanner, Jadbabaie & Pappas (2003), with the 2D/3D [`Vector`] abstraction.
//!
//! - [`Vector`]: the one code path for [`glam::DVec2`] and [`glam::DVec3`].
//! - [`Domain`]: open space or a periodic box, with the minimum image.
//! - [`SigmaNorm`], [`sigma1`], [`sigma1_vec`]: the σ-norm, its gradient σ_ε and the sigmoid σ₁.
//! - [`Bump`]: ρ_h (TAC eq. 10) and the C^k influence map (ACC 2004 eq. 4).
//! - [`Potential`]: a pair ψ, φ = ψ′, implemented by [`UnevenSigmoid`] (2003 eq. 29),
//!   [`BumpedAction`] (φ_α, ψ_α, φ_β, ψ_β of TAC 2006) and [`TannerPotential`].
//! - [`GaussLegendre`], [`CumulativeIntegral`]: the quadrature behind ψ_α and ψ_β.
//! - [`stream`]: keyed, counter-based random streams (Philox), on which the models' noise and the
//!   real conditions both stand.
//! - [`parallel`]: the one switch between rayon and serial loops (feature `parallel`, default), and
//!   [`interrupt`]: the process's Ctrl-C, which the long loops of a step check per block of work.

pub mod action;
pub mod bump;
pub mod domain;
pub mod interrupt;
pub mod parallel;
pub mod potential;
pub mod quadrature;
pub mod sigma;
pub mod sigmoid;
pub mod stream;
pub mod tanner;
pub mod vector;

pub use action::BumpedAction;
pub use bump::Bump;
pub use domain::{Domain, minimum_image, periodic_displacement, wrap_coordinate};
pub use potential::Potential;
pub use quadrature::{CumulativeIntegral, GaussLegendre};
pub use sigma::{SigmaNorm, sigma1, sigma1_vec};
pub use sigmoid::UnevenSigmoid;
pub use tanner::TannerPotential;
pub use vector::{Vector, mean, mean_of};
