//! The flocking metrics of TAC 2006, Section VIII.

use flock_graph::parallel::{join, map_chunks};
use flock_graph::{Components, Numbering, ProximityNet, nearest_pair_distance};
use flock_math::{Vector, mean_of};

/// What the metrics compare against.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetricParams {
    /// The lattice scale d of the deviation energy.
    pub d: f64,
    /// Two agents closer than this collide; must be below the net's range so that every colliding
    /// pair is an edge of the net.
    pub collision_distance: f64,
}

/// Agents per parallel chunk of the shortest edge and the close pairs.
const EDGE_CHUNK: usize = 4096;

/// One evaluation of every metric.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlockMetrics {
    /// Relative connectivity C = rank(L)/(n − 1) ∈ [0, 1].
    pub connectivity: f64,
    /// C* = |giant component| / n.
    pub giant_component: f64,
    /// The number of connected components (flocks) of the net.
    pub components: usize,
    /// Cohesion radius R = max_i ‖q_i − q_c‖.
    pub cohesion_radius: f64,
    /// Normalised deviation energy Ẽ = E / d².
    pub deviation_energy: f64,
    /// Normalised velocity mismatch K̃ = K / n.
    pub velocity_mismatch: f64,
    /// The smallest distance between two agents (∞ for fewer than two agents).
    pub min_distance: f64,
    /// The number of pairs closer than the collision distance.
    pub collisions: usize,
}

impl FlockMetrics {
    /// The metrics of a flock without agents (every agent removed by faults): undefined, NaN
    /// (C, C*, R, Ẽ, K̃), with no component, no pair (min distance ∞) and no collision. Issue 27:
    /// such a flock was reported "C = 1 (0 components)" and judged strictly α-flocking.
    pub const EMPTY: Self = Self {
        connectivity: f64::NAN,
        giant_component: f64::NAN,
        components: 0,
        cohesion_radius: f64::NAN,
        deviation_energy: f64::NAN,
        velocity_mismatch: f64::NAN,
        min_distance: f64::INFINITY,
        collisions: 0,
    };

    /// Whether these are the metrics of a flock without agents ([`FlockMetrics::EMPTY`]).
    #[must_use]
    pub fn is_empty_flock(&self) -> bool {
        self.components == 0 && self.connectivity.is_nan()
    }

    /// Every metric of the state (q, p) with its net; [`FlockMetrics::EMPTY`] without agents.
    ///
    /// `net` is the net of `q`, with or without stored distances
    /// ([`ProximityNet::without_distances`]): the edge lengths are the same bits either way. The
    /// states may be stored in any order with the net's [`Numbering`]: every sum runs in original
    /// order, so the metrics have the bits of the agents in original order. With the `parallel`
    /// feature the components (union-find) are found while another thread measures the edges,
    /// the cohesion radius and the velocity mismatch; each is computed as without it.
    ///
    /// A net built by [`NeighbourSearch`](flock_graph::NeighbourSearch) from `q` has the identity
    /// numbering: `q` and `p` are then simply in the order of the agents. A simulation that
    /// stores its agents otherwise measures them itself (`flock_protocols::Simulation::metrics`),
    /// so that a state and a net of different orders never meet.
    ///
    /// # Example
    /// ```
    /// use flock_graph::{NeighbourSearch, ProximityNet};
    /// use flock_metrics::{FlockMetrics, MetricParams};
    /// use glam::DVec2;
    ///
    /// // three agents at the lattice distance d = 7 on a line, moving together
    /// let q = [DVec2::ZERO, DVec2::new(7.0, 0.0), DVec2::new(14.0, 0.0)];
    /// let p = [DVec2::X; 3];
    /// let mut net = ProximityNet::new();
    /// NeighbourSearch::new().build(&q, 8.4, &mut net);
    /// let params = MetricParams { d: 7.0, collision_distance: 1.75 };
    /// let m = FlockMetrics::measure(&q, &p, &net, &params);
    /// assert_eq!((m.connectivity, m.components), (1.0, 1));
    /// assert_eq!((m.deviation_energy, m.velocity_mismatch), (0.0, 0.0));
    /// assert_eq!((m.cohesion_radius, m.min_distance, m.collisions), (7.0, 7.0, 0));
    /// ```
    #[must_use]
    pub fn measure<V: Vector>(q: &[V], p: &[V], net: &ProximityNet, params: &MetricParams) -> Self {
        if q.is_empty() {
            return Self::EMPTY;
        }
        let components = || Components::of(net.graph());
        let numbering = net.numbering();
        let rest = || {
            (
                EdgeMetrics::of(q, net, params),
                radius_about(q, mean_of(numbering.ordered(q))),
                mismatch(numbering.ordered(p)),
            )
        };
        let (components, (edges, cohesion_radius, velocity_mismatch)) = join(components, rest);
        Self {
            connectivity: relative_connectivity(&components),
            giant_component: components.giant_share(),
            components: components.count(),
            cohesion_radius,
            deviation_energy: edges.deviation_energy,
            velocity_mismatch,
            min_distance: edges.min_distance(q),
            collisions: edges.collisions,
        }
    }
}

