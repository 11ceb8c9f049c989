//! [`Scene`]: what the figures draw, independent of files: the frames of a run (positions and
//! velocities of the α-agents, the γ-agent), the interaction range r that defines the net's edges,
//! and the obstacles.

use flock_graph::{NeighbourSearch, ProximityNet};
use flock_math::{Domain, Vector};
use glam::DVec3;

use crate::error::VizError;
use crate::scene::drawable::Drawable;
use crate::scene::projection::lift;

/// The state of the flock at one recorded time.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    /// The time t (s).
    pub t: f64,
    /// The α-agents' positions q_i, in agent order (z = 0 in 2D).
    pub positions: Vec<DVec3>,
    /// The α-agents' velocities p_i, aligned with `positions`: the heading of each marker.
    pub velocities: Vec<DVec3>,
    /// The γ-agent's position q_r, when the run has one.
    pub gamma: Option<DVec3>,
    /// The direction each vehicle points (its body's forward axis), aligned with `positions`,
    /// for agents that are vehicles; `None` for point masses, which point along their velocity.
    pub headings: Option<Vec<DVec3>>,
    /// Whether each agent has failed (the trajectory's `failed` column of a run with
    /// `conditions.faults`), aligned with `positions`; empty for a run without faults.
    pub failed: Vec<bool>,
}

impl Frame {
    /// A frame from positions and velocities of equal length.
    #[must_use]
    pub fn new(t: f64, positions: Vec<DVec3>, velocities: Vec<DVec3>) -> Self {
        Self {
            t,
            positions,
            velocities,
            gamma: None,
            headings: None,
            failed: Vec::new(),
        }
    }

    /// The frame with each agent's failure flag (aligned with the positions).
    #[must_use]
    pub fn with_failed(mut self, failed: Vec<bool>) -> Self {
        self.failed = failed;
        self
    }

    /// Whether agent `i` has failed.
    #[must_use]
    pub fn has_failed(&self, i: usize) -> bool {
        self.failed.get(i).copied().unwrap_or(false)
    }

    /// How many agents have failed.
    #[must_use]
    pub fn failed_count(&self) -> usize {
        self.failed.iter().filter(|&&f| f).count()
    }

    /// The frame with each vehicle pointing along `headings` (aligned with the positions).
    #[must_use]
    pub fn with_headings(mut self, headings: Vec<DVec3>) -> Self {
        self.headings = Some(headings);
        self
    }

    /// The direction agent `i`'s marker points: its vehicle's heading, or its velocity.
    #[must_use]
    pub fn facing(&self, i: usize) -> DVec3 {
        self.headings
            .as_ref()
            .map_or(self.velocities[i], |headings| headings[i])
    }

    /// A frame from a run's own vectors (`DVec2` or `DVec3`), as the protocols hold them.
    #[must_use]
    pub fn from_vectors<V: Vector>(t: f64, positions: &[V], velocities: &[V]) -> Self {
        Self::new(
            t,
            positions.iter().map(|&q| lift(q)).collect(),
            velocities.iter().map(|&p| lift(p)).collect(),
        )
    }

    /// The frame with the γ-agent at `gamma`.
    #[must_use]
    pub fn with_gamma(mut self, gamma: DVec3) -> Self {
        self.gamma = Some(gamma);
        self
    }
}

/// Everything a figure of a run draws: frames, the range r of the proximity net, obstacles.
///
/// # Example
/// ```
/// use flock_viz::{Drawable, Frame, Scene};
/// use glam::DVec2;
///
/// let q = [DVec2::new(0.0, 0.0), DVec2::new(5.0, 0.0), DVec2::new(20.0, 0.0)];
/// let p = [DVec2::X; 3];
/// let scene = Scene::new(2, 8.4)
///     .with_title("three agents")
///     .with_frame(Frame::from_vectors(0.0, &q, &p))
///     .with_obstacle(Drawable::ball(DVec2::new(10.0, 10.0), 2.0))
///     .with_gamma(|t| glam::DVec3::new(t, 0.0, 0.0));
/// assert_eq!(scene.edges(0), vec![(0, 1)]); // ‖q_1 − q_0‖ = 5 < 8.4, the third is alone
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// A title for the figures (the scenario's name), may be empty.
    pub title: String,
    /// The dimension of the run, 2 or 3.
    pub dim: usize,
    /// The interaction range r: agents closer than r are neighbours, joined by an edge.
    pub range: f64,
    /// The recorded frames, in time order.
    pub frames: Vec<Frame>,
    /// The obstacles.
    pub obstacles: Vec<Drawable>,
    /// A fixed interaction graph (pairs (i, j), i < j) drawn instead of the proximity net: the
    /// neighbouring graph of the Tanner law (Tanner et al. 2003, Figs. 3–8).
    pub interaction_graph: Option<Vec<(u32, u32)>>,
    /// The desired distance d of the lattice, by which an edge's stress weight has its sign
    /// (ACC 2004 eq. 26: attraction beyond d, repulsion within).
    pub desired_distance: Option<f64>,
    /// The sides (L₁, L₂[, L₃]) of the periodic box [0, L₁) × … the run lives in, z = 0 in 2D;
    /// `None` in open space. A periodic scene draws the box, its net by minimum image, no edge
    /// and no trail segment across the wrap.
    pub periodic_box: Option<DVec3>,
}

