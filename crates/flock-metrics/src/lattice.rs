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
//! In 3D neither statement holds: the face-centred cubic lattice of spacing d with r = 1.2 d is an
//! α-lattice with twelve neighbours per agent, |E| → 6n, so [`LatticeSummary::edge_bound`] is
//! `None` there (the seed states ii) for dimension 2 only; its "planar in dimensions m = 2, 3" of i)
//! can only mean that no two edges cross, which straight segments in 3D generically never do).

use core::fmt;

use flock_graph::{NeighbourSearch, ProximityNet};
use flock_math::{Domain, Vector};

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
/// assert_eq!((lattice.triangles, lattice.equilateral_triangles), (2, 2));
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
    /// The triangles of the net: unordered triples of agents linked pairwise.
    pub triangles: usize,
    /// The triangles whose three edges are all within the tolerance of d.
    pub equilateral_triangles: usize,
    /// TAC 2006 Theorem 5 ii): an α-lattice of n ≥ 3 agents in 2D has at most 3n − 6 edges; `None`
    /// in 3D (no such bound, see the [module](self)) or for n < 3.
    pub edge_bound: Option<usize>,
    /// In 2D, the pairs of edges without a common agent whose segments cross (zero for an α-lattice,
    /// Theorem 5 i); `None` in 3D.
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
    /// thousands for a net of 100 neighbours per agent), memory O(n + |E|) either way.
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
        let graph = net.graph();
        let n = graph.len();
        let near: Vec<bool> = net
            .edge_lengths_in(domain, q)
            .map(|length| (length - d).abs() <= tolerance * d)
            .collect();
        let near_directed = near.iter().filter(|&&x| x).count();
        let (triangles, equilateral_triangles) = count_triangles(net, &near);
        let planar = V::DIM == 2;
        Self {
            agents: n,
            edges: graph.undirected_edge_count(),
            near_edges: near_directed / 2,
            triangles,
            equilateral_triangles,
            edge_bound: (planar && n >= 3).then(|| 3 * n - 6),
            crossings: planar.then(|| count_crossings(domain, q, net)),
        }
    }

    /// The fraction of edges within the tolerance of d (0 without edges).
    #[must_use]
    pub fn near_fraction(&self) -> f64 {
        fraction(self.near_edges, self.edges)
    }

    /// The fraction of triangles that are equilateral within the tolerance (0 without triangles).
    #[must_use]
    pub fn equilateral_fraction(&self) -> f64 {
        fraction(self.equilateral_triangles, self.triangles)
    }

    /// Whether |E| ≤ 3n − 6 (Theorem 5 ii), when the bound applies.
    #[must_use]
    pub fn within_edge_bound(&self) -> Option<bool> {
        self.edge_bound.map(|bound| self.edges <= bound)
    }
}

impl fmt::Display for LatticeSummary {
    /// One line: `259 edges (95.4 % near d, bound 3n − 6 = 294), 157 triangles (141 equilateral),
    /// 0 crossings`.
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
        write!(
            f,
            "), {} triangles ({} equilateral)",
            self.triangles, self.equilateral_triangles
        )?;
        if let Some(crossings) = self.crossings {
            write!(f, ", {crossings} crossings")?;
        }
        Ok(())
    }
}

fn fraction(part: usize, whole: usize) -> f64 {
    if whole == 0 {
        0.0
    } else {
        part as f64 / whole as f64
    }
}

/// (triangles, equilateral triangles): each triple i < j < k (storage indices) linked pairwise is
/// found once, from i through j; `near` flags the directed edges within the tolerance.
fn count_triangles(net: &ProximityNet, near: &[bool]) -> (usize, usize) {
    let graph = net.graph();
    let neighbours = graph.neighbour_indices();
    // slot[k] = the directed edge i → k while i's neighbours are marked
    let mut slot = vec![usize::MAX; graph.len()];
    let (mut triangles, mut equilateral) = (0, 0);
    for i in 0..graph.len() {
        let range = graph.edge_range(i);
        for e in range.clone() {
            slot[neighbours[e] as usize] = e;
        }
        for e_ij in range.clone() {
            let j = neighbours[e_ij] as usize;
            if j <= i {
                continue;
            }
            for e_jk in graph.edge_range(j) {
                let k = neighbours[e_jk] as usize;
                let e_ik = slot[k];
                if k > j && e_ik != usize::MAX {
                    triangles += 1;
                    equilateral += usize::from(near[e_ij] && near[e_jk] && near[e_ik]);
                }
            }
        }
        for e in range {
            slot[neighbours[e] as usize] = usize::MAX;
        }
    }
    (triangles, equilateral)
}

/// The pairs of edges without a common endpoint whose segments properly cross, in the plane of the
/// first two coordinates. Candidates come from a neighbour search on the edges' midpoints: a
/// crossing point is within half an edge of both midpoints, so crossing edges have midpoints closer
/// than the longest edge.
fn count_crossings<V: Vector>(domain: &Domain<V>, q: &[V], net: &ProximityNet) -> usize {
    let graph = net.graph();
    // each edge (i, j), i < j, as the segment from q_i to q_j's image nearest it
    let mut ends = Vec::with_capacity(graph.undirected_edge_count());
    let mut longest: f64 = 0.0;
    for i in 0..graph.len() {
        for &j in graph.neighbours(i) {
            let j = j as usize;
            if j > i {
                let far = domain.image_near(q[i], q[j]);
                ends.push((i, j, q[i], far));
                longest = longest.max((far - q[i]).length());
            }
        }
    }
    if ends.len() < 2 || longest == 0.0 {
        return 0;
    }
    let midpoints: Vec<V> = ends
        .iter()
        .map(|&(_, _, a, b)| domain.wrap((a + b) * 0.5))
        .collect();
    // the candidate pairs are counted as they are found: a net of them would hold every
    // midpoint's list, E × thousands of entries for a dense net (r_c = 100 m of Vásárhelyi's drones)
    let search_range = longest * (1.0 + 1e-9);
    NeighbourSearch::new().count_pairs_in(domain, &midpoints, search_range, |a, b| {
        let ((i, j, qi, qj), (k, l, qk, ql)) = (ends[a], ends[b]);
        if i == k || i == l || j == k || j == l {
            return false;
        }
        // segment b moved to the image of its midpoint nearest segment a's
        let shift = domain.image_near(midpoints[a], midpoints[b]) - midpoints[b];
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
            (triangles, triangles)
        );
        assert_eq!(s.near_fraction(), 1.0);
        assert_eq!(s.equilateral_fraction(), 1.0);
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
        assert_eq!(s.equilateral_triangles, exact.triangles - 4);
        assert!(s.near_fraction() < 1.0);
    }

    #[test]
    fn square_with_diagonals_has_one_crossing() {
        // K4 drawn as a unit square with its diagonals (r > √2): planar as a graph (6 = 3n − 6
        // edges) but its straight-line drawing crosses once, and it has four triangles
        let q = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        let s = LatticeSummary::measure(&q, &ProximityNet::brute_force(&q, 1.5), 1.0, 0.1);
        assert_eq!((s.edges, s.near_edges), (6, 4));
        assert_eq!((s.triangles, s.equilateral_triangles), (4, 0));
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
