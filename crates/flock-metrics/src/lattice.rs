//! How close a (final) configuration is to an α-lattice: the shape of its proximity net.
//!
//! CDS 03-006 (seed 004, § 11, Fig. 9) describes the limiting net of the sink run as "a planar
//! graph that dominantly consists of equilateral triangular faces"; TAC 2006 (seed 002, Theorem 5)
//! bounds the net of an α-lattice: it is planar and has at most 3n − 6 links in dimension 2.
//! [`LatticeSummary::measure`] counts what those statements are about:
//!
//! - the edges |E| of the net and those within ±10 % of d (a quasi α-lattice with edge-length
//!   uncertainty δ = 0.1 d, seed 002 "quasi α-lattice": −δ ≤ ‖q_j − q_i‖ − d ≤ δ);
//! - the triangles of the net (its 3-cliques) and the *equilateral* ones, whose three edges are all
//!   within the tolerance of d;
//! - Theorem 5 ii)'s bound 3n − 6 (2D, n ≥ 3) and the crossings of the straight-line drawing of the
//!   net (2D): an exact α-lattice has none (Theorem 5 i).
//!
//! Both counts cost more than the net as it grows dense (O(Σ_i deg_i²) for the triangles, and
//! for the crossings the pairs of edges whose midpoints are within the longest edge: thousands per
//! edge with Vásárhelyi's r_c = 100 m, |E|² when every agent sees every other). Each is counted
//! when its work is at most [`WORK_BUDGET`] pair tests, or [`WORK_PER_EDGE`] per edge (so every
//! net near a lattice, of any size); beyond that it is `None`, and the summary says the net was too
//! dense. A summary computed once at the end of a run must not outlast the run, nor exhaust memory.
//!
//! In 3D neither statement holds: the face-centred cubic lattice of spacing d with r = 1.2 d is an
//! α-lattice with twelve neighbours per agent, |E| → 6n, so [`LatticeSummary::edge_bound`] is
//! `None` there (the seed states ii) for dimension 2 only; its "planar in dimensions m = 2, 3" of i)
//! can only mean that no two edges cross, which straight segments in 3D generically never do).

use core::fmt;

use flock_graph::{NeighbourSearch, ProximityNet};
use flock_math::parallel::{map_chunks, threads};
use flock_math::{Domain, Vector};

/// The pair tests each count of [`LatticeSummary::measure`] may take whatever the net's size: the
/// triangles of 10,000 boids of mean degree 452 (10⁹ tests) take ≈ 0.7 s on one core of a 2026
/// machine, the crossings about a second.
pub const WORK_BUDGET: usize = 1 << 30;

/// The pair tests per edge each count may take: a triangular lattice's crossings take ≈ 31 (its
/// edges' midpoints in cells of side d, times those of their own and the eight adjacent cells),
/// its triangles ≈ 6.
pub const WORK_PER_EDGE: usize = 128;

/// The default tolerance of [`LatticeSummary::measure`]: an edge is "at d" when its length is within
/// ±10 % of d.
pub const EDGE_TOLERANCE: f64 = 0.1;

/// The lattice summary of a configuration: counts on its proximity net (see the [module](self)).
///
/// # Example
/// ```
/// use flock_graph::ProximityNet;
/// use flock_metrics::LatticeSummary;
/// use glam::DVec2;
///
/// // an equilateral triangle of side 7 and a fourth agent 7 from two of its corners
/// let h = 7.0 * 3f64.sqrt() / 2.0;
/// let q = [DVec2::ZERO, DVec2::new(7.0, 0.0), DVec2::new(3.5, h), DVec2::new(10.5, h)];
/// let net = ProximityNet::brute_force(&q, 8.4);
/// let lattice = LatticeSummary::measure(&q, &net, 7.0, 0.1);
/// assert_eq!((lattice.edges, lattice.near_edges), (5, 5));
/// assert_eq!((lattice.triangles, lattice.equilateral_triangles), (Some(2), Some(2)));
/// assert_eq!(lattice.edge_bound, Some(6)); // 3n − 6
/// assert_eq!(lattice.crossings, Some(0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LatticeSummary {
    /// The number of agents n.
    pub agents: usize,
    /// The undirected edges |E| of the net.
    pub edges: usize,
    /// The edges whose length ℓ satisfies |ℓ − d| ≤ tolerance · d.
    pub near_edges: usize,
    /// The triangles of the net: unordered triples of agents linked pairwise; `None` when the net
    /// is too dense to count them (see the [module](self)).
    pub triangles: Option<usize>,
    /// The triangles whose three edges are all within the tolerance of d; `None` with
    /// `triangles`.
    pub equilateral_triangles: Option<usize>,
    /// TAC 2006 Theorem 5 ii): an α-lattice of n ≥ 3 agents in 2D has at most 3n − 6 edges; `None`
    /// in 3D (no such bound, see the [module](self)) or for n < 3.
    pub edge_bound: Option<usize>,
    /// In 2D, the pairs of edges without a common agent whose segments cross (zero for an α-lattice,
    /// Theorem 5 i); `None` in 3D, and when the net is too dense to count them (see the
    /// [module](self)).
    pub crossings: Option<usize>,
}