impl FlockMetrics {
    /// The metrics with C, C* and the number of components of another graph on the same agents
    /// (a protocol's fixed interaction graph, Tanner et al. 2003), the others unchanged.
    #[must_use]
    pub fn with_connectivity_of(self, components: &Components) -> Self {
        Self {
            connectivity: relative_connectivity(components),
            giant_component: components.giant_share(),
            components: components.count(),
            ..self
        }
    }

    /// The names of [`FlockMetrics::reals`], in its order: the columns of `metrics.csv` between
    /// `t` and `collisions`.
    pub const REAL_COLUMNS: [&'static str; 6] = [
        "connectivity",
        "giant_component",
        "cohesion_radius",
        "deviation_energy",
        "velocity_mismatch",
        "min_distance",
    ];

    /// The real-valued metrics in the order of the columns of `metrics.csv`
    /// ([`FlockMetrics::REAL_COLUMNS`]): C, C*, R, Ẽ, K̃ and the minimum distance.
    #[must_use]
    pub fn reals(&self) -> [f64; 6] {
        [
            self.connectivity,
            self.giant_component,
            self.cohesion_radius,
            self.deviation_energy,
            self.velocity_mismatch,
            self.min_distance,
        ]
    }

    /// The metrics of [`FlockMetrics::reals`] `reals` (read back from `metrics.csv`, say), with
    /// the counts that are not among them.
    #[must_use]
    pub const fn from_reals(reals: [f64; 6], components: usize, collisions: usize) -> Self {
        let [
            connectivity,
            giant_component,
            cohesion_radius,
            deviation_energy,
            velocity_mismatch,
            min_distance,
        ] = reals;
        Self {
            connectivity,
            giant_component,
            components,
            cohesion_radius,
            deviation_energy,
            velocity_mismatch,
            min_distance,
            collisions,
        }
    }
}

/// The metrics of the edge lengths, from one pass over them: Ẽ, the shortest edge and the
/// colliding pairs (behind [`FlockMetrics::measure`], [`deviation_energy`] and [`collisions`]).
struct EdgeMetrics {
    deviation_energy: f64,
    /// The shortest edge, ∞ without edges.
    shortest: f64,
    collisions: usize,
}

impl EdgeMetrics {
    /// One pass over the edges in storage order for the squared errors of each agent, added in
    /// original order ([`Numbering::ordered_sum`]), and one, in chunks, for the shortest edge and
    /// the close pairs (which do not depend on the order).
    fn of<V: Vector>(q: &[V], net: &ProximityNet, params: &MetricParams) -> Self {
        debug_assert!(
            params.collision_distance <= net.range(),
            "collision distance beyond the net's range"
        );
        let (d, n) = (params.d, net.graph().len());
        let sum = net.numbering().ordered_sum(n, |i| {
            net.lengths_of(i, q)
                .fold(0.0, |sum, l| sum + (l - d) * (l - d))
        });
        let (shortest, close) = map_chunks(n, EDGE_CHUNK, |agents| {
            agents.flat_map(|i| net.lengths_of(i, q)).fold(
                (f64::INFINITY, 0),
                |(shortest, close), l| {
                    let colliding = usize::from(l < params.collision_distance);
                    (shortest.min(l), close + colliding)
                },
            )
        })
        .into_iter()
        .fold((f64::INFINITY, 0), |(s, c), (chunk_s, chunk_c)| {
            (s.min(chunk_s), c + chunk_c)
        });
        let edges = net.graph().directed_edge_count();
        Self {
            deviation_energy: sum / (edges as f64 + 1.0) / (d * d),
            shortest,
            collisions: close / 2,
        }
    }

    /// [`min_distance`].
    fn min_distance<V: Vector>(&self, q: &[V]) -> f64 {
        if self.shortest.is_finite() {
            self.shortest
        } else {
            nearest_pair_distance(q).unwrap_or(f64::INFINITY)
        }
    }
}

