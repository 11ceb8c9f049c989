//! The α-α interaction of TAC 2006: gradient-based term and velocity consensus (eq. 23–24).

use flock_graph::ProximityNet;
use flock_math::interrupt::cuts_short;
use flock_math::parallel::{
    fill_interruptible, for_each_chunk_mut, for_each_chunk_mut_with, threads,
};
use flock_math::{Bump, BumpedAction, Potential, SigmaNorm, UnevenSigmoid, Vector};

use crate::error::{ParamError, check};

/// Bounds on the agents per chunk of [`AlphaInteraction::inputs`] (any size gives the same inputs;
/// large chunks have fewer pairs computed twice across their first boundary).
const SWEEP_CHUNK: (usize, usize) = (1024, 1 << 17);

/// Agents per chunk of [`AlphaInteraction::inputs`] for a net with a numbering: pairs leaving a
/// chunk are computed twice, and a chunk keeps two vectors per edge (about 3 MB in 2D, 9 MB in
/// 3D at the papers' density).
const PAIRED_CHUNK: usize = 1 << 14;

/// A thread's buffers for [`AlphaInteraction::paired`], reused from chunk to chunk.
#[derive(Default)]
struct Paired<V> {
    /// The terms each edge of the chunk receives, and one where reverse terms leaving it go.
    terms: Vec<(V, V)>,
    /// (e, i, j) of each pair the chunk computes: i's edge e to j (agent indices as a net
    /// stores them).
    pairs: Vec<(usize, u32, u32)>,
}

/// Agents per chunk of [`AlphaInteraction::inputs`]: about four chunks per thread, within
/// [`SWEEP_CHUNK`].
fn sweep_chunk(n: usize) -> usize {
    n.div_ceil(4 * threads())
        .clamp(SWEEP_CHUNK.0, SWEEP_CHUNK.1)
}

/// Parameters of the α-interaction, with the papers' values as [`Default`]:
/// d = 7, r = 1.2 d, ε = 0.1, a = b = 5, h = 0.2 (TAC 2006, Section VIII).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlphaParams {
    /// Desired inter-agent distance d (the lattice scale).
    pub d: f64,
    /// Interaction range r > d.
    pub r: f64,
    /// σ-norm parameter ε > 0.
    pub epsilon: f64,
    /// Attraction bound a of the uneven sigmoid, 0 < a ≤ b.
    pub a: f64,
    /// Repulsion bound b of the uneven sigmoid.
    pub b: f64,
    /// Flat part h ∈ (0, 1) of the bump ρ_h in φ_α and in the adjacency.
    pub h: f64,
}

impl AlphaParams {
    /// The papers' lattice distance d = 7 (TAC 2006, Section VIII).
    pub const PAPERS_D: f64 = 7.0;

    /// The papers' parameters for lattice distance `d`: r = 1.2 d ([`AlphaParams::range_for`]),
    /// ε = 0.1, a = b = 5, h = 0.2 (TAC 2006, Section VIII).
    #[must_use]
    pub fn papers(d: f64) -> Self {
        Self {
            d,
            r: Self::range_for(d),
            epsilon: 0.1,
            a: 5.0,
            b: 5.0,
            h: 0.2,
        }
    }

    /// The papers' interaction range for lattice distance `d`: r = 1.2 d (κ = r/d = 1.2).
    #[must_use]
    pub fn range_for(d: f64) -> f64 {
        1.2 * d
    }

