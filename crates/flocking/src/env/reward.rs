//! The default reward of an agent ([`Reward`]), from the true state after its step and the
//! measures of TAC 2006 § VIII: its share of the deviation energy, its velocity mismatch with its
//! neighbours, a collision penalty and its distance to the γ-agent, weighted.

use flock_graph::Graph;

use super::row_of;

/// The weights of the default reward
/// r_i = −(w_E e_i + w_K m_i + w_C c_i + w_γ g_i), each term of the true state after the step:
///
/// - e_i = Σ_{j∈N_i} (‖q_j − q_i‖ − d)² / ((|E| + 1) d²), agent i's share of the normalised
///   deviation energy Ẽ = E(q)/d² (TAC 2006 eq. 7, 82; |E| = Σ_i |N_i|): Σ_i e_i = Ẽ;
/// - m_i = (1/|N_i|) Σ_{j∈N_i} ‖p_j − p_i‖², its velocity mismatch with its neighbours (0 alone);
/// - c_i = #{ j ∈ N_i : ‖q_j − q_i‖ < d_c }, the agents closer than the scenario's collision
///   distance (d_c < r: every such agent is a neighbour);
/// - g_i = ‖q_i − q_r‖² / r², its distance to the γ-agent in interaction ranges (0 without one).
///
/// N_i is the proximity net of range r (or the protocol's fixed graph), on a torus by the
/// nearest image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reward {
    /// w_E, on the share of the deviation energy.
    pub deviation: f64,
    /// w_K, on the velocity mismatch with the neighbours.
    pub mismatch: f64,
    /// w_C, per agent closer than the collision distance.
    pub collision: f64,
    /// w_γ, on the squared distance to the γ-agent.
    pub gamma: f64,
}

impl Default for Reward {
    /// w_E = 1, w_K = 0.1, w_C = 1, w_γ = 0.01.
    fn default() -> Self {
        Self {
            deviation: 1.0,
            mismatch: 0.1,
            collision: 1.0,
            gamma: 0.01,
        }
    }
}

/// What the reward reads of a scenario: d, r, the collision distance and a periodic box.
#[derive(Clone, Debug, PartialEq)]
pub struct Scales {
    /// The desired distance d.
    pub d: f64,
    /// The interaction range r.
    pub r: f64,
    /// The collision distance d_c.
    pub collision_distance: f64,
    /// The side of the periodic box per axis, `None` in open space.
    pub box_size: Option<Vec<f64>>,
}

impl Scales {
    /// q_j − q_i, by the nearest image in a periodic box.
    fn displacement(&self, qi: &[f64], qj: &[f64], out: &mut [f64]) {
        for (c, o) in out.iter_mut().enumerate() {
            let mut x = qj[c] - qi[c];
            if let Some(size) = &self.box_size {
                x -= size[c] * (x / size[c]).round();
            }
            *o = x;
        }
    }
}

impl Reward {
    /// Every agent's reward into `out` (n), from the positions and velocities (n rows of `dim`,
    /// original order) and their `graph`, and the γ-agent's position q_r if any; agents that do not
    /// move (`active` false) get 0.
    pub fn of(
        &self,
        scales: &Scales,
        dim: usize,
        (q, p, graph): (&[f64], &[f64], &Graph),
        gamma: Option<&[f64]>,
        active: impl Fn(usize) -> bool,
        out: &mut [f64],
    ) {
        let square = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>();
        let edges = graph.directed_edge_count() as f64;
        let mut dq = [0.0; 3];
        let dq = &mut dq[..dim];
        let collision2 = scales.collision_distance * scales.collision_distance;
        for (i, r) in out.iter_mut().enumerate() {
            if !active(i) {
                *r = 0.0;
                continue;
            }
            let (mut deviation, mut mismatch, mut collisions) = (0.0, 0.0, 0usize);
            let neighbours = graph.neighbours(i);
            for &j in neighbours {
                let j = j as usize;
                scales.displacement(row_of(dim, q, i), row_of(dim, q, j), dq);
                let length2 = square(dq);
                deviation += (length2.sqrt() - scales.d).powi(2);
                mismatch += row_of(dim, p, j)
                    .iter()
                    .zip(row_of(dim, p, i))
                    .map(|(a, b)| (a - b) * (a - b))
                    .sum::<f64>();
                collisions += usize::from(length2 < collision2 && active(j));
            }
            let e = deviation / ((edges + 1.0) * scales.d * scales.d);
            let m = if neighbours.is_empty() {
                0.0
            } else {
                mismatch / neighbours.len() as f64
            };
            let g = gamma.map_or(0.0, |q_r| {
                scales.displacement(q_r, row_of(dim, q, i), dq);
                square(dq) / (scales.r * scales.r)
            });
            *r = -(self.deviation * e
                + self.mismatch * m
                + self.collision * collisions as f64
                + self.gamma * g);
        }
    }
}
