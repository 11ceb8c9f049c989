//! The flocking metrics of TAC 2006, Section VIII.

use flock_graph::{Components, NeighbourSearch, Numbering, ProximityNet};
use flock_math::parallel::join;
use flock_math::{Domain, Vector, mean_of};

use crate::heading::{milling_about, polarisation_of};

/// What the metrics compare against.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetricParams {
    /// The lattice scale d of the deviation energy.
    pub d: f64,
    /// Two agents closer than this collide; must be below the net's range so that every colliding
    /// pair is an edge of the net.
    pub collision_distance: f64,
}

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
    /// The polarisation (order parameter) Φ = ‖Σ_i p_i/‖p_i‖‖ / N ∈ [0, 1]: 1 when every agent
    /// heads the same way, about 1/√N for random headings. Vicsek et al., PRL 75 (1995), v_a (for
    /// agents of constant speed); Couzin et al., J. theor. Biol. 218 (2002), p_group. Agents at
    /// rest (p_i = 0, or not finite) are left out of the sum but counted in N; undefined (NaN, [`FlockMetrics::EMPTY`]) for no agent.
    pub polarisation: f64,
    /// The milling (angular momentum) parameter M = ‖Σ_i r̂_ic × p̂_i‖ / N ∈ [0, 1], r̂_ic the unit
    /// vector from the group centre q_c to agent i and p̂_i its heading: 1 for agents circling the
    /// centre all the same way (a mill, a torus), near 0 for a polarised group. Couzin et al.,
    /// J. theor. Biol. 218 (2002), m_group. In 3D the norm of the summed cross products, in 2D the
    /// absolute value of the summed scalar cross products r̂_x p̂_y − r̂_y p̂_x. On a torus q_c is
    /// the circular mean ([`Domain::centre_of`]) and r_ic the minimum image. Agents at rest or at
    /// the centre add nothing but count in N; undefined (NaN) for no agent.
    pub milling: f64,
    /// The mean over agents of the distance to the nearest other agent, (1/N) Σ_i min_{j≠i}
    /// ‖q_j − q_i‖ (minimum image on a torus), the mean nearest-neighbour distance of the
    /// collective-motion literature (e.g. Ballerini et al., PNAS 105 (2008), r₁). Exact: from the
    /// net when every agent has a neighbour in it, otherwise from a search over all agents
    /// ([`NeighbourSearch::nearest_distances_in`]). +∞ for fewer than two agents (as
    /// [`FlockMetrics::min_distance`]), or when an agent has a non-finite position.
    pub nearest_neighbour_mean: f64,
    /// The least over agents of the distance to the nearest other agent: the smallest distance
    /// between two agents, so equal to [`FlockMetrics::min_distance`] (computed from the same
    /// nearest-neighbour distances as [`FlockMetrics::nearest_neighbour_mean`]); +∞ for fewer than
    /// two agents.
    pub nearest_neighbour_min: f64,
    /// The group's speed ‖p_c‖, p_c = (1/N) Σ_i p_i: the speed of the centre of mass. With
    /// [`FlockMetrics::velocity_mismatch`] it gives the agents' root-mean-square speed,
    /// (1/N) Σ_i ‖p_i‖² = ‖p_c‖² + 2 K̃, the speed scale against which Definition 5's velocity
    /// mismatch is judged ([`FlockingVerdict`](crate::FlockingVerdict)). Undefined (NaN) for no
    /// agent.
    pub group_speed: f64,
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
        polarisation: f64::NAN,
        milling: f64::NAN,
        nearest_neighbour_mean: f64::NAN,
        nearest_neighbour_min: f64::INFINITY,
        group_speed: f64::NAN,
    };

    /// Whether these are the metrics of a flock without agents ([`FlockMetrics::EMPTY`]).
    #[must_use]
    pub fn is_empty_flock(&self) -> bool {
        self.components == 0 && self.connectivity.is_nan()
    }

    /// Whether these are the metrics of a single agent: some agent, and no pair (the least
    /// distance between two agents is +∞ for fewer than two, and finite otherwise).
    #[must_use]
    pub fn is_lone_agent(&self) -> bool {
        !self.is_empty_flock() && self.min_distance == f64::INFINITY
    }

    /// The agents' root-mean-square speed, √((1/N) Σ_i ‖p_i‖²) = √(‖p_c‖² + 2 K̃) (NaN when
    /// either is unknown).
    #[must_use]
    pub fn rms_speed(&self) -> f64 {
        self.group_speed
            .mul_add(self.group_speed, 2.0 * self.velocity_mismatch)
            .sqrt()
    }

    /// Every metric of the state (q, p) with its net; [`FlockMetrics::EMPTY`] without agents.
    ///
    /// `net` is the net of `q`, with or without stored distances
    /// ([`ProximityNet::without_distances`]): the edge lengths are the same bits either way. The
    /// states may be stored in any order with the net's [`Numbering`]: every sum runs in original
    /// order, so the metrics have the bits of the agents in original order. With the `parallel`
    /// feature the components (union-find) are found while another thread measures the cohesion
    /// radius, the velocity mismatch, the polarisation and the milling, and the edge lengths are
    /// then measured in one pass on every thread; each is computed as without it.
    ///
    /// A net built by [`NeighbourSearch`] from `q` has the identity
    /// numbering: `q` and `p` are then simply in the order of the agents. A simulation that
    /// stores its agents otherwise measures them itself (`flock_sim::Simulation::metrics`),
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
        Self::measure_in(&Domain::Open, q, p, net, params)
    }

    /// Every metric of the state (q, p) in `domain` with its net, built in that domain
    /// ([`NeighbourSearch::build_in`]). [`Domain::Open`] is [`FlockMetrics::measure`], bit for bit.
    ///
    /// On a torus every metric is measured as the agents see each other, by minimum image:
    /// - C, C* and the components are those of the net, whose edges are minimum-image pairs;
    /// - the centre q_c is the circular mean per axis ([`Domain::centre_of`], Bai & Breen 2008),
    ///   and R = max_i ‖displacement(q_c, q_i)‖ (at most half the box's diagonal);
    /// - Ẽ, the collisions and the minimum distance use the minimum-image edge lengths
    ///   ([`ProximityNet::lengths_of_in`]), the nearest-neighbour distances the minimum-image
    ///   distances, and the milling r_ic = displacement(q_c, q_i);
    /// - K̃ and the polarisation read the velocities only, which the wrap does not change.
    ///
    /// # Example
    /// ```
    /// use flock_graph::{NeighbourSearch, ProximityNet};
    /// use flock_math::Domain;
    /// use flock_metrics::{FlockMetrics, MetricParams};
    /// use glam::DVec2;
    ///
    /// // three agents 7 apart on a line that crosses the wrap at x = 0 of a 100 × 100 box
    /// let torus = Domain::Periodic { size: DVec2::new(100.0, 100.0) };
    /// let q = [DVec2::new(93.0, 50.0), DVec2::new(0.0, 50.0), DVec2::new(7.0, 50.0)];
    /// let p = [DVec2::X; 3];
    /// let mut net = ProximityNet::new();
    /// NeighbourSearch::new().build_in(&torus, &q, 8.4, &mut net);
    /// let params = MetricParams { d: 7.0, collision_distance: 1.75 };
    /// let m = FlockMetrics::measure_in(&torus, &q, &p, &net, &params);
    /// assert_eq!((m.connectivity, m.components, m.min_distance), (1.0, 1, 7.0));
    /// assert!(m.deviation_energy < 1e-24 && (m.cohesion_radius - 7.0).abs() < 1e-9);
    /// assert_eq!((m.polarisation, m.nearest_neighbour_mean, m.nearest_neighbour_min), (1.0, 7.0, 7.0));
    /// ```
    #[must_use]
    pub fn measure_in<V: Vector>(
        domain: &Domain<V>,
        q: &[V],
        p: &[V],
        net: &ProximityNet,
        params: &MetricParams,
    ) -> Self {
        if q.is_empty() {
            return Self::EMPTY;
        }
        let numbering = net.numbering();
        // the labels of the components are dropped before the edges' buffer is allocated
        let connectivity = || {
            let components = Components::of(net.graph());
            (
                relative_connectivity(&components),
                components.giant_share(),
                components.count(),
            )
        };
        let spread = || {
            let centre = domain.centre_of(numbering.ordered(q));
            (
                radius_about(domain, q, centre),
                mismatch_and_speed(numbering.ordered(p)),
                polarisation_of(numbering.ordered(p)),
                milling_about(domain, centre, numbering.ordered(q), numbering.ordered(p)),
            )
        };
        let (
            (connectivity, giant_component, components),
            (cohesion_radius, (velocity_mismatch, group_speed), polarisation, milling),
        ) = join(connectivity, spread);
        let edges = EdgeMetrics::of(domain, q, net, params);
        let nearest = NearestNeighbours::of(domain, q, net, &edges);
        Self {
            connectivity,
            giant_component,
            components,
            cohesion_radius,
            deviation_energy: edges.deviation_energy(net, params.d),
            velocity_mismatch,
            min_distance: if edges.shortest.is_finite() {
                edges.shortest
            } else {
                nearest.min
            },
            collisions: edges.close / 2,
            polarisation,
            milling,
            nearest_neighbour_mean: nearest.mean,
            nearest_neighbour_min: nearest.min,
            group_speed,
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

    /// The names of [`FlockMetrics::extras`], in its order: the columns of `metrics.csv` after
    /// `energy`, followed there by `components`.
    pub const EXTRA_COLUMNS: [&'static str; 5] = [
        "polarisation",
        "milling",
        "nearest_neighbour_mean",
        "nearest_neighbour_min",
        "group_speed",
    ];

    /// The real-valued metrics of the columns [`FlockMetrics::EXTRA_COLUMNS`]: the polarisation,
    /// the milling, the mean and least nearest-neighbour distances and the group's speed.
    #[must_use]
    pub fn extras(&self) -> [f64; 5] {
        [
            self.polarisation,
            self.milling,
            self.nearest_neighbour_mean,
            self.nearest_neighbour_min,
            self.group_speed,
        ]
    }

    /// The metrics with the values of [`FlockMetrics::extras`] `extras` (read back from
    /// `metrics.csv`, say), the others unchanged.
    #[must_use]
    pub const fn with_extras(self, extras: [f64; 5]) -> Self {
        let [
            polarisation,
            milling,
            nearest_neighbour_mean,
            nearest_neighbour_min,
            group_speed,
        ] = extras;
        Self {
            polarisation,
            milling,
            nearest_neighbour_mean,
            nearest_neighbour_min,
            group_speed,
            ..self
        }
    }

    /// The metrics of [`FlockMetrics::reals`] `reals` (read back from `metrics.csv`, say), with
    /// the counts that are not among them; the [`FlockMetrics::extras`] are NaN (unknown) until
    /// set with [`FlockMetrics::with_extras`].
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
            polarisation: f64::NAN,
            milling: f64::NAN,
            nearest_neighbour_mean: f64::NAN,
            nearest_neighbour_min: f64::NAN,
            group_speed: f64::NAN,
        }
    }
}

