//! The fixed-topology flocking law of Tanner, Jadbabaie & Pappas, *Stable flocking of mobile
//! agents, Part I: fixed topology*, 2003 (seed 001), and a seeded generator of random connected
//! graphs for it.

use core::fmt;

use flock_graph::{Components, Graph, ProximityNet};
use flock_math::{Potential, TannerPotential, Vector, mean};

use crate::{LocalForm, Perceived, Protocol, Swarm};
use flock_math::parallel::fill_interruptible;

/// The Tanner–Jadbabaie–Pappas law on a fixed connected neighbouring graph G (seed 001 eq. 5):
///
/// u_i = −Σ_{j∼i} (v_i − v_j) − Σ_{j∼i} ∇_{r_i} V_ij,  ∇_{r_i} V_ij = V′(‖r_ij‖) r_ij/‖r_ij‖,
/// r_ij = r_i − r_j,
///
/// with the pair potential V_ij = V(‖r_ij‖) of [`TannerPotential`] (→ ∞ at 0, unique minimum at the
/// desired distance; Definition IV.3). The graph is the user's and never changes (Assumption IV.2:
/// connected); the proximity net the simulation builds is not used by the law, only by metrics, so
/// [`Protocol::interaction_range`] returns a range of the caller's choice.
///
/// [`Protocol::energy`] is W = ½ Σ_i (V_i + v_iᵀ v_i), V_i = Σ_{j∼i} V_ij, with Ẇ = −vᵀ(L ⊗ I)v ≤ 0
/// (Theorem IV.4): velocities align, and linked agents never collide, since V_ij ≤ W(0) bounds
/// their distance away from 0 ([`TannerJadbabaiePappas::collision_bound`]).
#[derive(Clone, Debug, PartialEq)]
pub struct TannerJadbabaiePappas {
    graph: Graph,
    potential: TannerPotential,
    range: f64,
}

/// Why [`TannerJadbabaiePappas::new`] refused a graph: it is not connected (Assumption IV.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DisconnectedGraph {
    /// The number of connected components of the graph (0 for no agents).
    pub components: usize,
}

impl fmt::Display for DisconnectedGraph {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the neighbouring graph must be connected; it has {} components",
            self.components
        )
    }
}

impl std::error::Error for DisconnectedGraph {}

impl TannerJadbabaiePappas {
    /// The law on the fixed `graph` with pair potential `potential`; `range` is the radius of the
    /// proximity net built for metrics only (e.g. a few desired distances).
    ///
    /// # Errors
    /// [`DisconnectedGraph`] unless the graph is connected.
    pub fn new(
        graph: Graph,
        potential: TannerPotential,
        range: f64,
    ) -> Result<Self, DisconnectedGraph> {
        let components = Components::of(&graph);
        if !components.is_connected() {
            return Err(DisconnectedGraph {
                components: components.count(),
            });
        }
        Ok(Self {
            graph,
            potential,
            range,
        })
    }

    /// The neighbouring graph G.
    #[must_use]
    pub const fn graph(&self) -> &Graph {
        &self.graph
    }

    /// The pair potential V_ij.
    #[must_use]
    pub const fn pair_potential(&self) -> &TannerPotential {
        &self.potential
    }

    /// u_i for agent `i` (eq. 5). Linked agents at the same position give a NaN input, as the law
    /// is undefined there (V_ij = ∞).
    #[must_use]
    pub fn input<V: Vector>(&self, i: usize, r: &[V], v: &[V]) -> V {
        let neighbours = self.graph.neighbours(i).iter().map(|&j| j as usize);
        self.sum(r[i], v[i], neighbours.map(|j| (r[j], v[j])))
    }

