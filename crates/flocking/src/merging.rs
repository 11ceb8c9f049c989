//! Merged agents: pairs closer than [`MERGE_FRACTION`] · d. The α-force between two agents acts
//! along n_ij = σ_ε(q_j − q_i) (TAC 2006 eq. 9), which vanishes linearly as they meet, and ψ_α is
//! finite at zero distance: agents driven onto each other (a strong navigational or obstacle gain)
//! converge to one point and are never separated again. A run names the first such pair, when it
//! first appears at a record ([`Merge`]), and counts the merged agents of its final state
//! ([`MergedAgents`]). A pair found at the start was placed there ([`MergeCause::Start`]), most
//! often by a random start denser than the α-lattice ([`DenseStart`]): the gains play no part.

use std::fmt;

use flock_graph::{Components, NeighbourSearch, ProximityNet};
use flock_math::Vector;
use glam::{DVec2, DVec3};

use crate::estimate::{LATTICE_DEGREE, start_edges};
use crate::scenario::{Algorithm, Scenario};
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
    /// Why: driven together, or as they started.
    pub cause: MergeCause,
}

impl fmt::Display for Merge {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (i, j) = self.pair;
        let t = time_text(self.t, self.step);
        let (distance, tolerance) = (self.distance, self.tolerance);
        match &self.cause {
            MergeCause::Driven => write!(
                f,
                "warning: agents {i} and {j} merged at t = {t} (distance {distance:.3e} < 10⁻³ d = {tolerance:.3e}): the α-force along σ_ε(q_j − q_i) vanishes at zero distance, so they will not separate. Fix: lower the gain that drives them together (the navigational c1, or the obstacle gains)"
            ),
            MergeCause::Start(dense) => {
                write!(
                    f,
                    "warning: agents {i} and {j} start merged (distance {distance:.3e} < 10⁻³ d = {tolerance:.3e} at t = {t}): the gains play no part, "
                )?;
                match dense {
                    Some(dense) => write!(
                        f,
                        "the start is {dense}, and a random start that dense places pairs that close; the α-force, which vanishes at zero distance, parts them slowly. Fix: {}",
                        dense.fix()
                    ),
                    None => write!(
                        f,
                        "the initial positions place them that close; the α-force, which vanishes at zero distance, parts them slowly. Fix: start every pair of agents at least 10⁻³ d apart"
                    ),
                }
            }
        }
    }
}

/// Why two agents are found merged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MergeCause {
    /// They came together during the run: a gain drove them onto each other.
    Driven,
    /// They start that close; the start's density when it is denser than the α-lattice.
    Start(Option<DenseStart>),
}

/// How many times the α-lattice's degree ([`LATTICE_DEGREE`]) the start's mean degree within r
/// must exceed to count as dense: a uniform random start at the lattice's density (n agents on
/// n · √3/2 d², the area of its hexagonal cells) has mean degree π (1.2 d)² · 2/(√3 d²) ≈ 5.2
/// in the plane, below the lattice's 6; twice the lattice's degree is a start packed more than
/// twice as densely as the lattice, its agents well under d apart.
pub const DENSE_FACTOR: f64 = 2.0;

/// A start denser than the α-lattice: its agents start well under d apart, a random one places
/// some pairs within [`MERGE_FRACTION`] · d, and the α-forces throw the crowd apart before it
/// flocks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DenseStart {
    /// The start's mean number of neighbours within the range r.
    pub degree: f64,
    /// The α-lattice's: 6 in the plane, 12 in space.
    pub lattice: f64,
    /// The range r.
    pub range: f64,
    /// The lattice distance d.
    pub d: f64,
    /// The number of agents.
    pub agents: usize,
    /// The dimension.
    pub dim: usize,
}

impl DenseStart {
    /// The start of `scenario` when it is denser than the α-lattice (mean degree within r above
    /// [`DENSE_FACTOR`] times the lattice's), for the algorithms that form α-lattices
    /// (Algorithms 1–3, the 2003 protocols); `None` otherwise, or when the start is too dense to
    /// count (the estimate refuses it).
    #[must_use]
    pub fn of(scenario: &Scenario) -> Option<Self> {
        let forms_lattice = matches!(
            scenario.algorithm,
            Algorithm::Algorithm1
                | Algorithm::Algorithm2(_)
                | Algorithm::Algorithm3(_)
                | Algorithm::Flocking2003(_)
        );
        if !forms_lattice || scenario.agents < 2 {
            return None;
        }
        let edges = match scenario.dim {
            2 => start_edges::<DVec2>(scenario),
            _ => start_edges::<DVec3>(scenario),
        }?;
        let dim = scenario.dim.clamp(2, 3);
        let dense = Self {
            degree: 2.0 * edges as f64 / scenario.agents as f64,
            lattice: LATTICE_DEGREE[dim - 2],
            range: scenario.range(),
            d: scenario.alpha.d,
            agents: scenario.agents,
            dim,
        };
        (dense.degree > DENSE_FACTOR * dense.lattice).then_some(dense)
    }

    /// The fix: a region that holds the agents about d apart, n times the lattice's cell
    /// (√3/2 d² in the plane, d³/√2 in space: the hexagonal and the face-centred cubic cell).
    #[must_use]
    pub fn fix(&self) -> String {
        let (cell, formula, region, side) = if self.dim == 2 {
            (
                3f64.sqrt() / 2.0 * self.d.powi(2),
                "√3/2 d²",
                "an area",
                "a square",
            )
        } else {
            (self.d.powi(3) / 2f64.sqrt(), "d³/√2", "a volume", "a cube")
        };
        let size = self.agents as f64 * cell;
        format!(
            "spread `initial.positions` over {region} of at least n · {formula} = {size:.1} ({side} of side {:.1}), so that the agents start about d = {} apart",
            size.powf(1.0 / self.dim as f64),
            self.d
        )
    }
}

impl fmt::Display for DenseStart {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "denser than the α-lattice: {:.1} neighbours per agent within r = {} on average, where an α-lattice has {}",
            self.degree, self.range, self.lattice
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