/// One agent's edge lengths l: Σ (l − d)² and the shortest (∞ without edges).
#[derive(Clone, Copy, Debug, Default)]
struct AgentLengths {
    squared_errors: f64,
    nearest: f64,
}

/// The metrics of the edge lengths, from one pass over them (behind [`FlockMetrics::measure`],
/// [`deviation_energy`] and [`collisions`]): Ẽ, the sum of the agents' nearest edges, the
/// shortest edge and the colliding pairs.
#[derive(Clone, Copy, Debug)]
struct EdgeMetrics {
    /// Σ_i Σ_j (l_ij − d)² over the directed edges, in original order of i.
    squared_errors: f64,
    /// Σ_i min_j l_ij in original order of i: ∞ when an agent has no edge.
    nearest_sum: f64,
    /// The shortest edge, ∞ without edges.
    shortest: f64,
    /// The directed edges shorter than the collision distance (each colliding pair twice).
    close: usize,
}

impl EdgeMetrics {
    const ZERO: Self = Self {
        squared_errors: 0.0,
        nearest_sum: 0.0,
        shortest: f64::INFINITY,
        close: 0,
    };

    /// One pass over each agent's edges in storage order, the agents' sums added in original
    /// order ([`Numbering::ordered_fold`]), so that each sum has the bits it has alone. Only an
    /// agent whose nearest edge is shorter than the collision distance has its edges read again,
    /// to count the close ones.
    fn of<V: Vector>(
        domain: &Domain<V>,
        q: &[V],
        net: &ProximityNet,
        params: &MetricParams,
    ) -> Self {
        debug_assert!(
            params.collision_distance <= net.range(),
            "collision distance beyond the net's range"
        );
        let (d, c) = (params.d, params.collision_distance);
        let lengths = |i| {
            net.lengths_of_in(domain, i, q).fold(
                AgentLengths {
                    squared_errors: 0.0,
                    nearest: f64::INFINITY,
                },
                |a, l| AgentLengths {
                    squared_errors: a.squared_errors + (l - d) * (l - d),
                    nearest: a.nearest.min(l),
                },
            )
        };
        let add = |m: Self, i, a: AgentLengths| {
            let close = if a.nearest < c {
                net.lengths_of_in(domain, i, q).filter(|&l| l < c).count()
            } else {
                0
            };
            m.merge(Self {
                squared_errors: a.squared_errors,
                nearest_sum: a.nearest,
                shortest: a.nearest,
                close,
            })
        };
        let n = net.graph().len();
        net.numbering()
            .ordered_fold(n, lengths, add, Self::merge, Self::ZERO)
    }