    /// −Σ_j (v_i − v_j) + ∇_{r_i} V_ij over the states `others` = (r_j, v_j), in their order: the
    /// one sum of [`TannerJadbabaiePappas::input`] and of the [`LocalForm`].
    #[inline]
    fn sum<V: Vector>(&self, ri: V, vi: V, others: impl Iterator<Item = (V, V)>) -> V {
        let mut total = V::ZERO;
        for (rj, vj) in others {
            let r_ij = ri - rj;
            let distance = r_ij.length();
            total -= (vi - vj) + r_ij * (self.potential.action(distance) / distance);
        }
        total
    }

    /// ½ Σ_i V_i = Σ_{(i,j)∈E} V_ij, the potential part of W.
    #[must_use]
    pub fn potential_energy<V: Vector>(&self, r: &[V]) -> f64 {
        let mut total = 0.0;
        for i in 0..self.graph.len() {
            for &j in self.graph.neighbours(i) {
                if j as usize > i {
                    total += self.potential.potential((r[j as usize] - r[i]).length());
                }
            }
        }
        total
    }

    /// W = ½ Σ_i (V_i + v_iᵀ v_i) (seed 001, proof of Theorem IV.4).
    #[must_use]
    pub fn lyapunov<V: Vector>(&self, swarm: &Swarm<V>) -> f64 {
        let kinetic: f64 = swarm.velocities.iter().map(|v| v.length_squared()).sum();
        self.potential_energy(&swarm.positions) + 0.5 * kinetic
    }

    /// The velocity disagreement ½ Σ_i ‖v_i − v̄‖²: zero exactly when all velocities are equal,
    /// the outcome of Theorem IV.4 (Fig. 6–8 show the velocity vectors converging).
    #[must_use]
    pub fn velocity_disagreement<V: Vector>(velocities: &[V]) -> f64 {
        let v_bar = mean(velocities);
        0.5 * velocities
            .iter()
            .map(|&v| (v - v_bar).length_squared())
            .sum::<f64>()
    }

    /// The largest pairwise velocity mismatch max_{i,j} ‖v_i − v_j‖ (0 for fewer than two agents).
    #[must_use]
    pub fn max_velocity_mismatch<V: Vector>(velocities: &[V]) -> f64 {
        let mut worst: f64 = 0.0;
        for (i, &vi) in velocities.iter().enumerate() {
            for &vj in &velocities[i + 1..] {
                worst = worst.max((vi - vj).length());
            }
        }
        worst
    }

    /// The smallest distance between linked agents, min_{(i,j)∈E} ‖r_ij‖ (∞ without edges).
    #[must_use]
    pub fn min_linked_distance<V: Vector>(&self, r: &[V]) -> f64 {
        let mut least = f64::INFINITY;
        for i in 0..self.graph.len() {
            for &j in self.graph.neighbours(i) {
                least = least.min((r[j as usize] - r[i]).length());
            }
        }
        least
    }

    /// The collision-avoidance guarantee of Theorem IV.4 from an energy level `w` (e.g. W(0)): W is
    /// non-increasing and V_ij ≤ W, so linked agents stay at least z* apart, the solution below the
    /// desired distance d of V(z*) = w (bisection; d itself when w ≤ 0).
    #[must_use]
    pub fn collision_bound(&self, w: f64) -> f64 {
        let d = self.potential.distance();
        let (mut lo, mut hi) = (0.0, d);
        // V decreases on (0, d] from +∞ to 0: keep V(lo) > w ≥ V(hi)
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.potential.potential(mid) > w {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        lo
    }
}

impl<V: Vector> Protocol<V> for TannerJadbabaiePappas {
    /// The metrics range given to [`TannerJadbabaiePappas::new`]; the law ignores the net.
    fn interaction_range(&self) -> f64 {
        self.range
    }

    /// # Panics
    /// When the swarm and the graph have different sizes.
    fn controls(&self, _t: f64, swarm: &Swarm<V>, _net: &ProximityNet, inputs: &mut [V]) {
        assert_eq!(swarm.len(), self.graph.len(), "one agent per graph node");
        let (r, v) = (&swarm.positions, &swarm.velocities);
        fill_interruptible(inputs, |i| self.input(i, r, v));
    }