impl LatticeSummary {
    /// The summary of positions `q` with their proximity net `net` (with or without stored
    /// distances; stored in any order with its numbering), desired distance `d` and relative
    /// `tolerance` (e.g. [`EDGE_TOLERANCE`]).
    ///
    /// Cost: O(Σ_i deg_i²) for the triangles, and in 2D a neighbour search on the edges'
    /// midpoints for the crossings (two crossing edges shorter than r have midpoints closer than
    /// r): time O(|E| k), k the midpoints within the longest edge of each (a few for a lattice,
    /// thousands for a net of 100 neighbours per agent), each count within its work budget (see
    /// the [module](self)); memory O(n + |E|).
    #[must_use]
    pub fn measure<V: Vector>(q: &[V], net: &ProximityNet, d: f64, tolerance: f64) -> Self {
        Self::measure_in(&Domain::Open, q, net, d, tolerance)
    }

    /// [`LatticeSummary::measure`] in `domain`: on a torus every edge is the segment from q_i to
    /// the image of q_j nearest it (the net's minimum image), its length the minimum-image
    /// distance, and two edges cross when they do with their midpoints at their nearest images;
    /// in open space, the bits of [`LatticeSummary::measure`].
    #[must_use]
    pub fn measure_in<V: Vector>(
        domain: &Domain<V>,
        q: &[V],
        net: &ProximityNet,
        d: f64,
        tolerance: f64,
    ) -> Self {
        let edges = net.graph().undirected_edge_count();
        let budget = WORK_BUDGET.max(WORK_PER_EDGE.saturating_mul(edges));
        Self::measure_within(domain, q, net, d, tolerance, budget)
    }

    /// [`LatticeSummary::measure_in`] with at most `budget` pair tests for each count.
    fn measure_within<V: Vector>(
        domain: &Domain<V>,
        q: &[V],
        net: &ProximityNet,
        d: f64,
        tolerance: f64,
        budget: usize,
    ) -> Self {
        let graph = net.graph();
        let n = graph.len();
        let near: Vec<bool> = net
            .edge_lengths_in(domain, q)
            .map(|length| (length - d).abs() <= tolerance * d)
            .collect();
        let near_directed = near.iter().filter(|&&x| x).count();
        let triangles = count_triangles(net, &near, budget);
        let planar = V::DIM == 2;
        Self {
            agents: n,
            edges: graph.undirected_edge_count(),
            near_edges: near_directed / 2,
            triangles: triangles.map(|(all, _)| all),
            equilateral_triangles: triangles.map(|(_, equilateral)| equilateral),
            edge_bound: (planar && n >= 3).then(|| 3 * n - 6),
            crossings: planar
                .then(|| count_crossings(domain, q, net, budget))
                .flatten(),
        }
    }

    /// The fraction of edges within the tolerance of d (0 without edges).
    #[must_use]
    pub fn near_fraction(&self) -> f64 {
        fraction(self.near_edges, self.edges)
    }

    /// The fraction of triangles that are equilateral within the tolerance (0 without triangles),
    /// `None` when they were not counted.
    #[must_use]
    pub fn equilateral_fraction(&self) -> Option<f64> {
        Some(fraction(self.equilateral_triangles?, self.triangles?))
    }