    /// The metrics of the edges of `self` and then `other`: sums and counts added, the least
    /// shortest edge.
    fn merge(self, other: Self) -> Self {
        Self {
            squared_errors: self.squared_errors + other.squared_errors,
            nearest_sum: self.nearest_sum + other.nearest_sum,
            shortest: self.shortest.min(other.shortest),
            close: self.close + other.close,
        }
    }

    /// Ẽ = E / d² (TAC 2006 eq. 82) with E = Σ (l − d)² / (|E| + 1) over the directed edges.
    fn deviation_energy(&self, net: &ProximityNet, d: f64) -> f64 {
        let edges = net.graph().directed_edge_count();
        self.squared_errors / (edges as f64 + 1.0) / (d * d)
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
    radius_about(&Domain::Open, q, mean_of(q.iter().copied()))
}

/// max_i ‖displacement(centre, q_i)‖ (0 for no agent).
fn radius_about<V: Vector>(domain: &Domain<V>, q: &[V], centre: V) -> f64 {
    q.iter()
        .map(|&qi| domain.displacement(centre, qi).length())
        .fold(0.0, f64::max)
}

/// The mean and least nearest-neighbour distances.
struct NearestNeighbours {
    mean: f64,
    min: f64,
}

impl NearestNeighbours {
    /// From the net's edges when every agent has a neighbour in it (its nearest is then its
    /// shortest edge, summed in original order in `edges`, and the least of them the net's
    /// shortest edge), otherwise from an exact search over all agents; the mean summed in
    /// original order.
    fn of<V: Vector>(domain: &Domain<V>, q: &[V], net: &ProximityNet, edges: &EdgeMetrics) -> Self {
        let n = q.len();
        if n < 2 {
            return Self {
                mean: f64::INFINITY,
                min: f64::INFINITY,
            };
        }
        let graph = net.graph();
        if graph.len() == n && (0..n).all(|i| graph.degree(i) > 0) {
            return Self {
                mean: edges.nearest_sum / n as f64,
                min: edges.shortest,
            };
        }
        let mut nearest = vec![f64::INFINITY; n];
        NeighbourSearch::new().nearest_distances_in(domain, q, &mut nearest);
        Self {
            mean: net.numbering().ordered_sum(n, |s| nearest[s]) / n as f64,
            min: nearest.iter().copied().fold(f64::INFINITY, f64::min),
        }
    }
}

/// The distance from each agent to its nearest other agent in `domain` (minimum image on a
/// torus), +∞ for an agent without another finite agent: exact, by
/// [`NeighbourSearch::nearest_distances_in`].
///
/// # Example
/// ```
/// use flock_math::Domain;
/// use flock_metrics::nearest_neighbour_distances;
/// use glam::DVec2;
///
/// let q = [DVec2::new(0.0, 0.0), DVec2::new(3.0, 0.0), DVec2::new(3.0, 1.0)];
/// assert_eq!(nearest_neighbour_distances(&Domain::Open, &q), [3.0, 1.0, 1.0]);
/// assert_eq!(nearest_neighbour_distances(&Domain::Open, &q[..1]), [f64::INFINITY]);
/// ```
#[must_use]
pub fn nearest_neighbour_distances<V: Vector>(domain: &Domain<V>, q: &[V]) -> Vec<f64> {
    let mut out = Vec::new();
    NeighbourSearch::new().nearest_distances_in(domain, q, &mut out);
    out
}

/// Ẽ = E(q) / d² with E(q) = (1/(|E| + 1)) Σ_i Σ_{j∈N_i} (‖q_j − q_i‖ − d)² (TAC 2006 eq. 7 and 82),
/// where E is the set of ordered pairs (i, j), j ∈ N_i, so |E| = Σ_i |N_i| and E is close to the mean
/// squared edge-length error.
///
/// `net` is the net of `q`, with or without stored distances.
#[must_use]
pub fn deviation_energy<V: Vector>(q: &[V], net: &ProximityNet, d: f64) -> f64 {
    EdgeMetrics::of(
        &Domain::Open,
        q,
        net,
        &MetricParams {
            d,
            collision_distance: 0.0,
        },
    )
    .deviation_energy(net, d)
}

/// K̃ = K / n with K = ½ Σ ‖p_i − p_c‖² (TAC 2006 eq. 83); 0 for no agent.
#[must_use]
pub fn velocity_mismatch<V: Vector>(p: &[V]) -> f64 {
    mismatch(p.iter().copied())
}

/// K̃ of the velocities, summed in the iterator's order.
fn mismatch<V: Vector>(p: impl ExactSizeIterator<Item = V> + Clone) -> f64 {
    mismatch_and_speed(p).0
}

/// K̃ and the group's speed ‖p_c‖ of the velocities, summed in the iterator's order; (0, 0) for
/// no velocity.
fn mismatch_and_speed<V: Vector>(p: impl ExactSizeIterator<Item = V> + Clone) -> (f64, f64) {
    let n = p.len();
    if n == 0 {
        return (0.0, 0.0);
    }
    let p_c = mean_of(p.clone());
    let k = 0.5 * p.map(|pi| (pi - p_c).length_squared()).sum::<f64>() / n as f64;
    (k, p_c.length())
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
        flock_graph::nearest_pair_distance(q).unwrap_or(f64::INFINITY)
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
    EdgeMetrics::of(&Domain::Open, q, net, &params).close / 2
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heading::{milling, polarisation};
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
        let bits = |m: FlockMetrics| {
            let [a, b, c, d, e, f] = m.reals().map(f64::to_bits);
            let [g, h, i, j, k] = m.extras().map(f64::to_bits);
            [a, b, c, d, e, f, g, h, i, j, k]
        };
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
        assert!(back.polarisation.is_nan() && back.nearest_neighbour_min.is_nan());
        assert_eq!(
            back.with_extras(original.extras()),
            original,
            "from_reals and with_extras invert reals and extras"
        );
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

    /// A deterministic stream of numbers in [0, 1).
    fn uniform(seed: u64) -> impl FnMut() -> f64 {
        let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A flock about `centre` (spread ±`spread` per axis) with velocities turning about it.
    fn moving_group<V: Vector>(seed: u64, n: usize, centre: V, spread: f64) -> (Vec<V>, Vec<V>) {
        let mut u = uniform(seed);
        let q: Vec<V> = (0..n)
            .map(|_| centre + V::from_fn(|_| spread * (2.0 * u() - 1.0)))
            .collect();
        let p: Vec<V> = (0..n)
            .map(|_| V::from_fn(|k| if k == 0 { 1.0 } else { 0.0 } + 0.8 * (2.0 * u() - 1.0)))
            .collect();
        (q, p)
    }

    /// The same flock measured in open space and cut by the faces of a periodic box (its centre
    /// near a corner, so on every axis some agents are wrapped to the far side): every metric
    /// agrees, so none of them reads a wrapped coordinate as a distance.
    fn check_torus_matches_open<V: Vector>() {
        let size = V::from_fn(|k| [60.0, 50.0, 40.0][k]);
        let torus = Domain::Periodic { size };
        let params = MetricParams {
            d: 7.0,
            collision_distance: 2.0,
        };
        // clustered (every agent has a neighbour) and sparse (some have none: the search path)
        for (seed, n, spread) in [(1, 60, 6.0), (2, 40, 14.0), (3, 2, 1.0)] {
            let (q_open, p) = moving_group::<V>(seed, n, V::from_fn(|_| 100.0), spread);
            let corner = V::from_fn(|k| size.coord(k) - 0.7);
            let shift = corner - V::from_fn(|_| 100.0);
            let q_torus: Vec<V> = q_open.iter().map(|&x| torus.wrap(x + shift)).collect();
            assert!(
                q_torus.iter().any(|x| x.coord(0) < 10.0)
                    && q_torus.iter().any(|x| x.coord(0) > 50.0)
                    || n < 10
            );
            let open_net = ProximityNet::brute_force(&q_open, 8.4);
            let mut torus_net = ProximityNet::without_distances();
            flock_graph::NeighbourSearch::new().build_in(&torus, &q_torus, 8.4, &mut torus_net);
            let a = FlockMetrics::measure(&q_open, &p, &open_net, &params);
            let b = FlockMetrics::measure_in(&torus, &q_torus, &p, &torus_net, &params);
            assert_eq!(
                (a.components, a.collisions),
                (b.components, b.collisions),
                "seed {seed}"
            );
            // R and the milling are measured from the circular mean, a little off the mean:
            // compare with open space about the same centre, unwrapped
            let centre = torus.centre_of(q_torus.iter().copied());
            let unwrapped = q_open[0] + torus.displacement(q_torus[0], centre);
            let mean = mean_of(q_open.iter().copied());
            assert!(
                (unwrapped - mean).length() < 0.1 * spread,
                "{unwrapped:?} {mean:?}"
            );
            let a = FlockMetrics {
                cohesion_radius: radius_about(&Domain::Open, &q_open, unwrapped),
                milling: milling_about(
                    &Domain::Open,
                    unwrapped,
                    q_open.iter().copied(),
                    p.iter().copied(),
                ),
                ..a
            };
            for (x, y) in a
                .reals()
                .into_iter()
                .chain(a.extras())
                .zip(b.reals().into_iter().chain(b.extras()))
            {
                assert_relative_eq!(x, y, epsilon = 1e-9, max_relative = 1e-9);
            }
            if n > 10 {
                assert!(a.milling > 0.01 && a.polarisation > 0.3, "{a:?}");
            }
            // the metrics with the open-space formulas are wrong on the torus: the test can fail
            let naive = FlockMetrics::measure(&q_torus, &p, &torus_net, &params);
            if n > 10 {
                assert!(naive.cohesion_radius > a.cohesion_radius + 5.0);
                assert!((naive.milling - a.milling).abs() > 1e-3);
            }
        }
    }

    #[test]
    fn torus_matches_open_space_2d() {
        check_torus_matches_open::<DVec2>();
    }

    #[test]
    fn torus_matches_open_space_3d() {
        check_torus_matches_open::<DVec3>();
    }

    /// Open space is `measure`, bit for bit, and `measure` keeps the former definitions.
    #[test]
    fn open_domain_is_measure_bit_for_bit() {
        let (q, p) = moving_group::<DVec3>(7, 80, DVec3::ZERO, 12.0);
        let net = ProximityNet::brute_force(&q, 8.4);
        let params = MetricParams {
            d: 7.0,
            collision_distance: 2.0,
        };
        let a = FlockMetrics::measure(&q, &p, &net, &params);
        let b = FlockMetrics::measure_in(&Domain::Open, &q, &p, &net, &params);
        let bits = |m: &FlockMetrics| (m.reals().map(f64::to_bits), m.extras().map(f64::to_bits));
        assert_eq!(bits(&a), bits(&b));
        assert_eq!(a.cohesion_radius.to_bits(), cohesion_radius(&q).to_bits());
        assert_eq!(a.min_distance.to_bits(), min_distance(&q, &net).to_bits());
        assert_eq!(a.polarisation.to_bits(), polarisation(&p).to_bits());
        assert_eq!(
            a.milling.to_bits(),
            milling(&Domain::Open, &q, &p).to_bits()
        );
    }

    /// The nearest-neighbour distances against brute force, on the net's path (every agent has a
    /// neighbour) and on the search's (loners beyond the range), in open space and on a torus.
    fn check_nearest<V: Vector>() {
        let size = V::from_fn(|_| 80.0);
        let params = MetricParams {
            d: 7.0,
            collision_distance: 2.0,
        };
        for domain in [Domain::Open, Domain::Periodic { size }] {
            for (seed, n, spread) in [(11, 50, 8.0), (12, 50, 39.9)] {
                let (q, p) = moving_group::<V>(seed, n, V::from_fn(|_| 40.0), spread);
                let brute: Vec<f64> = (0..n)
                    .map(|i| {
                        (0..n)
                            .filter(|&j| j != i)
                            .map(|j| domain.distance(q[i], q[j]))
                            .fold(f64::INFINITY, f64::min)
                    })
                    .collect();
                let mut net = ProximityNet::new();
                flock_graph::NeighbourSearch::new().build_in(&domain, &q, 8.4, &mut net);
                let isolated = (0..n).any(|i| net.graph().degree(i) == 0);
                assert_eq!(isolated, spread > 10.0, "both paths are tested");
                let m = FlockMetrics::measure_in(&domain, &q, &p, &net, &params);
                let mean = brute.iter().sum::<f64>() / n as f64;
                let least = brute.iter().copied().fold(f64::INFINITY, f64::min);
                assert_relative_eq!(m.nearest_neighbour_mean, mean, max_relative = 1e-12);
                assert_eq!(m.nearest_neighbour_min, least);
                assert_eq!(m.min_distance, least);
                assert_eq!(nearest_neighbour_distances(&domain, &q), brute);
            }
        }
    }

    #[test]
    fn nearest_neighbours_match_brute_force_2d() {
        check_nearest::<DVec2>();
    }

    #[test]
    fn nearest_neighbours_match_brute_force_3d() {
        check_nearest::<DVec3>();
    }

    #[test]
    fn order_parameters_of_known_states() {
        // a mill in 3D: agents on a circle in the plane z = 5 moving tangentially
        let q: Vec<DVec3> = (0..12)
            .map(|k| {
                let a = f64::from(k) * core::f64::consts::TAU / 12.0;
                DVec3::new(a.cos(), a.sin(), 5.0) * 10.0
            })
            .collect();
        let p: Vec<DVec3> = q.iter().map(|x| DVec3::new(-x.y, x.x, 0.0) * 0.3).collect();
        assert!((milling(&Domain::Open, &q, &p) - 1.0).abs() < 1e-12);
        assert!(polarisation(&p) < 1e-12);
        // clockwise in 2D: the absolute value
        let q2: Vec<DVec2> = q.iter().map(|x| x.truncate()).collect();
        let p2: Vec<DVec2> = q2.iter().map(|x| DVec2::new(x.y, -x.x)).collect();
        assert!((milling(&Domain::Open, &q2, &p2) - 1.0).abs() < 1e-12);
        // the same mill on a torus, cut by the faces: still a mill
        let torus = Domain::Periodic {
            size: DVec2::new(30.0, 30.0),
        };
        let wrapped: Vec<DVec2> = q2.iter().map(|&x| torus.wrap(x)).collect();
        assert!((milling(&torus, &wrapped, &p2) - 1.0).abs() < 1e-9);
        assert!(milling(&Domain::Open, &wrapped, &p2) < 0.9);
        // one agent: the polarisation of its heading, no milling, no nearest neighbour
        let one = [DVec2::new(3.0, 4.0)];
        let net = ProximityNet::brute_force(&one, 8.4);
        let params = MetricParams {
            d: 7.0,
            collision_distance: 2.0,
        };
        let m = FlockMetrics::measure(&one, &[DVec2::new(0.0, 2.0)], &net, &params);
        assert_eq!((m.polarisation, m.milling), (1.0, 0.0));
        assert_eq!(
            (
                m.nearest_neighbour_mean,
                m.nearest_neighbour_min,
                m.min_distance
            ),
            (f64::INFINITY, f64::INFINITY, f64::INFINITY)
        );
        // agents at rest count in N
        assert_eq!(
            polarisation(&[DVec3::X, DVec3::ZERO, DVec3::ZERO, DVec3::Y * 2.0]),
            2f64.sqrt() / 4.0
        );
        let none = FlockMetrics::measure::<DVec2>(
            &[],
            &[],
            &ProximityNet::brute_force::<DVec2>(&[], 8.4),
            &params,
        );
        // no agent: every order measure undefined (issue 27), not a flock of zero order
        assert!(none.is_empty_flock());
        assert!(none.polarisation.is_nan() && none.milling.is_nan());
        assert!(none.nearest_neighbour_mean.is_nan());
    }
}