impl Scene {
    /// An empty scene of dimension `dim` (2 or 3) and interaction range `range`.
    #[must_use]
    pub fn new(dim: usize, range: f64) -> Self {
        Self {
            title: String::new(),
            dim,
            range,
            frames: Vec::new(),
            obstacles: Vec::new(),
            interaction_graph: None,
            desired_distance: None,
            periodic_box: None,
        }
    }

    /// The scene of a run in the periodic box of sides `size` (lifted: z = 0 in 2D).
    ///
    /// # Example
    /// ```
    /// use flock_viz::{Frame, Scene};
    /// use glam::{DVec2, DVec3};
    ///
    /// // two agents either side of the wrap at x = 0 of a 20 × 20 box are neighbours
    /// let q = [DVec2::new(0.5, 5.0), DVec2::new(19.5, 5.0)];
    /// let scene = Scene::new(2, 8.4)
    ///     .with_frame(Frame::from_vectors(0.0, &q, &[DVec2::X; 2]))
    ///     .with_periodic_box(DVec3::new(20.0, 20.0, 0.0));
    /// assert_eq!(scene.edges(0), vec![(0, 1)]);
    /// assert!(scene.crosses_wrap(scene.frames[0].positions[0], scene.frames[0].positions[1]));
    /// ```
    #[must_use]
    pub fn with_periodic_box(mut self, size: DVec3) -> Self {
        self.periodic_box = Some(size);
        self
    }

    /// The domain of the lifted positions: open, or the periodic box (the unused z side of a
    /// 2D box is 1, where every z is 0).
    fn domain(&self) -> Domain<DVec3> {
        match self.periodic_box {
            None => Domain::Open,
            Some(size) if self.dim == 2 => Domain::Periodic {
                size: DVec3::new(size.x, size.y, 1.0),
            },
            Some(size) => Domain::Periodic { size },
        }
    }

    /// Whether the straight segment from `a` to `b` crosses the wrap of the periodic box: the
    /// minimum image of b − a is not b − a (some |b_k − a_k| > L_k/2). Never in open space.
    #[must_use]
    pub fn crosses_wrap(&self, a: DVec3, b: DVec3) -> bool {
        self.domain().displacement(a, b) != b - a
    }

    /// The positions of agent `agent` over `frames` (indices into [`Scene::frames`]), cut into
    /// runs where the agent crosses the wrap of the periodic box between two frames (one run in
    /// open space); empty when a frame lacks the agent.
    #[must_use]
    pub fn trail_runs(&self, agent: usize, frames: core::ops::Range<usize>) -> Vec<Vec<DVec3>> {
        let mut runs: Vec<Vec<DVec3>> = Vec::new();
        let mut previous: Option<DVec3> = None;
        for frame in &self.frames[frames] {
            let Some(&q) = frame.positions.get(agent) else {
                return Vec::new();
            };
            match previous {
                Some(p) if !self.crosses_wrap(p, q) => {
                    if let Some(run) = runs.last_mut() {
                        run.push(q);
                    }
                }
                _ => runs.push(vec![q]),
            }
            previous = Some(q);
        }
        runs
    }

    /// The scene with a title.
    #[must_use]
    pub fn with_title(mut self, title: impl Into<String>) -> Self {
        self.title = title.into();
        self
    }

    /// The scene with one more frame.
    #[must_use]
    pub fn with_frame(mut self, frame: Frame) -> Self {
        self.frames.push(frame);
        self
    }

    /// The scene with one more obstacle.
    #[must_use]
    pub fn with_obstacle(mut self, obstacle: Drawable) -> Self {
        self.obstacles.push(obstacle);
        self
    }