    /// The mean number of neighbours per agent, 2|E|/n (0 without agents).
    #[must_use]
    pub fn mean_degree(&self) -> f64 {
        fraction(2 * self.edges, self.agents)
    }

    /// Whether the crossings are missing because the net was too dense to count them, rather than
    /// because they are not defined (3D). In 2D they are always counted for n < 3 (none), and for
    /// n ≥ 3 the edge bound is given.
    #[must_use]
    pub fn crossings_too_dense(&self) -> bool {
        self.crossings.is_none() && self.edge_bound.is_some()
    }

    /// Why a count is missing: the net's density (`"mean degree 94.0: too dense to count"`).
    #[must_use]
    pub fn too_dense(&self) -> String {
        format!("mean degree {:.1}: too dense to count", self.mean_degree())
    }

    /// Whether |E| ≤ 3n − 6 (Theorem 5 ii), when the bound applies.
    #[must_use]
    pub fn within_edge_bound(&self) -> Option<bool> {
        self.edge_bound.map(|bound| self.edges <= bound)
    }
}

impl fmt::Display for LatticeSummary {
    /// One line: `259 edges (95.4 % near d, bound 3n − 6 = 294), 157 triangles (141 equilateral),
    /// 0 crossings`; a count left out for a net too dense is named with its reason, `899075
    /// edges (0.2 % near d, bound 3n − 6 = 59994), 16142014 triangles (10 equilateral), crossings
    /// not counted (mean degree 89.9: too dense to count)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} edges ({:.1} % near d",
            self.edges,
            100.0 * self.near_fraction()
        )?;
        if let Some(bound) = self.edge_bound {
            write!(f, ", bound 3n − 6 = {bound}")?;
        }
        write!(f, ")")?;
        if let (Some(all), Some(equilateral)) = (self.triangles, self.equilateral_triangles) {
            write!(f, ", {all} triangles ({equilateral} equilateral)")?;
        }
        if let Some(crossings) = self.crossings {
            write!(f, ", {crossings} crossings")?;
        }
        let missing = match (self.triangles.is_none(), self.crossings_too_dense()) {
            (true, true) => "triangles and crossings",
            (true, false) => "triangles",
            (false, true) => "crossings",
            (false, false) => return Ok(()),
        };
        write!(f, ", {missing} not counted ({})", self.too_dense())
    }
}

fn fraction(part: usize, whole: usize) -> f64 {
    if whole == 0 {
        0.0
    } else {
        part as f64 / whole as f64
    }
}

/// Chunks per thread of [`count_triangles`]: each holds a mark per agent, so there are few.
const TRIANGLE_CHUNKS_PER_THREAD: usize = 4;

/// (triangles, equilateral triangles): each triple i < j < k (original indices) linked pairwise
/// is found once, from i through j; `near` flags the directed edges within the tolerance. `None`
/// when that search would test more than `budget` pairs (i, j, k): Σ over the edges i → j, j > i,
/// of deg j (in original indices, so that the decision does not depend on the storage order).
///
/// Every list ascends in original index, so the neighbours above an agent are the end of its
/// list, and only those are read. Chunks of agents are counted in parallel, each with its own
/// marks (a byte per agent): the sums of integers are the same for any thread count.
fn count_triangles(net: &ProximityNet, near: &[bool], budget: usize) -> Option<(usize, usize)> {
    let graph = net.graph();
    let neighbours = graph.neighbour_indices();
    let numbering = net.numbering();
    let n = graph.len();
    // the edges i → j of agent i with j > i in original index
    let above = |i: usize| {
        let edges = graph.edge_range(i);
        let own = numbering.original(i);
        let below =
            neighbours[edges.clone()].partition_point(|&j| numbering.original(j as usize) < own);
        edges.start + below..edges.end
    };
    let tests = (0..n)
        .flat_map(|i| above(i).map(|e| neighbours[e] as usize))
        .fold(0_usize, |tests, j| tests.saturating_add(graph.degree(j)));
    if tests > budget {
        return None;
    }
    let chunk = n.div_ceil(TRIANGLE_CHUNKS_PER_THREAD * threads()).max(1);
    let counts = map_chunks(n, chunk, |agents| {
        // mark[k] while i's neighbours are marked: 1 for a neighbour k, 3 when i → k is near d
        // (no branch on whether a pair closes a triangle, which the processor cannot predict)
        let mut mark = vec![0_u8; n];
        let (mut triangles, mut equilateral) = (0, 0);
        for i in agents {
            let range = graph.edge_range(i);
            for e in range.clone() {
                mark[neighbours[e] as usize] = 1 | u8::from(near[e]) << 1;
            }
            for e_ij in above(i) {
                let near_ij = u8::from(near[e_ij]) << 1;
                for e_jk in above(neighbours[e_ij] as usize) {
                    let m = mark[neighbours[e_jk] as usize];
                    triangles += usize::from(m & 1);
                    equilateral += usize::from(m & near_ij & (u8::from(near[e_jk]) << 1) != 0);
                }
            }
            for e in range {
                mark[neighbours[e] as usize] = 0;
            }
        }
        (triangles, equilateral)
    });
    Some(
        counts
            .into_iter()
            .fold((0, 0), |(t, e), (ti, ei)| (t + ti, e + ei)),
    )
}

