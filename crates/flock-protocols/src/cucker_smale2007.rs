//! The Cucker–Smale model (F. Cucker and S. Smale, "Emergent behavior in flocks", IEEE TAC 52(5),
//! 2007): velocity alignment weighted by a kernel that decays with distance but never vanishes.

use flock_graph::ProximityNet;
use flock_math::parallel::fill_interruptible;
use flock_math::{Domain, Vector, mean_of};

use crate::error::{ParamError, check};
use crate::swarm::kinetic;
use crate::{LocalForm, Perceived, Protocol, Swarm};

/// ṗ_i = (λ/N) Σ_j ψ(‖q_j − q_i‖)(p_j − p_i) with ψ(r) = K/(σ² + r²)^β.
///
/// Cucker & Smale (2007) write the adjacency a_ij = H/(1 + ‖x_i − x_j‖²)^β (their eq. 2 with
/// σ = 1); the λ/N normalisation and the kernel with σ are those of Ha & Liu ("A simple proof of
/// the Cucker–Smale flocking dynamics and mean-field limit", Commun. Math. Sci. 7(2), 2009, eq. 1.1).
/// Their theorem: for β < 1/2 the velocities converge to the initial mean from any initial state
/// (unconditional flocking, Cucker & Smale 2007 Theorem 1; Ha & Liu 2009 Theorem 3.2), the
/// positions staying within a bounded distance; for β ≥ 1/2 flocking depends on the initial state.
///
/// All pairs interact (the sum is over every agent, O(n²) per step), unless a cut-off `range` is
/// given: ψ is then 0 beyond it (a truncated kernel, no longer the paper's; the model then has a
/// local form and runs under every perception condition). The mean velocity is invariant (the
/// sum of the inputs is 0, ψ symmetric) and the velocity mismatch ½ Σ ‖p_i − p̄‖²
/// ([`Protocol::energy`]) does not increase.
///
/// # Example
/// ```
/// use flock_graph::ProximityNet;
/// use flock_math::Domain;
/// use flock_protocols::{CuckerSmale, CuckerSmaleParams, Protocol, Swarm};
/// use glam::DVec2;
///
/// let q = vec![DVec2::ZERO, DVec2::new(30.0, 0.0)];
/// let p = vec![DVec2::new(1.0, 0.0), DVec2::new(-1.0, 2.0)];
/// let model = CuckerSmale::new(CuckerSmaleParams::with_beta(0.25), 8.4, 2, Domain::Open)?;
/// let mut u = vec![DVec2::ZERO; 2];
/// model.controls(0.0, &Swarm::new(q, p.clone()), &ProximityNet::new(), &mut u);
/// // each pulled towards the other's velocity, the mean velocity kept (aligned at the mean
/// // (0, 1) by flock-sim's test `cucker_smale_aligns_at_the_mean`)
/// assert_eq!(u[0], -u[1]);
/// assert!(u[0].dot(p[1] - p[0]) > 0.0);
/// # Ok::<(), flock_protocols::ParamError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CuckerSmale<V> {
    params: CuckerSmaleParams,
    range: f64,
    agents: usize,
    domain: Domain<V>,
}

/// The parameters of the Cucker–Smale model, as a scenario writes them (`beta` must be given,
/// the others default to [`CuckerSmaleParams::with_beta`]'s).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
pub struct CuckerSmaleParams {
    /// The coupling λ > 0.
    #[cfg_attr(
        feature = "serde",
        serde(default = "CuckerSmaleParams::default_lambda")
    )]
    pub lambda: f64,
    /// The kernel's scale K > 0.
    #[cfg_attr(feature = "serde", serde(default = "CuckerSmaleParams::default_k"))]
    pub k: f64,
    /// The kernel's offset σ > 0.
    #[cfg_attr(feature = "serde", serde(default = "CuckerSmaleParams::default_sigma"))]
    pub sigma: f64,
    /// The kernel's decay β ≥ 0 (unconditional flocking for β < 1/2).
    pub beta: f64,
    /// A cut-off of ψ beyond which pairs do not interact; `None` (the paper): every pair.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub cutoff: Option<f64>,
}

impl CuckerSmaleParams {
    /// The paper's model (λ = K = σ = 1, every pair) with decay `beta`.
    #[must_use]
    pub const fn with_beta(beta: f64) -> Self {
        Self {
            lambda: 1.0,
            k: 1.0,
            sigma: 1.0,
            beta,
            cutoff: None,
        }
    }