    /// W = ½ Σ_i (V_i + v_iᵀ v_i) (seed 001): Ẇ = −vᵀ(L ⊗ I)v ≤ 0.
    fn energy(&self, _t: f64, swarm: &Swarm<V>, _net: &ProximityNet) -> f64 {
        self.lyapunov(swarm)
    }

    fn uses_net_distances(&self) -> bool {
        false
    }

    /// The fixed neighbouring graph: C and C* are those of the graph the agents interact on
    /// (connected, Assumption IV.2), not of the proximity net.
    fn interaction_graph(&self) -> Option<&Graph> {
        Some(&self.graph)
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }

    /// `velocity_disagreement` (½ Σ ‖v_i − v̄‖²) and `min_linked_distance`.
    fn diagnostics(
        &self,
        _t: f64,
        swarm: &Swarm<V>,
        _net: &ProximityNet,
    ) -> Vec<(&'static str, f64)> {
        vec![
            (
                "velocity_disagreement",
                Self::velocity_disagreement(&swarm.velocities),
            ),
            (
                "min_linked_distance",
                self.min_linked_distance(&swarm.positions),
            ),
        ]
    }
}

/// u_i of eq. 5 from agent i's perception: `heard` are the graph neighbours whose messages
/// arrived (a neighbour not heard adds nothing; the graph itself never changes).
impl<V: Vector> LocalForm<V> for TannerJadbabaiePappas {
    fn local_input(&self, _t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        let others = heard.iter().map(|o| (o.position, o.velocity));
        self.sum(own.position, own.velocity, others)
    }
}

/// A random connected graph on `n` nodes, deterministic for `seed` (seed 001 § V: "generated in
/// random, with the only requirement being that it is connected"): a uniformly random labelled
/// recursive tree — the nodes in a random order, each joined to a uniformly chosen earlier one —
/// plus every other pair independently with probability `extra`.
///
/// The random numbers come from [`SplitMix64`], so the graph is the same on every platform.
///
/// # Example
/// ```
/// use flock_graph::Components;
/// use flock_protocols::random_connected_graph;
///
/// let g = random_connected_graph(10, 0.2, 7);
/// assert!(Components::of(&g).is_connected());
/// assert!(g.undirected_edge_count() >= 9);
/// assert_eq!(g, random_connected_graph(10, 0.2, 7));
/// ```
#[must_use]
pub fn random_connected_graph(n: usize, extra: f64, seed: u64) -> Graph {
    let mut rng = SplitMix64::new(seed);
    let mut order: Vec<usize> = (0..n).collect();
    // Fisher–Yates
    for k in (1..n).rev() {
        order.swap(k, rng.below(k + 1));
    }
    let mut linked = vec![false; n * n];
    let mut edges = Vec::new();
    for k in 1..n {
        let (child, parent) = (order[k], order[rng.below(k)]);
        linked[child * n + parent] = true;
        linked[parent * n + child] = true;
        edges.push((child, parent));
    }
    for i in 0..n {
        for j in i + 1..n {
            if !linked[i * n + j] && rng.unit() < extra {
                edges.push((i, j));
            }
        }
    }
    let Ok(graph) = Graph::from_edges(n, &edges) else {
        unreachable!("the edges join distinct nodes below n");
    };
    graph
}

/// SplitMix64 (Steele, Lea & Flood 2014, the seeding generator of Java's `SplittableRandom`): a
/// 64-bit state advanced by the golden-ratio increment and mixed by two xor-shift-multiply rounds.
/// Small, fast and statistically sound for test fixtures; not cryptographic.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// The generator started from `seed`.
    #[must_use]
    pub const fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform number in [0, 1) with 53 random bits.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A number in 0..bound (bound > 0) by the multiply-shift map of the 64 bits (bias below
    /// bound / 2⁶⁴).
    pub fn below(&mut self, bound: usize) -> usize {
        ((u128::from(self.next_u64()) * bound as u128) >> 64) as usize
    }
}
