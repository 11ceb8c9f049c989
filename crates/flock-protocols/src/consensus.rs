//! Velocity consensus, the velocity matching protocol the flocking papers build on (CDS 03-006,
//! seed 000, Proposition 1, eq. 9), and the protocol of the delay and sampled-data theorems of
//! consensus (Olfati-Saber & Murray, IEEE TAC 49(9), 2004).

use flock_graph::{Graph, ProximityNet};
use flock_math::parallel::fill_interruptible;
use flock_math::{Vector, mean_of};

use crate::error::{ParamError, check};
use crate::swarm::kinetic;
use crate::{LocalForm, Perceived, Protocol, Swarm};

/// u_i = c Σ_{j ∈ N_i} (p_j − p_i), c > 0 (seed 000 eq. 9): ṗ = −c (L ⊗ I) p with L the Laplacian
/// of a fixed graph (node k agent k) or of the proximity net (a_ij = 1 when ‖q_j − q_i‖ < r).
///
/// Σ_i u_i = 0, so the mean velocity is invariant, and the velocity mismatch
/// K_r = ½ Σ_i ‖p_i − p̄‖² ([`Protocol::energy`]) has K̇_r = −c p̃ᵀ L p̃ ≤ 0 (eq. 11): on a
/// connected graph every velocity converges to the initial mean. The positions play no part but
/// to define the proximity net.
///
/// # Example
/// ```
/// use flock_graph::{Graph, ProximityNet};
/// use flock_protocols::{Consensus, Protocol, Swarm};
/// use glam::DVec2;
///
/// // a path of three agents: u_i = −c Σ_{j∼i} (p_i − p_j) pulls each velocity towards its
/// // neighbours' (run to the mean (1, 0) by flock-sim's test `consensus_meets_at_the_mean`)
/// let graph = Graph::from_edges(3, &[(0, 1), (1, 2)])?;
/// let p = vec![DVec2::new(3.0, 0.0), DVec2::ZERO, DVec2::ZERO];
/// let swarm = Swarm::new(vec![DVec2::ZERO; 3], p);
/// let mut u = vec![DVec2::ZERO; 3];
/// Consensus::fixed(1.0, graph, 1.0)?.controls(0.0, &swarm, &ProximityNet::new(), &mut u);
/// assert_eq!(u, vec![DVec2::new(-3.0, 0.0), DVec2::new(3.0, 0.0), DVec2::ZERO]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Consensus {
    gain: f64,
    range: f64,
    graph: Option<Graph>,
}

impl Consensus {
    /// Consensus with gain `c` on the proximity net of radius `range`.
    ///
    /// # Errors
    /// `gain` or `range` not positive and finite.
    pub fn proximity(gain: f64, range: f64) -> Result<Self, ParamError> {
        check::positive("gain", gain)?;
        check::positive("range", range)?;
        Ok(Self {
            gain,
            range,
            graph: None,
        })
    }

    /// Consensus with gain `c` on the fixed `graph`; `range` is the radius of the proximity net
    /// the simulation builds for its metrics only.
    ///
    /// # Errors
    /// `gain` or `range` not positive and finite.
    pub fn fixed(gain: f64, graph: Graph, range: f64) -> Result<Self, ParamError> {
        Ok(Self {
            graph: Some(graph),
            ..Self::proximity(gain, range)?
        })
    }

    /// The gain c.
    #[must_use]
    pub const fn gain(&self) -> f64 {
        self.gain
    }

    /// c Σ_j (p_j − p_i) over the velocities `others`, in their order.
    #[inline]
    fn sum<V: Vector>(&self, pi: V, others: impl Iterator<Item = V>) -> V {
        let mut total = V::ZERO;
        for pj in others {
            total += pj - pi;
        }
        total * self.gain
    }
}

impl<V: Vector> Protocol<V> for Consensus {
    fn interaction_range(&self) -> f64 {
        self.range
    }

    fn uses_net_distances(&self) -> bool {
        false
    }

    /// On the proximity net the sums run over each agent's list, in ascending original index.
    fn follows_numbering(&self) -> bool {
        self.graph.is_none()
    }

    /// # Panics
    /// On a fixed graph, when the swarm and the graph have different sizes.
    fn controls(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let p = &swarm.velocities;
        let graph = self.graph.as_ref().unwrap_or(net.graph());
        assert_eq!(graph.len(), p.len(), "one agent per graph node");
        fill_interruptible(inputs, |i| {
            let neighbours = graph.neighbours(i).iter();
            self.sum(p[i], neighbours.map(|&j| p[j as usize]))
        });
    }

    /// The velocity mismatch K_r = ½ Σ_i ‖p_i − p̄‖² (seed 000 eq. 11: K̇_r = −c p̃ᵀ L p̃ ≤ 0).
    fn energy(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        let numbering = net.numbering();
        let p_bar = mean_of(numbering.ordered(&swarm.velocities));
        kinetic(&swarm.velocities, numbering, p_bar)
    }

    fn interaction_graph(&self) -> Option<&Graph> {
        self.graph.as_ref()
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }
}

/// u_i = c Σ_j (p_j − p_i) over the agents heard: on the proximity net those within r by their
/// perceived distance, on a fixed graph every graph neighbour heard.
impl<V: Vector> LocalForm<V> for Consensus {
    fn local_input(&self, _t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        let r2 = self.range * self.range;
        let near = |o: &&Perceived<V>| {
            self.graph.is_some() || (o.position - own.position).length_squared() < r2
        };
        self.sum(own.velocity, heard.iter().filter(near).map(|o| o.velocity))
    }
}
