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
mod tests;