    /// Checks every parameter against the domain of TAC 2006: 0 < d < r, ε > 0, 0 < a ≤ b,
    /// h ∈ (0, 1), lengths within [10⁻⁹, 10⁹].
    ///
    /// # Errors
    /// The first parameter outside its domain, named by its field (`d`, `r`, `epsilon`, `a`, `b`,
    /// `h`).
    pub fn validate(&self) -> Result<(), ParamError> {
        check::length("d", self.d)?;
        check::length("r", self.r)?;
        check::require(
            self.r > self.d,
            "r",
            self.r,
            &format!(
                "must exceed the lattice distance d = {} (0 < d < r)",
                self.d
            ),
            "raise r (the papers use r = 1.2 d) or lower d",
        )?;
        check::within_scale(
            "epsilon",
            self.epsilon,
            "where the σ-norm (√(1 + ε‖z‖²) − 1)/ε loses precision or overflows",
        )?;
        check::finite("h", self.h)?;
        check::require(
            self.h > 0.0 && self.h < 1.0,
            "h",
            self.h,
            "the bump ρ_h needs h in (0, 1)",
            "use e.g. h: 0.2 (the papers' value)",
        )?;
        let why =
            "where the uneven sigmoid's shift c = |a − b|/√(4ab) loses precision or overflows";
        check::within_scale("a", self.a, why)?;
        check::within_scale("b", self.b, why)?;
        check::require(
            self.a <= self.b,
            "a",
            self.a,
            &format!(
                "exceeds b = {}: the uneven sigmoid φ needs 0 < a ≤ b",
                self.b
            ),
            "swap a and b or lower a",
        )
    }
}

impl Default for AlphaParams {
    fn default() -> Self {
        Self::papers(Self::PAPERS_D)
    }
}

/// The α-interaction as a scenario writes it: the parameters of [`AlphaParams`] with the range
/// r optional (default 1.2 d) and the gains c₁^α, c₂^α (1 and 1 give Algorithms 1 and 2 exactly).
/// Every field defaults to the papers' value ([`AlphaParams::default`]).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields, default)
)]
pub struct AlphaConfig {
    /// Lattice distance d > 0.
    pub d: f64,
    /// Interaction range r > d; default 1.2 d.
    pub r: Option<f64>,
    /// σ-norm parameter ε > 0.
    pub epsilon: f64,
    /// Attraction bound a, 0 < a ≤ b.
    pub a: f64,
    /// Repulsion bound b.
    pub b: f64,
    /// Bump parameter h ∈ (0, 1).
    pub h: f64,
    /// Gradient gain c₁^α > 0.
    pub c1: f64,
    /// Consensus gain c₂^α ≥ 0.
    pub c2: f64,
}

impl Default for AlphaConfig {
    fn default() -> Self {
        let p = AlphaParams::default();
        Self {
            d: p.d,
            r: None,
            epsilon: p.epsilon,
            a: p.a,
            b: p.b,
            h: p.h,
            c1: 1.0,
            c2: 1.0,
        }
    }
}

impl AlphaConfig {
    /// The interaction range r (default 1.2 d).
    #[must_use]
    pub fn range(&self) -> f64 {
        self.r.unwrap_or_else(|| AlphaParams::range_for(self.d))
    }

    /// The parameters, r filled in.
    #[must_use]
    pub fn params(&self) -> AlphaParams {
        AlphaParams {
            d: self.d,
            r: self.range(),
            epsilon: self.epsilon,
            a: self.a,
            b: self.b,
            h: self.h,
        }
    }

    /// Checks the parameters ([`AlphaParams::validate`]) and the gains (c₁ > 0, c₂ ≥ 0).
    ///
    /// # Errors
    /// The first value outside its domain, named by its field.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.params().validate()?;
        check_gains(self.c1, self.c2)
    }

    /// The α-interaction of these parameters and gains.
    ///
    /// # Errors
    /// As [`AlphaConfig::validate`].
    pub fn interaction(&self) -> Result<AlphaInteraction, ParamError> {
        AlphaInteraction::new(self.params(), self.c1, self.c2)
    }
}

/// The gains of the α-interaction: c₁^α > 0, c₂^α ≥ 0.
fn check_gains(c1: f64, c2: f64) -> Result<(), ParamError> {
    check::positive("c1", c1)?;
    check::finite("c2", c2)?;
    check::not_huge("c2", c2)?;
    check::require(
        c2 >= 0.0,
        "c2",
        c2,
        "a negative consensus gain amplifies velocity mismatch",
        "use c2 ≥ 0",
    )
}