    /// The scene with the γ-agent at `gamma(t)` in every frame (runs record the α-agents only;
    /// the γ-agent's motion is known from the scenario).
    #[must_use]
    pub fn with_gamma(mut self, gamma: impl Fn(f64) -> DVec3) -> Self {
        for frame in &mut self.frames {
            frame.gamma = Some(gamma(frame.t));
        }
        self
    }

    /// The scene drawn on the fixed graph of `edges` (pairs of agent indices, any order) instead of
    /// the proximity net.
    #[must_use]
    pub fn with_interaction_graph(mut self, edges: impl IntoIterator<Item = (u32, u32)>) -> Self {
        let mut edges: Vec<(u32, u32)> = edges
            .into_iter()
            .map(|(i, j)| (i.min(j), i.max(j)))
            .collect();
        edges.sort_unstable();
        edges.dedup();
        self.interaction_graph = Some(edges);
        self
    }

    /// The scene with the lattice's desired distance d (for edges coloured by stress).
    #[must_use]
    pub fn with_desired_distance(mut self, d: f64) -> Self {
        self.desired_distance = Some(d);
        self
    }

    /// The edges drawn in frame `frame`: those of the [interaction
    /// graph](Scene::with_interaction_graph) if the scene has one, else of the proximity net —
    /// pairs (i, j), i < j, with ‖q_j − q_i‖ < r, in order (built with
    /// [`flock_graph::NeighbourSearch`]).
    ///
    /// # Panics
    /// When `frame` is out of range.
    #[must_use]
    pub fn edges(&self, frame: usize) -> Vec<(u32, u32)> {
        if let Some(edges) = &self.interaction_graph {
            return edges.clone();
        }
        let mut net = ProximityNet::new();
        NeighbourSearch::new().build_in(
            &self.domain(),
            &self.frames[frame].positions,
            self.range,
            &mut net,
        );
        let graph = net.graph();
        let mut edges = Vec::with_capacity(graph.undirected_edge_count());
        for i in 0..graph.len() {
            for &j in graph.neighbours(i) {
                if (j as usize) > i {
                    edges.push((i as u32, j));
                }
            }
        }
        edges
    }

    /// The index of the frame recorded nearest to time `t` (the earlier on a tie), if any.
    #[must_use]
    pub fn frame_nearest(&self, t: f64) -> Option<usize> {
        (0..self.frames.len()).min_by(|&a, &b| {
            let da = (self.frames[a].t - t).abs();
            let db = (self.frames[b].t - t).abs();
            da.total_cmp(&db).then(a.cmp(&b))
        })
    }

    /// `count` frame indices spread evenly over the run, first and last included, without
    /// repeats: the snapshot times of a figure like TAC 2006 Figs. 10–13 (a)–(f).
    #[must_use]
    pub fn evenly_spaced_frames(&self, count: usize) -> Vec<usize> {
        let n = self.frames.len();
        if n == 0 || count == 0 {
            return Vec::new();
        }
        if count == 1 {
            return vec![n - 1];
        }
        let mut out: Vec<usize> = (0..count)
            .map(|k| ((k * (n - 1)) as f64 / (count - 1) as f64).round() as usize)
            .collect();
        out.dedup();
        out
    }

    /// [`Scene::frame_nearest`] each of `times` (s), without repeats, in order: the snapshots a
    /// scenario asks for where things happen (its `snapshots`).
    #[must_use]
    pub fn frames_nearest(&self, times: &[f64]) -> Vec<usize> {
        let mut out: Vec<usize> = times
            .iter()
            .filter_map(|&t| self.frame_nearest(t))
            .collect();
        out.dedup();
        out
    }

    /// Checks that the scene can be drawn.
    pub(crate) fn validate(&self) -> Result<(), VizError> {
        if self.dim != 2 && self.dim != 3 {
            return Err(VizError::invalid(format!(
                "a scene has dimension 2 or 3, not {}",
                self.dim
            )));
        }
        if self.frames.is_empty() {
            return Err(VizError::invalid("the scene has no frames"));
        }
        for (k, frame) in self.frames.iter().enumerate() {
            if frame.positions.len() != frame.velocities.len() {
                return Err(VizError::invalid(format!(
                    "frame {k} (t = {}) has {} positions but {} velocities",
                    frame.t,
                    frame.positions.len(),
                    frame.velocities.len()
                )));
            }
            if let Some(&(i, j)) = self
                .interaction_graph
                .iter()
                .flatten()
                .find(|&&(_, j)| j as usize >= frame.positions.len())
            {
                return Err(VizError::invalid(format!(
                    "the interaction graph's edge ({i}, {j}) names an agent beyond the {} of frame {k}",
                    frame.positions.len()
                )));
            }
        }
        Ok(())
    }
}