/// C(t) = rank(L(q)) / (n − 1) = (n − #components) / (n − 1) for an undirected net (TAC 2006
/// eq. 80): rank(L) = n − #components, so no dense rank is needed. 1 for a single agent.
#[must_use]
pub fn relative_connectivity(components: &Components) -> f64 {
    let n = components.labels().len();
    if n <= 1 {
        return 1.0;
    }
    (n - components.count()) as f64 / (n - 1) as f64
}

/// R(t) = max_i ‖q_i − q_c‖ (TAC 2006 eq. 81).
#[must_use]
pub fn cohesion_radius<V: Vector>(q: &[V]) -> f64 {
    radius_about(q, mean_of(q.iter().copied()))
}

/// max_i ‖q_i − centre‖ (0 for no agent).
fn radius_about<V: Vector>(q: &[V], centre: V) -> f64 {
    q.iter()
        .map(|&qi| (qi - centre).length())
        .fold(0.0, f64::max)
}

/// Ẽ = E(q) / d² with E(q) = (1/(|E| + 1)) Σ_i Σ_{j∈N_i} (‖q_j − q_i‖ − d)² (TAC 2006 eq. 7 and 82),
/// where E is the set of ordered pairs (i, j), j ∈ N_i, so |E| = Σ_i |N_i| and E is close to the mean
/// squared edge-length error.
///
/// `net` is the net of `q`, with or without stored distances.
#[must_use]
pub fn deviation_energy<V: Vector>(q: &[V], net: &ProximityNet, d: f64) -> f64 {
    EdgeMetrics::of(
        q,
        net,
        &MetricParams {
            d,
            collision_distance: 0.0,
        },
    )
    .deviation_energy
}

/// K̃ = K / n with K = ½ Σ ‖p_i − p_c‖² (TAC 2006 eq. 83); 0 for no agent.
#[must_use]
pub fn velocity_mismatch<V: Vector>(p: &[V]) -> f64 {
    mismatch(p.iter().copied())
}

/// K̃ of the velocities, summed in the iterator's order.
fn mismatch<V: Vector>(p: impl ExactSizeIterator<Item = V> + Clone) -> f64 {
    let n = p.len();
    if n == 0 {
        return 0.0;
    }
    let p_c = mean_of(p.clone());
    0.5 * p.map(|pi| (pi - p_c).length_squared()).sum::<f64>() / n as f64
}

/// The velocity mismatch with each agent compared to the mean velocity of its own component:
/// (1/n) Σ_k ½ Σ_{i∈F_k} ‖p_i − p_c^k‖². It vanishes when every flock moves rigidly (translation),
/// the outcome of regular fragmentation under Algorithm 1 (TAC 2006 Fig. 12).
///
/// `components` are those of the net of the agents, stored as `numbering` says (the net's
/// [`ProximityNet::numbering`]); the sums run in original order.
#[must_use]
pub fn component_velocity_mismatch<V: Vector>(
    p: &[V],
    components: &Components,
    numbering: &Numbering,
) -> f64 {
    if p.is_empty() {
        return 0.0;
    }
    let labels = components.labels();
    let mut sums = vec![V::ZERO; components.count()];
    for i in numbering.stored_of(0..p.len()) {
        sums[labels[i] as usize] += p[i];
    }
    let means: Vec<V> = sums
        .iter()
        .zip(components.sizes())
        .map(|(&s, &size)| s / size as f64)
        .collect();
    let k: f64 = numbering
        .stored_of(0..p.len())
        .map(|i| (p[i] - means[labels[i] as usize]).length_squared())
        .sum();
    0.5 * k / p.len() as f64
}

/// The smallest distance between two agents: the shortest edge of the net when it has one (every
/// closer pair is an edge), otherwise an exact search; ∞ for fewer than two agents.
#[must_use]
pub fn min_distance<V: Vector>(q: &[V], net: &ProximityNet) -> f64 {
    let shortest = net.edge_lengths(q).fold(f64::INFINITY, f64::min);
    if shortest.is_finite() {
        shortest
    } else {
        nearest_pair_distance(q).unwrap_or(f64::INFINITY)
    }
}