/// u_i^α = c₁ Σ_{j∈N_i} φ_α(‖q_j − q_i‖_σ) n_ij + c₂ Σ_{j∈N_i} a_ij(q)(p_j − p_i),
/// n_ij = σ_ε(q_j − q_i), a_ij = ρ_h(‖q_j − q_i‖_σ / r_α) (TAC 2006 eq. 23; Algorithm 3's u^α with
/// gains c₁^α, c₂^α; c₁ = c₂ = 1 gives Algorithm 1 exactly).
#[derive(Clone, Debug, PartialEq)]
pub struct AlphaInteraction {
    params: AlphaParams,
    sigma: SigmaNorm,
    action: BumpedAction,
    c1: f64,
    c2: f64,
}

impl AlphaInteraction {
    /// The interaction with gains c₁ (gradient) and c₂ (consensus).
    ///
    /// # Example
    /// ```
    /// use flock_protocols::{AlphaInteraction, AlphaParams};
    ///
    /// let alpha = AlphaInteraction::new(AlphaParams::default(), 1.0, 1.0).unwrap();
    /// assert_eq!(alpha.params().r, 8.4);
    /// // r ≤ d is refused with the field at fault
    /// let bad = AlphaParams { r: 7.0, ..AlphaParams::default() };
    /// assert_eq!(AlphaInteraction::new(bad, 1.0, 1.0).unwrap_err().field, "r");
    /// ```
    ///
    /// # Errors
    /// Parameters outside their domain ([`AlphaParams::validate`]), c₁ ≤ 0 or c₂ < 0 (or either
    /// not finite).
    pub fn new(params: AlphaParams, c1: f64, c2: f64) -> Result<Self, ParamError> {
        params.validate()?;
        check_gains(c1, c2)?;
        let sigma = SigmaNorm::new(params.epsilon);
        let action = BumpedAction::alpha(
            UnevenSigmoid::new(params.a, params.b),
            Bump::tac(params.h),
            sigma.of_length(params.d),
            sigma.of_length(params.r),
        );
        Ok(Self {
            params,
            sigma,
            action,
            c1,
            c2,
        })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &AlphaParams {
        &self.params
    }

    /// The action function φ_α and its potential ψ_α.
    #[must_use]
    pub const fn action(&self) -> &BumpedAction {
        &self.action
    }

    /// The gradient gain c₁^α.
    #[must_use]
    pub const fn c1(&self) -> f64 {
        self.c1
    }

    /// u_i^α for agent `i`; the σ-norm, n_ij and a_ij of each pair share one square root and one cosine.
    ///
    /// [`AlphaInteraction::inputs`] gives the same values for all agents at once, at about half the
    /// cost.
    #[must_use]
    pub fn input<V: Vector>(&self, i: usize, q: &[V], p: &[V], net: &ProximityNet) -> V {
        let neighbours = net.graph().neighbours(i).iter().map(|&j| j as usize);
        self.sum(q[i], p[i], neighbours.map(|j| (q[j], p[j])))
    }

    /// u_i^α of an agent at (q_i, p_i) from the states `others` = (q_j, p_j) it perceives, summed
    /// in their order; agents beyond r add exactly zero (a_ij = φ_α = 0 there). With the exact
    /// states of its neighbours in list order, the bits of [`AlphaInteraction::input`].
    #[must_use]
    pub fn local_input<V: Vector>(
        &self,
        own: &crate::Perceived<V>,
        others: &[crate::Perceived<V>],
    ) -> V {
        let others = others.iter().map(|o| (o.position, o.velocity));
        self.sum(own.position, own.velocity, others)
    }

    /// [`AlphaInteraction::local_input`] of each receiver of `block`, bit for bit, into `out`.
    /// The pairs of all the receivers go through one run of fours, so a receiver's last pairs
    /// share a vector cosine with the next one's first instead of leaving lanes empty; each
    /// receiver's sums still start at zero and add its terms in its list's order.
    pub fn local_inputs<V: Vector>(&self, block: crate::Perceptions<'_, V>, out: &mut [V]) {
        let finish = |g: V, c: V| g * self.c1 + c * self.c2;
        out.fill(finish(V::ZERO, V::ZERO));
        let pairs = block.receivers().enumerate().flat_map(|(r, (own, heard))| {
            heard
                .iter()
                .map(move |o| (r, own.position, own.velocity, o.position, o.velocity))
        });
        let (mut current, mut gradient, mut consensus) = (None, V::ZERO, V::ZERO);
        self.for_each_term(pairs, |r, g, c| {
            if current != Some(r) {
                if let Some(done) = current {
                    out[done] = finish(gradient, consensus);
                }
                (current, gradient, consensus) = (Some(r), V::ZERO, V::ZERO);
            }
            gradient += g;
            consensus += c;
        });
        if let Some(done) = current {
            out[done] = finish(gradient, consensus);
        }
    }

    /// c₁ Σ_j φ_α(‖q_j − q_i‖_σ) n_ij + c₂ Σ_j a_ij (p_j − p_i) over `others` in their order.
    #[inline]
    fn sum<V: Vector>(&self, qi: V, pi: V, others: impl Iterator<Item = (V, V)>) -> V {
        let mut gradient = V::ZERO;
        let mut consensus = V::ZERO;
        let pairs = others.map(|(qj, pj)| ((), qi, pi, qj, pj));
        self.for_each_term(pairs, |(), g, c| {
            gradient += g;
            consensus += c;
        });
        gradient * self.c1 + consensus * self.c2
    }

    /// `apply(key, g, c)` for each pair `(key, q_i, p_i, q_j, p_j)` in their order, with the two
    /// terms agent i receives from neighbour j: g = φ_α(‖q_j − q_i‖_σ) n_ij and
    /// c = a_ij (p_j − p_i).
    ///
    /// The pairs are taken four at a time: their σ-norms one by one, then φ_α and a_ij of the four
    /// with one vector cosine ([`BumpedAction::actions_and_bumps`]); the last, shorter run goes
    /// through the same call with the lanes it does not fill left as they were. A lane is a
    /// function of its own argument only, so a pair's terms are the same bits wherever it falls
    /// in a run, whatever the other pairs, the thread count or the storage order.
    ///
    /// Swapping i and j negates both terms exactly: IEEE subtraction is antisymmetric (up to the
    /// sign of an exact zero), ‖·‖² and hence the scalar factors are the same bits, and so is the
    /// product of a negated vector.
    #[inline]
    fn for_each_term<V: Vector, K: Copy + Default>(
        &self,
        pairs: impl Iterator<Item = (K, V, V, V, V)>,
        mut apply: impl FnMut(K, V, V),
    ) {
        let mut keys = [K::default(); 4];
        let mut dq = [V::ZERO; 4];
        let mut dp = [V::ZERO; 4];
        let mut filled = 0;
        let mut flush = |keys: &[K; 4], dq: &[V; 4], dp: &[V; 4], filled: usize| {
            let norms = dq.map(|d| self.sigma.norm_and_gradient_scale(d.length_squared()));
            let (phi, a) = self.action.actions_and_bumps(norms.map(|(z, _)| z));
            for k in 0..filled {
                apply(keys[k], dq[k] * (phi[k] * norms[k].1), dp[k] * a[k]);
            }
        };
        for (key, qi, pi, qj, pj) in pairs {
            keys[filled] = key;
            dq[filled] = qj - qi;
            dp[filled] = pj - pi;
            filled += 1;
            if filled == 4 {
                flush(&keys, &dq, &dp, 4);
                filled = 0;
            }
        }
        if filled > 0 {
            flush(&keys, &dq, &dp, filled);
        }
    }

    /// `out[i] = finish(i, u_i^α)` for every agent, with u_i^α bit-identical to
    /// [`AlphaInteraction::input`]`(i, ..)`, for any thread count.
    ///
    /// Each undirected edge's terms are computed once where possible (one σ-norm and one cosine
    /// instead of two), and each agent still sums its terms over its neighbours in ascending order,
    /// as [`AlphaInteraction::input`] does. The agents are cut into chunks of consecutive indices
    /// (in parallel with the `parallel` feature); a chunk
    ///
    /// 1. starts each sum with the neighbours below the chunk (computed here, their chunk computes
    ///    them again for itself);
    /// 2. sweeps its agents i in ascending order: each pair {i, j} with j > i is computed once,
    ///    added to i's sums and subtracted from j's (j > i is still below j's own upper
    ///    neighbours, and the lower neighbours of j inside the chunk come in ascending order);
    ///    j beyond the chunk gets nothing (its chunk computes the pair in step 1).
    ///
    /// Sums start at +0 and so never hold −0: a term that differs only in the sign of an exact
    /// zero (when q_j and q_i share a coordinate) leaves them unchanged. The saving therefore
    /// needs neighbours close in index (agents indexed roughly in space); with random indices,
    /// most pairs are computed twice, as by [`AlphaInteraction::input`].
    ///
    /// For a net with a [`Numbering`](flock_graph::Numbering) other than the identity (agents
    /// stored in space order by a simulation (`flock_sim::Simulation`)), the lists are in ascending
    /// original index, not storage index, so the sweep's order does not apply. In 2D the agents
    /// are cut into chunks of 16,384 storage indices instead; a chunk computes each pair
    /// inside it once and keeps both directions' terms (the second negated) in a buffer aligned
    /// with its edges, each pair leaving the chunk directly, then sums every agent's terms in list
    /// order, as [`AlphaInteraction::input`] does. The pairs are listed, and each one's reverse
    /// edge found, without branching on the agents' indices, which are unrelated to their places
    /// (measured: 2D, 10⁶ agents at random, one thread, 170 → 139 ms per plain step), in buffers
    /// each thread keeps from one chunk to the next. In 3D such a chunk of agents in cell order is
    /// a thin slab that most pairs leave, and each agent's terms are computed directly as by
    /// [`AlphaInteraction::input`], in parallel (measured ≈ 8 % faster at 10⁶ agents).
    ///
    /// `net` must be the net of `q` (any symmetric graph works); `q`, `p` and `out` have one
    /// entry per agent, in the net's storage order.
    pub fn inputs<V: Vector>(
        &self,
        q: &[V],
        p: &[V],
        net: &ProximityNet,
        out: &mut [V],
        finish: impl Fn(usize, V) -> V + Sync,
    ) {
        // an interrupt that cuts the step short leaves the chunks not yet begun
        if net.numbering().is_identity() {
            let chunk = sweep_chunk(out.len());
            for_each_chunk_mut(out, chunk, |c, out| {
                if !cuts_short() {
                    self.sweep(c * chunk, q, p, net, out, &finish);
                }
            });
        } else if V::DIM == 2 {
            for_each_chunk_mut_with(out, PAIRED_CHUNK, Paired::default, |c, out, scratch| {
                if !cuts_short() {
                    self.paired(c * PAIRED_CHUNK, q, p, net, out, &finish, scratch);
                }
            });
        } else {
            fill_interruptible(out, |i| finish(i, self.input(i, q, p, net)));
        }
    }

    /// [`AlphaInteraction::inputs`] for the chunk of agents `start..start + out.len()` of a net
    /// whose lists follow a numbering: each pair inside the chunk computed once (by its agent of
    /// lower storage index), its terms kept for both directions; each agent's terms then summed
    /// in list order. Negating a term changes at most the sign of an exact zero, which a sum
    /// starting at +0 never keeps, so the sums are the bits of [`AlphaInteraction::input`].
    #[allow(clippy::too_many_arguments)]
    fn paired<V: Vector>(
        &self,
        start: usize,
        q: &[V],
        p: &[V],
        net: &ProximityNet,
        out: &mut [V],
        finish: &impl Fn(usize, V) -> V,
        scratch: &mut Paired<V>,
    ) {
        let graph = net.graph();
        let chunk = start..start + out.len();
        let base = graph.offsets()[chunk.start];
        let edges = graph.offsets()[chunk.end] - base;
        let Paired { terms, pairs } = scratch;
        // one more term than edges: where a pair leaving the chunk writes its reverse term
        terms.resize(edges + 1, (V::ZERO, V::ZERO));
        // each pair once, by its agent of lower storage index when both are in the chunk; the
        // pairs are listed without branching on which (agents at random make it unpredictable)
        let first = chunk.start;
        pairs.resize(edges, (0, 0, 0));
        let mut len = 0;
        for i in chunk.clone() {
            for (e, &j) in graph.edge_range(i).zip(graph.neighbours(i)) {
                // i < n ≤ u32::MAX, as in a net
                pairs[len] = (e, i as u32, j);
                len += usize::from(!(first..i).contains(&(j as usize)));
            }
        }
        let pairs = pairs[..len].iter().map(|&(e, i, j)| {
            let (i, j) = (i as usize, j as usize);
            ((i, e, j), q[i], p[i], q[j], p[j])
        });
        self.for_each_term(pairs, |(i, e, j), g, c| {
            terms[e - base] = (g, c);
            // the reverse edge: i's place in j's list, found without branching on it
            debug_assert!(
                graph.neighbours(j).contains(&(i as u32)),
                "lists are symmetric"
            );
            let back = graph.edge_range(j).zip(graph.neighbours(j));
            let back = back
                .map(|(f, &k)| if k as usize == i { f } else { 0 })
                .sum::<usize>();
            let inside = j > i && j < chunk.end;
            terms[if inside { back - base } else { edges }] = (-g, -c);
        });
        for (u, i) in out.iter_mut().zip(chunk) {
            let edges = graph.edge_range(i);
            let (mut gradient, mut consensus) = (V::ZERO, V::ZERO);
            for &(g, c) in &terms[edges.start - base..edges.end - base] {
                gradient += g;
                consensus += c;
            }
            *u = finish(i, gradient * self.c1 + consensus * self.c2);
        }
    }

    /// [`AlphaInteraction::inputs`] for the chunk of agents `start..start + out.len()`.
    fn sweep<V: Vector>(
        &self,
        start: usize,
        q: &[V],
        p: &[V],
        net: &ProximityNet,
        out: &mut [V],
        finish: &impl Fn(usize, V) -> V,
    ) {
        let graph = net.graph();
        let end = start + out.len();
        // `out` holds the gradient sums until the end.
        out.fill(V::ZERO);
        let mut consensus = vec![V::ZERO; out.len()];
        let state = |(i, j): (usize, usize)| ((i, j), q[i], p[i], q[j], p[j]);
        let below = (start..end).flat_map(|i| {
            let neighbours = graph.neighbours(i);
            let below = neighbours.partition_point(|&j| (j as usize) < start);
            neighbours[..below].iter().map(move |&j| (i, j as usize))
        });
        self.for_each_term(below.map(state), |(i, _), g, c| {
            out[i - start] += g;
            consensus[i - start] += c;
        });
        let above = (start..end).flat_map(|i| {
            let neighbours = graph.neighbours(i);
            let upper = neighbours.partition_point(|&j| (j as usize) < i);
            neighbours[upper..].iter().map(move |&j| (i, j as usize))
        });
        self.for_each_term(above.map(state), |(i, j), g, c| {
            out[i - start] += g;
            consensus[i - start] += c;
            if j < end {
                out[j - start] -= g;
                consensus[j - start] -= c;
            }
        });
        for (k, (u, &c)) in out.iter_mut().zip(&consensus).enumerate() {
            *u = finish(start + k, *u * self.c1 + c * self.c2);
        }
    }

    /// The collective potential V(q) = ½ Σ_i Σ_{j≠i} ψ_α(‖q_j − q_i‖_σ) (TAC 2006 eq. 20), shifted by
    /// the constant of a fully dispersed group so that it is O(|E|): pairs out of range contribute
    /// ψ_α(r_α) each, and we sum ψ_α(z) − ψ_α(r_α) over the net's edges only. Gradients and Ḣ are
    /// unchanged; V = 0 when no two agents interact. Each pair is taken once, by the agent of lower
    /// original index, whose pairs are summed in list order; the agents' sums are added in original
    /// order ([`Numbering::ordered_sum`](flock_graph::Numbering::ordered_sum)), so the bits do not
    /// depend on how the agents are stored.
    #[must_use]
    pub fn potential<V: Vector>(&self, q: &[V], net: &ProximityNet) -> f64 {
        let far = self.action.potential(self.action.range());
        let (graph, numbering) = (net.graph(), net.numbering());
        numbering.ordered_sum(graph.len(), |i| {
            let k = numbering.original(i);
            let mut total = 0.0;
            for &j in graph.neighbours(i) {
                let j = j as usize;
                if numbering.original(j) > k {
                    let z = self.sigma.norm(q[j] - q[i]);
                    total += self.action.potential(z) - far;
                }
            }
            total
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use flock_graph::NeighbourSearch;
    use glam::DVec2;
    use rand::{RngExt, SeedableRng};
    use rand_pcg::Pcg64;

    /// 20,000 agents with about 6 neighbours apiece: uniform in a square (numbered at random), or
    /// the same points sorted by rows (numbered along space).
    fn swarm(sorted: bool) -> (Vec<DVec2>, Vec<DVec2>) {
        let mut rng = Pcg64::seed_from_u64(11);
        let mut q: Vec<DVec2> = (0..20_000)
            .map(|_| DVec2::new(rng.random::<f64>() * 860.0, rng.random::<f64>() * 860.0))
            .collect();
        if sorted {
            q.sort_by(|a, b| {
                ((a.y / 8.4).floor(), a.x)
                    .partial_cmp(&((b.y / 8.4).floor(), b.x))
                    .unwrap()
            });
        }
        let p = (0..q.len())
            .map(|_| DVec2::new(rng.random::<f64>() - 0.5, rng.random::<f64>() - 0.5))
            .collect();
        (q, p)
    }

    /// The inputs of agents stored along space (rows), at random, and at random but stored by
    /// cell with their numbering (the direct path) are the bits of `input` on the agents in
    /// original order, with `finish` applied to the right agent, on one thread and on three; the
    /// potential too.
    #[test]
    fn every_path_of_inputs_is_bit_identical_to_input() {
        let alpha =
            AlphaInteraction::new(AlphaParams::default(), 1.0, 1.0).expect("valid α-parameters");
        let r = alpha.params().r;
        let finish = |k: usize, u: DVec2| u * 3.0 + DVec2::new(k as f64, 0.5);
        let bits = |u: DVec2| u.to_array().map(f64::to_bits);
        for sorted in [false, true] {
            let (q, p) = swarm(sorted);
            let mut search = NeighbourSearch::new();
            let mut net = ProximityNet::without_distances();
            search.build(&q, r, &mut net);
            assert_eq!(net.is_scattered(), !sorted);
            let expected: Vec<[u64; 2]> = (0..q.len())
                .map(|k| bits(finish(k, alpha.input(k, &q, &p, &net))))
                .collect();
            // the same agents stored by cell
            let order = search.cell_order(&q, r).to_vec();
            let stored =
                |x: &[DVec2]| -> Vec<DVec2> { order.iter().map(|&k| x[k as usize]).collect() };
            let (q_s, p_s) = (stored(&q), stored(&p));
            let mut numbered = ProximityNet::without_distances();
            numbered.permute(&order);
            search.build(&q_s, r, &mut numbered);
            assert!(!numbered.is_scattered());
            assert_eq!(
                alpha.potential(&q_s, &numbered).to_bits(),
                alpha.potential(&q, &net).to_bits()
            );
            for threads in [1, 3] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let mut out = vec![DVec2::ZERO; q.len()];
                pool.install(|| alpha.inputs(&q, &p, &net, &mut out, finish));
                let got: Vec<[u64; 2]> = out.iter().map(|&u| bits(u)).collect();
                assert!(got == expected, "sorted {sorted}, {threads} threads");
                let renumbered = |s: usize, u| finish(order[s] as usize, u);
                pool.install(|| alpha.inputs(&q_s, &p_s, &numbered, &mut out, renumbered));
                let got: Vec<[u64; 2]> =
                    stored_back(&order, &out).iter().map(|&u| bits(u)).collect();
                assert!(got == expected, "stored by cell, {threads} threads");
            }
        }
    }

    /// A pair's terms are the same bits wherever it falls in a run of four pairs (first, last, or
    /// in the short run at the end) and whatever pairs share its run: pairs in the flat part of
    /// ρ_h, across its cosine part, at r and beyond, each alone and behind 0–3 others.
    #[test]
    fn a_pairs_terms_do_not_depend_on_its_place_in_a_run() {
        let alpha =
            AlphaInteraction::new(AlphaParams::default(), 1.0, 1.0).expect("valid α-parameters");
        let mut q = vec![DVec2::new(1.0, -2.0)];
        let mut p = vec![DVec2::new(0.3, 0.1)];
        for (k, distance) in [0.5, 1.5, 3.0, 5.5, 7.0, 8.0, 8.39, 8.4, 9.0, 12.0]
            .into_iter()
            .enumerate()
        {
            let angle = 0.7 * k as f64;
            q.push(q[0] + DVec2::new(angle.cos(), angle.sin()) * distance);
            p.push(DVec2::new(0.2 * k as f64, -0.1));
        }
        let terms = |run: &[(usize, usize)]| {
            let mut out = Vec::new();
            let pairs = run.iter().map(|&(i, j)| ((i, j), q[i], p[i], q[j], p[j]));
            alpha.for_each_term(pairs, |key, g: DVec2, c: DVec2| {
                out.push((
                    key,
                    g.to_array().map(f64::to_bits),
                    c.to_array().map(f64::to_bits),
                ));
            });
            out
        };
        let pairs: Vec<(usize, usize)> = (1..q.len()).map(|j| (0, j)).collect();
        let alone: Vec<_> = pairs.iter().map(|&pair| terms(&[pair])[0]).collect();
        assert!(
            alone.iter().any(|(_, g, _)| g[0] != 0),
            "some pairs interact"
        );
        let reversed: Vec<(usize, usize)> = pairs.iter().map(|&(i, j)| (j, i)).rev().collect();
        for lead in 0..4 {
            for (others, ours) in [(&reversed, &pairs), (&pairs, &reversed)] {
                let run: Vec<(usize, usize)> = others[..lead].iter().chain(ours).copied().collect();
                let expected: Vec<_> = ours.iter().map(|&pair| terms(&[pair])[0]).collect();
                assert_eq!(terms(&run)[lead..], expected[..], "behind {lead} pairs");
            }
        }
    }

    /// `x` (in storage order `order`) in original order.
    fn stored_back(order: &[u32], x: &[DVec2]) -> Vec<DVec2> {
        let mut back = vec![DVec2::NAN; x.len()];
        for (&k, &v) in order.iter().zip(x) {
            back[k as usize] = v;
        }
        back
    }
}