/// The pairs of edges without a common endpoint whose segments properly cross, in the plane of the
/// first two coordinates. Candidates come from a neighbour search on the edges' midpoints: a
/// crossing point is within half an edge of both midpoints, so crossing edges have midpoints closer
/// than the longest edge. `None` when the search's candidate pairs exceed `budget`
/// ([`NeighbourSearch::count_pairs_in`]).
fn count_crossings<V: Vector>(
    domain: &Domain<V>,
    q: &[V],
    net: &ProximityNet,
    budget: usize,
) -> Option<usize> {
    let graph = net.graph();
    // each edge (i, j), i < j, as the segment from q_i to q_j's image nearest it; kept as its two
    // indices (8 bytes an edge, its ends found again when it is tested) beside its midpoint
    let segment = |i: usize, j: usize| (q[i], domain.image_near(q[i], q[j]));
    let mut ends = Vec::with_capacity(graph.undirected_edge_count());
    let mut midpoints = Vec::with_capacity(graph.undirected_edge_count());
    let mut longest: f64 = 0.0;
    for i in 0..graph.len() {
        for &j in graph.neighbours(i) {
            if j as usize > i {
                let (a, b) = segment(i, j as usize);
                ends.push((i as u32, j));
                midpoints.push(domain.wrap((a + b) * 0.5));
                longest = longest.max((b - a).length());
            }
        }
    }
    if ends.len() < 2 || longest == 0.0 {
        return Some(0);
    }
    // the candidate pairs are counted as they are found: a net of them would hold every
    // midpoint's list, E × thousands of entries for a dense net (r_c = 100 m of Vásárhelyi's drones)
    let search_range = longest * (1.0 + 1e-9);
    NeighbourSearch::new().count_pairs_in(domain, &midpoints, search_range, budget, |e, f| {
        let ((i, j), (k, l)) = (ends[e], ends[f]);
        if i == k || i == l || j == k || j == l {
            return false;
        }
        let ((qi, qj), (qk, ql)) = (
            segment(i as usize, j as usize),
            segment(k as usize, l as usize),
        );
        // segment f moved to the image of its midpoint nearest segment e's
        let shift = domain.image_near(midpoints[e], midpoints[f]) - midpoints[f];
        cross(qi, qj, qk + shift, ql + shift)
    })
}

