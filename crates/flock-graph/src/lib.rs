//! Proximity nets of flocking (Olfati-Saber, IEEE TAC 51(3) 2006; ACC 2004): the graphs, weights
//! and matrices of a flock, for 2D and 3D through [`flock_math::Vector`].
//!
//! - [`Graph`]: an undirected graph in CSR form, edges stored in both directions.
//! - [`ProximityNet`]: the net N_i = { j ≠ i : ‖q_j − q_i‖ < r } with its edge lengths (or
//!   without them: [`ProximityNet::without_distances`], [`ProximityNet::edge_lengths`]), built in
//!   expected O(n) by [`NeighbourSearch`] (a uniform cell grid), exactly as
//!   [`ProximityNet::brute_force`]; [`nearest_pair_distance`] for the closest pair. On a periodic
//!   box ([`flock_math::Domain`]) by minimum image: [`NeighbourSearch::build_in`],
//!   [`ProximityNet::brute_force_in`], [`ProximityNet::edge_lengths_in`], and each agent's
//!   nearest-neighbour distance, [`NeighbourSearch::nearest_distances_in`].
//! - [`binary_weights`], [`weights_from_distances`]: adjacency weights a_ij per directed edge.
//! - [`laplacian_apply`], [`laplacian_row`], [`laplacian_quadratic_form`]: L̂ = (Δ(A) − A) ⊗ I_m without matrices;
//!   [`laplacian_eigenvalues`], [`weighted_laplacian_eigenvalues`]: the spectrum of L.
//! - [`StressWeights`], [`Friends`]: stress weights, local stress, signed friends and centres.
//! - [`Components`]: connected components (flocks) and the density δ₀.
//! - [`Numbering`]: agents stored out of their original order (sorted in space), with nets and
//!   sums that keep the original order's bits.
//!
//! Feature `parallel` (default, [`flock_math::parallel`]'s switch): build nets and apply Laplacians
//! on the rayon pool; results are bit-identical without it.

pub mod adjacency;
pub mod components;
pub mod graph;
pub mod laplacian;
pub mod net;
pub mod numbering;
pub mod search;
pub mod stress;

pub use adjacency::{binary_weights, weights_from_distances};
pub use components::Components;
pub use graph::{Graph, GraphError};
pub use laplacian::{
    laplacian_apply, laplacian_eigenvalues, laplacian_quadratic_form, laplacian_row,
    weighted_laplacian_eigenvalues,
};
pub use net::ProximityNet;
pub use numbering::{Numbering, Ordered};
pub use search::{NeighbourSearch, nearest_pair_distance};
pub use stress::{Friends, StressWeights};