    #[cfg(feature = "serde")]
    const fn default_lambda() -> f64 {
        Self::with_beta(0.0).lambda
    }

    #[cfg(feature = "serde")]
    const fn default_k() -> f64 {
        Self::with_beta(0.0).k
    }

    #[cfg(feature = "serde")]
    const fn default_sigma() -> f64 {
        Self::with_beta(0.0).sigma
    }
}

impl<V: Vector> CuckerSmale<V> {
    /// The model of `agents` agents in `domain`; `range` is the radius of the proximity net the
    /// simulation measures connectivity on (the cut-off instead, when one is given).
    ///
    /// # Errors
    /// A parameter outside its domain, named `lambda`, `k`, `sigma`, `beta`, `cutoff` or `range`.
    pub fn new(
        params: CuckerSmaleParams,
        range: f64,
        agents: usize,
        domain: Domain<V>,
    ) -> Result<Self, ParamError> {
        check::positive("lambda", params.lambda)?;
        check::positive("k", params.k)?;
        check::positive("sigma", params.sigma)?;
        check::non_negative("beta", params.beta)?;
        check::positive("range", range)?;
        if let Some(c) = params.cutoff {
            check::positive("cutoff", c)?;
        }
        Ok(Self {
            params,
            range: params.cutoff.unwrap_or(range),
            agents: agents.max(1),
            domain,
        })
    }

    /// The kernel ψ(r) = K/(σ² + r²)^β of the squared distance r².
    #[inline]
    #[must_use]
    pub fn psi(&self, r2: f64) -> f64 {
        let CuckerSmaleParams { k, sigma, beta, .. } = self.params;
        k / (sigma * sigma + r2).powf(beta)
    }

    /// ψ(‖q_j − q_i‖)(p_j − p_i) of one pair, 0 beyond the cut-off.
    #[inline]
    fn pair(&self, qi: V, pi: V, qj: V, pj: V) -> V {
        let r2 = self.domain.displacement(qi, qj).length_squared();
        if self.params.cutoff.is_some_and(|c| r2 >= c * c) {
            return V::ZERO;
        }
        (pj - pi) * self.psi(r2)
    }
}

impl<V: Vector> Protocol<V> for CuckerSmale<V> {
    fn interaction_range(&self) -> f64 {
        self.range
    }

    fn uses_net_distances(&self) -> bool {
        false
    }

    /// (λ/N) Σ_j ψ(‖q_j − q_i‖)(p_j − p_i), j over every agent in ascending index (over the net's
    /// neighbours within the cut-off, when one is given).
    fn controls(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let (q, p) = (&swarm.positions, &swarm.velocities);
        let scale = self.params.lambda / self.agents as f64;
        fill_interruptible(inputs, |i| {
            let mut total = V::ZERO;
            if self.params.cutoff.is_some() {
                for &j in net.graph().neighbours(i) {
                    let j = j as usize;
                    total += self.pair(q[i], p[i], q[j], p[j]);
                }
            } else {
                for j in (0..q.len()).filter(|&j| j != i) {
                    total += self.pair(q[i], p[i], q[j], p[j]);
                }
            }
            total * scale
        });
    }

    /// The velocity mismatch ½ Σ_i ‖p_i − p̄‖², non-increasing along the flow.
    fn energy(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        let numbering = net.numbering();
        let p_bar = mean_of(numbering.ordered(&swarm.velocities));
        kinetic(&swarm.velocities, numbering, p_bar)
    }

    /// With a cut-off: each agent's sum runs over its list in ascending original index. The
    /// paper's all-to-all sum runs over every agent in storage order, so it keeps its agents in
    /// original order.
    fn follows_numbering(&self) -> bool {
        self.params.cutoff.is_some()
    }

    fn measures_in_domain(&self) -> bool {
        true
    }

    /// With a cut-off only: the paper's all-to-all sum needs every agent's state, which no
    /// communication range delivers.
    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        self.params.cutoff.map(|_| self as &dyn LocalForm<V>)
    }
}

/// (λ/N) Σ ψ(‖q_j − q_i‖)(p_j − p_i) over the agents heard within the cut-off, N the size of the
/// flock as the agent knows it (unchanged by what it hears).
impl<V: Vector> LocalForm<V> for CuckerSmale<V> {
    fn local_input(&self, _t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        let mut total = V::ZERO;
        for o in heard {
            total += self.pair(own.position, own.velocity, o.position, o.velocity);
        }
        total * (self.params.lambda / self.agents as f64)
    }
}