/// The number of unordered pairs closer than `collision_distance`, which must not exceed the net's
/// range (every such pair is then an edge); `net` is the net of `q`, with or without stored
/// distances.
#[must_use]
pub fn collisions<V: Vector>(q: &[V], net: &ProximityNet, collision_distance: f64) -> usize {
    let params = MetricParams {
        d: 1.0,
        collision_distance,
    };
    EdgeMetrics::of(q, net, &params).collisions
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use flock_graph::Graph;
    use glam::{DVec2, DVec3};

    /// A triangular α-lattice patch in the plane (spacing d), lifted to V.
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

    fn lattice_metrics<V: Vector>() {
        let d = 7.0;
        let q: Vec<V> = triangular_lattice(5, 6, d);
        let p = vec![V::from_fn(|k| k as f64 + 1.0); q.len()];
        let net = ProximityNet::brute_force(&q, 1.2 * d);
        let m = FlockMetrics::measure(
            &q,
            &p,
            &net,
            &MetricParams {
                d,
                collision_distance: 0.5 * d,
            },
        );
        assert_eq!(m.connectivity, 1.0);
        assert_eq!(m.giant_component, 1.0);
        assert_eq!(m.components, 1);
        assert_relative_eq!(m.deviation_energy, 0.0, epsilon = 1e-28);
        assert_eq!(m.velocity_mismatch, 0.0);
        assert_relative_eq!(m.min_distance, d, epsilon = 1e-12);
        assert_eq!(m.collisions, 0);
    }

    #[test]
    fn alpha_lattice_is_a_perfect_flock_2d() {
        lattice_metrics::<DVec2>();
    }

    #[test]
    fn alpha_lattice_is_a_perfect_flock_3d() {
        lattice_metrics::<DVec3>();
    }

    #[test]
    fn connectivity_of_the_papers_examples() {
        // TAC slides: populations 1,1,1,1,96 → C = 95/99, C* = 0.96; 5 × 20 → C = 95/99, C* = 0.2
        let chain = |sizes: &[usize]| {
            let mut edges = Vec::new();
            let mut start = 0;
            for &s in sizes {
                edges.extend((start..start + s - 1).map(|i| (i, i + 1)));
                start += s;
            }
            Components::of(&Graph::from_edges(start, &edges).expect("valid edges"))
        };
        let skewed = chain(&[1, 1, 1, 1, 96]);
        assert_relative_eq!(relative_connectivity(&skewed), 95.0 / 99.0);
        assert_relative_eq!(skewed.giant_share(), 0.96);
        let even = chain(&[20; 5]);
        assert_relative_eq!(relative_connectivity(&even), 95.0 / 99.0);
        assert_relative_eq!(even.giant_share(), 0.2);
    }

    #[test]
    fn deviation_energy_of_a_stretched_pair() {
        // two agents 8 apart with d = 7: E = (1/(2 + 1)) · 2 · 1² = 2/3, Ẽ = 2/(3 · 49)
        let q = [DVec2::ZERO, DVec2::new(8.0, 0.0)];
        let net = ProximityNet::brute_force(&q, 8.4);
        assert_relative_eq!(
            deviation_energy(&q, &net, 7.0),
            2.0 / 147.0,
            epsilon = 1e-15
        );
        assert_eq!(collisions(&q, &net, 8.1), 1);
        assert_eq!(collisions(&q, &net, 8.0), 0);
    }

    #[test]
    fn velocity_mismatch_has_its_half() {
        // p = ±v: K = ½ (‖v‖² + ‖v‖²) = ‖v‖², K̃ = ‖v‖²/2
        let p = [DVec3::new(1.0, 2.0, 2.0), DVec3::new(-1.0, -2.0, -2.0)];
        assert_relative_eq!(velocity_mismatch(&p), 4.5);
    }

    #[test]
    fn rigid_components_have_no_component_mismatch() {
        let graph = Graph::from_edges(4, &[(0, 1), (2, 3)]).expect("valid edges");
        let components = Components::of(&graph);
        let p = [DVec2::X, DVec2::X, DVec2::Y, DVec2::Y];
        assert_eq!(
            component_velocity_mismatch(&p, &components, &Numbering::identity()),
            0.0
        );
        assert!(velocity_mismatch(&p) > 0.1);
    }

    #[test]
    fn cohesion_radius_and_min_distance_without_edges() {
        let q = [
            DVec2::new(-10.0, 0.0),
            DVec2::new(10.0, 0.0),
            DVec2::new(0.0, 30.0),
        ];
        let net = ProximityNet::brute_force(&q, 8.4);
        assert_relative_eq!(cohesion_radius(&q), 20.0);
        assert_relative_eq!(min_distance(&q, &net), 20.0);
        assert_eq!(
            min_distance::<DVec2>(&[], &ProximityNet::new()),
            f64::INFINITY
        );
    }

    #[test]
    fn measure_is_the_same_with_or_without_stored_distances() {
        let q: Vec<DVec2> = (0..300)
            .map(|k| {
                let t = f64::from(k);
                DVec2::new((t * 1.7).sin() * 30.0, (t * 0.37).cos() * 30.0 + 0.1 * t)
            })
            .collect();
        let p: Vec<DVec2> = q.iter().map(|&x| DVec2::new(x.y, -x.x) * 0.01).collect();
        let params = MetricParams {
            d: 7.0,
            collision_distance: 2.0,
        };
        let full = ProximityNet::brute_force(&q, 8.4);
        let mut lean = ProximityNet::without_distances();
        flock_graph::NeighbourSearch::new().build(&q, 8.4, &mut lean);
        let (a, b) = (
            FlockMetrics::measure(&q, &p, &full, &params),
            FlockMetrics::measure(&q, &p, &lean, &params),
        );
        let bits = |m: &FlockMetrics| {
            [
                m.deviation_energy.to_bits(),
                m.min_distance.to_bits(),
                m.collisions as u64,
            ]
        };
        assert_eq!(bits(&a), bits(&b));
        assert!(a.collisions > 0, "the test wants colliding pairs");
        assert_eq!(
            a.deviation_energy.to_bits(),
            deviation_energy(&q, &full, 7.0).to_bits()
        );
        assert_eq!(a.collisions, collisions(&q, &full, 2.0));
        assert_eq!(a.min_distance.to_bits(), min_distance(&q, &full).to_bits());
        assert_eq!(a.min_distance.to_bits(), min_distance(&q, &lean).to_bits());
    }

    /// The agents stored in another order, with the net's numbering, give every metric the bits
    /// of the agents in original order.
    #[test]
    fn measure_follows_the_numbering() {
        let q: Vec<DVec3> = (0..500)
            .map(|k| {
                let t = f64::from(k);
                DVec3::new((t * 1.7).sin() * 20.0, (t * 0.37).cos() * 20.0, 0.3 * t)
            })
            .collect();
        let p: Vec<DVec3> = q
            .iter()
            .map(|&x| DVec3::new(x.y, -x.x, 0.3) * 0.01)
            .collect();
        let params = MetricParams {
            d: 7.0,
            collision_distance: 2.0,
        };
        let mut search = flock_graph::NeighbourSearch::new();
        let mut net = ProximityNet::new();
        search.build(&q, 8.4, &mut net);
        let order = search.cell_order(&q, 8.4).to_vec();
        assert!(order.iter().enumerate().any(|(s, &k)| k as usize != s));
        let stored = |x: &[DVec3]| -> Vec<DVec3> { order.iter().map(|&k| x[k as usize]).collect() };
        let (q_s, p_s) = (stored(&q), stored(&p));
        let mut numbered = ProximityNet::without_distances();
        numbered.permute(&order);
        search.build(&q_s, 8.4, &mut numbered);
        let bits = |m: FlockMetrics| m.reals().map(f64::to_bits);
        let (original, renumbered) = (
            FlockMetrics::measure(&q, &p, &net, &params),
            FlockMetrics::measure(&q_s, &p_s, &numbered, &params),
        );
        assert_eq!(bits(original), bits(renumbered));
        assert_eq!(original.components, renumbered.components);
        assert_eq!(original.collisions, renumbered.collisions);
        assert!(
            original.components > 1 && original.collisions > 0,
            "{original:?}"
        );
        let mismatch = |p: &[DVec3], net: &ProximityNet| {
            component_velocity_mismatch(p, &Components::of(net.graph()), net.numbering()).to_bits()
        };
        assert_eq!(mismatch(&p, &net), mismatch(&p_s, &numbered));
        let back =
            FlockMetrics::from_reals(original.reals(), original.components, original.collisions);
        assert_eq!(back, original, "from_reals inverts reals");
    }

    #[test]
    fn edge_metrics_are_the_same_with_or_without_stored_distances() {
        let q = [DVec2::ZERO, DVec2::X, DVec2::new(0.5, 3.0)];
        let full = ProximityNet::brute_force(&q, 3.5);
        let mut lean = ProximityNet::without_distances();
        flock_graph::NeighbourSearch::new().build(&q, 3.5, &mut lean);
        assert_eq!(
            deviation_energy(&q, &lean, 1.0).to_bits(),
            deviation_energy(&q, &full, 1.0).to_bits()
        );
        assert_eq!(collisions(&q, &lean, 1.5), 1);
        assert_eq!(collisions(&q, &full, 1.5), 1);
    }
}
