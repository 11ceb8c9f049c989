//! Merged agents: pairs closer than [`MERGE_FRACTION`] · d. The α-force between two agents acts
//! along n_ij = σ_ε(q_j − q_i) (TAC 2006 eq. 9), which vanishes linearly as they meet, and ψ_α is
//! finite at zero distance: agents driven onto each other (a strong navigational or obstacle gain)
//! converge to one point and are never separated again. A run names the first such pair, when it
//! first appears at a record ([`Merge`]), and counts the merged agents of its final state
//! ([`MergedAgents`]).

use std::fmt;

use flock_graph::{Components, NeighbourSearch, ProximityNet};
use flock_math::Vector;
use glam::{DVec2, DVec3};

use crate::simulation::State;
use crate::time::time_text;

/// Agents closer than this fraction of the lattice distance d have merged: the α-force between
/// them is below 10⁻³ of its scale, and shrinks as they close.
pub const MERGE_FRACTION: f64 = 1e-3;

/// The first pair of agents found merged in a run, at the record where it first appears.
#[derive(Clone, Debug, PartialEq)]
pub struct Merge {
    /// The time of the record.
    pub t: f64,
    /// The step h (for printing t).
    pub step: f64,
    /// The closest pair (original indices, i < j).
    pub pair: (usize, usize),
    /// Its distance.
    pub distance: f64,
    /// The distance below which agents count as merged, [`MERGE_FRACTION`] · d.
    pub tolerance: f64,
}

impl fmt::Display for Merge {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (i, j) = self.pair;
        write!(
            f,
            "warning: agents {i} and {j} merged at t = {} (distance {:.3e} < 10⁻³ d = {:.3e}): the α-force along σ_ε(q_j − q_i) vanishes at zero distance, so they will not separate. Fix: lower the gain that drives them together (the navigational c1, or the obstacle gains)",
            time_text(self.t, self.step),
            self.distance,
            self.tolerance
        )
    }
}

/// The agents of a state that share a point with another (closer than [`MERGE_FRACTION`] · d),
/// and how many points they share.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MergedAgents {
    /// Agents within the tolerance of another.
    pub agents: usize,
    /// The groups they form (chains of pairs within the tolerance), each one point.
    pub points: usize,
}

impl fmt::Display for MergedAgents {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} agent(s) on {} point(s)", self.agents, self.points)
    }
}

/// The pairs of `state` closer than `tolerance`, as a net.
fn close_pairs(state: &State<'_>, tolerance: f64) -> ProximityNet {
    fn build<V: Vector + bytemuck::Pod>(rows: &[f64], tolerance: f64) -> ProximityNet {
        let q: &[V] = bytemuck::cast_slice(rows);
        let mut net = ProximityNet::new();
        NeighbourSearch::new().build(q, tolerance, &mut net);
        net
    }
    match state.dim {
        2 => build::<DVec2>(&state.positions, tolerance),
        _ => build::<DVec3>(&state.positions, tolerance),
    }
}

/// The closest pair of `state` (i < j) and its distance, among the pairs closer than `tolerance`.
#[must_use]
pub fn closest_pair(state: &State<'_>, tolerance: f64) -> Option<((usize, usize), f64)> {
    let net = close_pairs(state, tolerance);
    let graph = net.graph();
    let mut best: Option<((usize, usize), f64)> = None;
    for i in 0..graph.len() {
        for (e, &j) in graph.edge_range(i).zip(graph.neighbours(i)) {
            let (j, distance) = (j as usize, net.distances()[e]);
            if j > i && best.is_none_or(|(_, d)| distance < d) {
                best = Some(((i, j), distance));
            }
        }
    }
    best
}

/// The merged agents of `state`.
#[must_use]
pub fn merged_agents(state: &State<'_>, tolerance: f64) -> MergedAgents {
    let net = close_pairs(state, tolerance);
    let groups = Components::of(net.graph());
    let merged = groups.sizes().iter().filter(|&&size| size > 1);
    MergedAgents {
        agents: merged.clone().sum(),
        points: merged.count(),
    }
}