/// Whether the segments [a, b] and [c, d] of the plane cross at a point interior to both (strict
/// orientation tests: touching or collinear segments do not count).
fn cross<V: Vector>(a: V, b: V, c: V, d: V) -> bool {
    let orient = |p: V, q: V, r: V| {
        (q.coord(0) - p.coord(0)) * (r.coord(1) - p.coord(1))
            - (q.coord(1) - p.coord(1)) * (r.coord(0) - p.coord(0))
    };
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    o1 * o2 < 0.0 && o3 * o4 < 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    /// R rows of C points, odd rows shifted by d/2: a triangular α-lattice patch for r < √3 d.
    fn triangular_lattice<V: Vector>(rows: usize, cols: usize, d: f64) -> Vec<V> {
        let mut points = Vec::new();
        for r in 0..rows {
            for c in 0..cols {
                let x = d * (c as f64 + 0.5 * (r % 2) as f64);
                let y = d * r as f64 * 3f64.sqrt() / 2.0;
                points.push(V::from_fn(|k| [x, y, 0.0][k]));
            }
        }
        points
    }

    /// On a torus the summary is of the minimum image: a lattice patch, and a unit square with
    /// its crossing diagonals, moved across the corner of a periodic box and wrapped, count what
    /// they count in open space; measured as if open (the old summary) the wrapped patch loses
    /// its edges across the wrap.
    #[test]
    fn a_lattice_across_the_wrap_keeps_its_counts() {
        let domain = Domain::Periodic {
            size: DVec2::new(40.0, 30.0),
        };
        let wrapped = |q: &[DVec2]| -> Vec<DVec2> {
            q.iter()
                .map(|&p| domain.wrap(p + DVec2::new(-9.0, -7.5)))
                .collect()
        };
        let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        let patch: Vec<DVec2> = triangular_lattice(4, 4, 7.0);
        for (q, r, d) in [(&patch[..], 8.4, 7.0), (&square[..], 1.5, 1.0)] {
            let open = LatticeSummary::measure(q, &ProximityNet::brute_force(q, r), d, 0.1);
            let moved = wrapped(q);
            let net = ProximityNet::brute_force_in(&domain, &moved, r);
            let torus = LatticeSummary::measure_in(&domain, &moved, &net, d, 0.1);
            assert_eq!(torus, open);
            if q.len() == 4 {
                assert_eq!((open.edges, open.crossings), (6, Some(1)));
            } else {
                let as_if_open =
                    LatticeSummary::measure(&moved, &ProximityNet::brute_force(&moved, r), d, 0.1);
                assert!(as_if_open.edges < open.edges);
            }
        }
    }

    /// R rows of C: R(C − 1) edges along the rows and 2C − 1 between consecutive rows; 2C − 2
    /// triangles between consecutive rows; all at d, all equilateral, no crossing.
    fn exact_lattice<V: Vector>() {
        let (rows, cols, d) = (5, 6, 7.0);
        let q: Vec<V> = triangular_lattice(rows, cols, d);
        let net = ProximityNet::brute_force(&q, 1.2 * d);
        let s = LatticeSummary::measure(&q, &net, d, EDGE_TOLERANCE);
        let edges = rows * (cols - 1) + (rows - 1) * (2 * cols - 1);
        let triangles = (rows - 1) * (2 * cols - 2);
        assert_eq!(s.agents, 30);
        assert_eq!((s.edges, s.near_edges), (edges, edges));
        assert_eq!(
            (s.triangles, s.equilateral_triangles),
            (Some(triangles), Some(triangles))
        );
        assert_eq!(s.near_fraction(), 1.0);
        assert_eq!(s.equilateral_fraction(), Some(1.0));
        if V::DIM == 2 {
            assert_eq!(s.edge_bound, Some(84));
            assert_eq!(s.within_edge_bound(), Some(true));
            assert_eq!(s.crossings, Some(0));
        } else {
            assert_eq!((s.edge_bound, s.crossings), (None, None));
        }
    }

    #[test]
    fn exact_triangular_lattice_2d() {
        exact_lattice::<DVec2>();
    }

    #[test]
    fn exact_triangular_lattice_3d() {
        exact_lattice::<DVec3>();
    }

    #[test]
    fn stretched_agent_leaves_the_tolerance() {
        let d = 7.0;
        let mut q: Vec<DVec2> = triangular_lattice(5, 6, d);
        let exact = LatticeSummary::measure(&q, &ProximityNet::brute_force(&q, 1.2 * d), d, 0.1);
        // agent 14 (row 2, column 2) has six neighbours; moving it by 0.9 along x takes its two
        // edges along x to 6.1 and 7.9 (outside 7 ± 0.7) and the four others to 6.60 and 7.49
        q[14].x += 0.9;
        let s = LatticeSummary::measure(&q, &ProximityNet::brute_force(&q, 1.2 * d), d, 0.1);
        assert_eq!(s.edges, exact.edges);
        assert_eq!(s.triangles, exact.triangles);
        assert_eq!(s.near_edges, exact.edges - 2);
        // of the six triangles around agent 14, the four with an edge along x are no longer
        // equilateral
        assert_eq!(s.equilateral_triangles, exact.triangles.map(|t| t - 4));
        assert!(s.near_fraction() < 1.0);
    }

    #[test]
    fn square_with_diagonals_has_one_crossing() {
        // K4 drawn as a unit square with its diagonals (r > √2): planar as a graph (6 = 3n − 6
        // edges) but its straight-line drawing crosses once, and it has four triangles
        let q = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        let s = LatticeSummary::measure(&q, &ProximityNet::brute_force(&q, 1.5), 1.0, 0.1);
        assert_eq!((s.edges, s.near_edges), (6, 4));
        assert_eq!((s.triangles, s.equilateral_triangles), (Some(4), Some(0)));
        assert_eq!(s.crossings, Some(1));
        assert_eq!(s.within_edge_bound(), Some(true));
    }

    /// Theorem 5 ii) is a 2D statement: the face-centred cubic α-lattice (spacing d, r = 1.2 d,
    /// twelve neighbours at d, the next at √2 d) has more than 3n − 6 edges.
    #[test]
    fn fcc_alpha_lattice_exceeds_three_n_minus_six() {
        let (a, m) = (7.0 * 2f64.sqrt(), 4);
        let mut q = Vec::new();
        for x in 0..m {
            for y in 0..m {
                for z in 0..m {
                    let corner = DVec3::new(f64::from(x), f64::from(y), f64::from(z)) * a;
                    for offset in [
                        DVec3::ZERO,
                        DVec3::new(0.5, 0.5, 0.0),
                        DVec3::new(0.5, 0.0, 0.5),
                        DVec3::new(0.0, 0.5, 0.5),
                    ] {
                        q.push(corner + offset * a);
                    }
                }
            }
        }
        let net = ProximityNet::brute_force(&q, 1.2 * 7.0);
        let s = LatticeSummary::measure(&q, &net, 7.0, 0.01);
        assert_eq!(s.near_edges, s.edges, "an α-lattice: every edge at d");
        assert!(
            s.edges > 3 * q.len() - 6,
            "{} edges, n = {}",
            s.edges,
            q.len()
        );
        assert_eq!(s.edge_bound, None);
    }

    /// A lattice's counts take fewer than [`WORK_PER_EDGE`] tests per edge, so the budget never
    /// leaves them out, whatever the lattice's size: 10,000 agents measured with the per-edge
    /// budget alone (no floor) keep both counts.
    #[test]
    fn a_lattice_is_counted_within_the_budget_per_edge() {
        let q: Vec<DVec2> = triangular_lattice(100, 100, 7.0);
        let net = ProximityNet::brute_force(&q, 8.4);
        let edges = net.graph().undirected_edge_count();
        let s = LatticeSummary::measure_within(
            &Domain::Open,
            &q,
            &net,
            7.0,
            0.1,
            WORK_PER_EDGE * edges,
        );
        assert_eq!(s.crossings, Some(0));
        assert_eq!(s.triangles, Some(2 * 99 * 99));
    }

    /// The triangles and equilateral triangles of irregular nets against every triple, in 2D and
    /// 3D, from agents stored in original order and stored in another order with their numbering;
    /// the budget's decision is the same for both (it is counted on original indices).
    fn triangles_match_every_triple<V: Vector>() {
        let n = 150;
        let q: Vec<V> = (0..n)
            .map(|k| {
                let t = k as f64 + 0.5;
                V::from_fn(|axis| {
                    (t * [0.754_877_7, 0.569_840_3, 0.438_897_3][axis]).fract() * 10.0
                })
            })
            .collect();
        let (r, d, tolerance) = (2.5, 2.0, 0.3);
        let net = ProximityNet::brute_force(&q, r);
        let close = |i: usize, j: usize| (q[i] - q[j]).length_squared() < r * r;
        let near = |i: usize, j: usize| ((q[i] - q[j]).length() - d).abs() <= tolerance * d;
        let (mut triangles, mut equilateral) = (0, 0);
        for i in 0..n {
            for j in i + 1..n {
                for k in j + 1..n {
                    if close(i, j) && close(j, k) && close(i, k) {
                        triangles += 1;
                        equilateral += usize::from(near(i, j) && near(j, k) && near(i, k));
                    }
                }
            }
        }
        assert!(
            triangles > 100 && equilateral > 0,
            "{triangles} {equilateral}"
        );
        // the work of the count: Σ over the edges i → j, j > i, of deg j
        let graph = net.graph();
        let tests: usize = (0..n)
            .flat_map(|i| graph.neighbours(i).iter().filter(move |&&j| j as usize > i))
            .map(|&j| graph.degree(j as usize))
            .sum();
        // stored in the order s ↦ 67 s mod n (67 and 150 coprime), with that numbering
        let order: Vec<u32> = (0..n as u32).map(|s| s * 67 % n as u32).collect();
        let stored: Vec<V> = order.iter().map(|&k| q[k as usize]).collect();
        let mut numbered = ProximityNet::new();
        numbered.permute(&order);
        NeighbourSearch::new().build(&stored, r, &mut numbered);
        assert!(!numbered.numbering().is_identity());
        for (positions, net) in [(&q[..], &net), (&stored[..], &numbered)] {
            let measure = |budget| {
                LatticeSummary::measure_within(&Domain::Open, positions, net, d, tolerance, budget)
            };
            let counted = measure(tests);
            assert_eq!(counted.triangles, Some(triangles));
            assert_eq!(counted.equilateral_triangles, Some(equilateral));
            assert_eq!(measure(tests - 1).triangles, None);
        }
    }

    #[test]
    fn triangles_match_every_triple_2d() {
        triangles_match_every_triple::<DVec2>();
    }

    #[test]
    fn triangles_match_every_triple_3d() {
        triangles_match_every_triple::<DVec3>();
    }

    /// The complete net of 30 agents: its triangle search tests Σ_{i<j} deg j = 29 · 435 = 12,615
    /// triples (C(30, 3) = 4,060 triangles); a budget of exactly that counts them, one less does
    /// not, and the summary says why. Its crossings need every midpoint with every other, far more
    /// than 12,615.
    #[test]
    fn a_net_too_dense_for_the_budget_leaves_its_counts_out() {
        let q: Vec<DVec2> = (0..30)
            .map(|k| {
                let t = f64::from(k) * 2.399_963;
                DVec2::new(t.cos(), t.sin()) * (1.0 + f64::from(k) / 30.0)
            })
            .collect();
        let net = ProximityNet::brute_force(&q, 10.0);
        assert_eq!(net.graph().undirected_edge_count(), 435);
        let measure =
            |budget| LatticeSummary::measure_within(&Domain::Open, &q, &net, 100.0, 0.1, budget);
        let all = measure(usize::MAX);
        assert_eq!(all.triangles, Some(4060));
        assert!(all.crossings > Some(0), "{all}");
        let at = measure(12_615);
        assert_eq!(at.triangles, Some(4060));
        assert_eq!(at.crossings, None);
        assert!(at.crossings_too_dense());
        let below = measure(12_614);
        assert_eq!((below.triangles, below.equilateral_triangles), (None, None));
        assert_eq!(below.equilateral_fraction(), None);
        assert_eq!(
            below.to_string(),
            "435 edges (0.0 % near d, bound 3n − 6 = 84), triangles and crossings not counted \
             (mean degree 29.0: too dense to count)"
        );
        assert_eq!(
            at.to_string(),
            "435 edges (0.0 % near d, bound 3n − 6 = 84), 4060 triangles (0 equilateral), \
             crossings not counted (mean degree 29.0: too dense to count)"
        );
        // in 3D the crossings are not defined, not missing
        let flat: Vec<DVec3> = q.iter().map(|p| p.extend(0.0)).collect();
        let s = LatticeSummary::measure_within(&Domain::Open, &flat, &net, 100.0, 0.1, 0);
        assert!(!s.crossings_too_dense());
        assert!(
            s.to_string()
                .ends_with("), triangles not counted (mean degree 29.0: too dense to count)")
        );
    }

    #[test]
    fn display_is_one_line() {
        let q: Vec<DVec2> = triangular_lattice(2, 2, 1.0);
        let s = LatticeSummary::measure(&q, &ProximityNet::brute_force(&q, 1.2), 1.0, 0.1);
        assert_eq!(
            s.to_string(),
            "5 edges (100.0 % near d, bound 3n − 6 = 6), 2 triangles (2 equilateral), \
             0 crossings"
        );
    }
}
