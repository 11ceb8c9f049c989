//! The observation of one agent ([`Layout`]): a fixed-size row of numbers made from what the
//! agent perceives ([`Perception`]) — its own measured velocity, the k nearest agents it heard,
//! the γ-agent and the nearest β-agent, each relative to itself, padded and masked.

use super::row_of;
use crate::perception::Perception;

/// Where each field of an agent's observation lies, for dimension `dim` and `k` neighbours.
///
/// | field | length | content |
/// | --- | --- | --- |
/// | `velocity` | dim | p_i as agent i measures it |
/// | `neighbours` | k × 2·dim | for the k nearest agents heard (by ‖q_j − q_i‖, ties by index): q_j − q_i, then p_j − p_i; zeros past the agents heard |
/// | `neighbour_mask` | k | 1 for an agent heard, 0 for padding |
/// | `gamma` | 2·dim | q_r − q_i, p_r − p_i of the γ-agent (zeros without one) |
/// | `gamma_mask` | 1 | 1 when the protocol tracks a γ-agent |
/// | `beta` | 2·dim | q̂_ik − q_i, p̂_ik − p_i of the nearest β-agent (zeros without one) |
/// | `beta_mask` | 1 | 1 when a β-agent is within r′ |
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    /// The dimension, 2 or 3.
    pub dim: usize,
    /// The number of neighbours observed, k.
    pub k: usize,
}

impl Layout {
    /// The fields in order, each with its length.
    #[must_use]
    pub const fn fields(&self) -> [(&'static str, usize); 7] {
        let d = self.dim;
        [
            ("velocity", d),
            ("neighbours", self.k * 2 * d),
            ("neighbour_mask", self.k),
            ("gamma", 2 * d),
            ("gamma_mask", 1),
            ("beta", 2 * d),
            ("beta_mask", 1),
        ]
    }

    /// The length of an agent's observation: 5·dim + 2 + k(2·dim + 1).
    #[must_use]
    pub const fn size(&self) -> usize {
        5 * self.dim + 2 + self.k * (2 * self.dim + 1)
    }

    /// Writes every agent's observation (n rows of [`Layout::size`]) into `out`, from
    /// `perception`; `order` is scratch for the sort of each agent's neighbours.
    pub fn observe(&self, perception: &Perception, out: &mut [f64], order: &mut Vec<(f64, usize)>) {
        let (d, k) = (self.dim, self.k);
        for (i, obs) in out.chunks_exact_mut(self.size()).enumerate() {
            obs.fill(0.0);
            let (velocity, rest) = obs.split_at_mut(d);
            velocity.copy_from_slice(row_of(d, &perception.velocities, i));
            let (neighbours, rest) = rest.split_at_mut(k * 2 * d);
            let (mask, rest) = rest.split_at_mut(k);
            order.clear();
            order.extend((perception.indptr[i]..perception.indptr[i + 1]).map(|m| {
                let dq = row_of(d, &perception.relative_positions, m);
                (dq.iter().map(|x| x * x).sum::<f64>(), m)
            }));
            order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            for ((slot, flag), &(_, m)) in neighbours.chunks_exact_mut(2 * d).zip(mask).zip(&*order)
            {
                slot[..d].copy_from_slice(row_of(d, &perception.relative_positions, m));
                slot[d..].copy_from_slice(row_of(d, &perception.relative_velocities, m));
                *flag = 1.0;
            }
            let (gamma, rest) = rest.split_at_mut(2 * d);
            if let Some((q_r, p_r)) = &perception.gamma {
                let (q, p) = (
                    row_of(d, &perception.positions, i),
                    row_of(d, &perception.velocities, i),
                );
                for c in 0..d {
                    gamma[c] = q_r[c] - q[c];
                    gamma[d + c] = p_r[c] - p[c];
                }
                rest[0] = 1.0;
            }
            let (beta, beta_mask) = rest[1..].split_at_mut(2 * d);
            let nearest =
                (perception.beta_indptr[i]..perception.beta_indptr[i + 1]).min_by(|&a, &b| {
                    let length = |m| {
                        row_of(d, &perception.beta_relative_positions, m)
                            .iter()
                            .map(|x| x * x)
                            .sum::<f64>()
                    };
                    length(a).total_cmp(&length(b))
                });
            if let Some(m) = nearest {
                beta[..d].copy_from_slice(row_of(d, &perception.beta_relative_positions, m));
                beta[d..].copy_from_slice(row_of(d, &perception.beta_relative_velocities, m));
                beta_mask[0] = 1.0;
            }
        }
    }
}
