//! The state of a group of double-integrator agents.

use flock_graph::Numbering;
use flock_math::{Vector, mean};

/// Positions q and velocities p of n agents with dynamics q̇_i = p_i, ṗ_i = u_i (TAC 2006 eq. 1).
#[derive(Clone, Debug, PartialEq)]
pub struct Swarm<V> {
    /// Positions q_i.
    pub positions: Vec<V>,
    /// Velocities p_i.
    pub velocities: Vec<V>,
}

impl<V: Vector> Swarm<V> {
    /// A swarm from positions and velocities of equal length.
    ///
    /// # Panics
    /// When the two lengths differ.
    #[must_use]
    pub fn new(positions: Vec<V>, velocities: Vec<V>) -> Self {
        assert_eq!(
            positions.len(),
            velocities.len(),
            "one velocity per position"
        );
        Self {
            positions,
            velocities,
        }
    }

    /// The number of agents n.
    #[must_use]
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// True when there is no agent.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// The centre of mass q_c = (1/n) Σ q_i.
    #[must_use]
    pub fn centre(&self) -> V {
        mean(&self.positions)
    }

    /// The average velocity p_c = (1/n) Σ p_i.
    #[must_use]
    pub fn mean_velocity(&self) -> V {
        mean(&self.velocities)
    }
}

/// ½ Σ ‖p_i − p_ref‖², summed in ascending original index ([`Numbering::ordered_sum`]).
pub(crate) fn kinetic<V: Vector>(velocities: &[V], numbering: &Numbering, reference: V) -> f64 {
    let p = velocities;
    0.5 * numbering.ordered_sum(p.len(), |i| (p[i] - reference).length_squared())
}

/// The heading mismatch n − ‖Σ_i p̂_i‖ ≥ 0 (p̂_i = p_i/‖p_i‖, 0 at rest): 0 when every agent
/// heads alike, n (1 − polarisation). The `energy` column of the models that decrease no
/// energy (Vicsek, boids, Couzin, Vásárhelyi), the headings added in ascending original index.
pub(crate) fn heading_mismatch<V: Vector>(velocities: &[V], numbering: &Numbering) -> f64 {
    let total = numbering
        .ordered(velocities)
        .fold(V::ZERO, |acc, p| acc + p.normalize_or_zero());
    velocities.len() as f64 - total.length()
}
