//! The Vicsek model (T. Vicsek, A. Czirók, E. Ben-Jacob, I. Cohen and O. Shochet, "Novel type of
//! phase transition in a system of self-driven particles", PRL 75(6), 1226, 1995): constant
//! speed, the heading of the neighbours plus uniform angular noise.

use flock_graph::ProximityNet;
use flock_math::parallel::fill_interruptible;
use flock_math::{Domain, Vector};

use crate::error::{ParamError, check};
use crate::swarm::heading_mismatch;
use crate::{LocalForm, Perceived, Protocol, Swarm, Update};
use flock_math::stream::{Purpose, Streams};

/// The parameters of the Vicsek model, as a scenario writes them (the paper's names; `eta` must
/// be given, the others default to [`VicsekParams::with_eta`]'s).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
pub struct VicsekParams {
    /// The speed v₀ > 0 of every particle (the paper's Fig. 2: v₀ = 0.03).
    #[cfg_attr(feature = "serde", serde(default = "VicsekParams::default_v0"))]
    pub v0: f64,
    /// The interaction radius r > 0 (the paper's unit: r = 1).
    #[cfg_attr(feature = "serde", serde(default = "VicsekParams::default_r"))]
    pub r: f64,
    /// The noise amplitude η ∈ [0, 2π]: Δθ uniform in [−η/2, η/2].
    pub eta: f64,
}

impl VicsekParams {
    /// The paper's model (its Fig. 2: v₀ = 0.03, in units of r = 1) with noise amplitude `eta`.
    #[must_use]
    pub const fn with_eta(eta: f64) -> Self {
        Self {
            v0: 0.03,
            r: 1.0,
            eta,
        }
    }

    #[cfg(feature = "serde")]
    const fn default_v0() -> f64 {
        Self::with_eta(0.0).v0
    }

    #[cfg(feature = "serde")]
    const fn default_r() -> f64 {
        Self::with_eta(0.0).r
    }
}

/// θ_i(t + Δt) = ⟨θ(t)⟩_r + Δθ and x_i(t + Δt) = x_i(t) + v_i(t) Δt, v_i = v₀ (cos θ_i, sin θ_i)
/// (Vicsek et al. 1995, eq. 1–2; the step h is the paper's Δt = 1).
///
/// ⟨θ(t)⟩_r is the direction of the mean velocity of the particles within r of particle i, i
/// itself included, arctan(⟨sin θ⟩_r / ⟨cos θ⟩_r) taken in the right quadrant (atan2); Δθ is
/// uniform in [−η/2, η/2], drawn per particle and step from the run's keyed streams
/// ([`Purpose::ModelNoise`]), so a run is bit-identical whatever the thread count and after a
/// resume. The output u_i is the new velocity, applied after the move ([`Update::MoveThenTurn`]).
/// The paper's order parameter is v_a = ‖Σ v_i‖ / (N v₀) (the `polarisation` of the metrics).
///
/// The paper's model is planar: a 3D run is refused (its 3D form, Czirók, Vicsek & Vicsek 1999,
/// draws the noise on the sphere and is not built here).
#[derive(Clone, Debug, PartialEq)]
pub struct Vicsek<V> {
    params: VicsekParams,
    step: f64,
    streams: Streams,
    domain: Domain<V>,
}

impl<V: Vector> Vicsek<V> {
    /// The model with step `step` (the paper's Δt), its noise drawn from the streams of `seed`,
    /// in `domain` (the paper's: a periodic square).
    ///
    /// # Errors
    /// A space of other than two dimensions (`dim`), `v0`, `r` or `step` not positive and
    /// finite, `eta` outside [0, 2π].
    pub fn new(
        params: VicsekParams,
        step: f64,
        seed: u64,
        domain: Domain<V>,
    ) -> Result<Self, ParamError> {
        planar("the Vicsek model", V::DIM)?;
        check::positive("v0", params.v0)?;
        check::positive("r", params.r)?;
        check::positive("step", step)?;
        check::non_negative("eta", params.eta)?;
        check::require(
            params.eta <= core::f64::consts::TAU,
            "eta",
            params.eta,
            "is above 2π (the noise interval [−η/2, η/2] would wrap past a full turn)",
            "give η in [0, 2π]; η = 2π is already uniform over every direction",
        )?;
        Ok(Self {
            params,
            step,
            streams: Streams::new(seed),
            domain,
        })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> VicsekParams {
        self.params
    }

    /// The noise Δθ of agent `i` at time `t`.
    fn noise(&self, i: u32, t: f64) -> f64 {
        let k = (t / self.step).round() as u64;
        let u = self
            .streams
            .draws(Purpose::ModelNoise, u64::from(i), k)
            .uniform();
        self.params.eta * (u - 0.5)
    }

    /// v₀ (cos θ, sin θ) with θ = arg(own + Σ others) + Δθ; own heading when the sum vanishes.
    fn heading(&self, i: u32, t: f64, own: V, sum: V) -> V {
        let mean = if sum == V::ZERO { own } else { sum };
        let theta = mean.coord(1).atan2(mean.coord(0)) + self.noise(i, t);
        let (sin, cos) = theta.sin_cos();
        V::from_fn(|k| if k == 0 { cos } else { sin }) * self.params.v0
    }
}

impl<V: Vector> Protocol<V> for Vicsek<V> {
    fn interaction_range(&self) -> f64 {
        self.params.r
    }

    fn uses_net_distances(&self) -> bool {
        false
    }

    /// Each particle's new velocity from the velocities of its neighbours within r (the net's
    /// edges, ascending original index) and its own, its noise keyed by its original index.
    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let p = &swarm.velocities;
        let numbering = net.numbering();
        fill_interruptible(inputs, |i| {
            let mut sum = p[i];
            for &j in net.graph().neighbours(i) {
                sum += p[j as usize];
            }
            self.heading(numbering.original(i) as u32, t, p[i], sum)
        });
    }

    /// The sums run over each particle's list in ascending original index and the noise is
    /// keyed by original index: particles at random are stored by cell.
    fn follows_numbering(&self) -> bool {
        true
    }

    /// The heading mismatch n − ‖Σ_i p̂_i‖ (p̂_i = p_i/‖p_i‖): the model decreases no
    /// energy.
    fn energy(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        heading_mismatch(&swarm.velocities, net.numbering())
    }

    fn update(&self) -> Update {
        Update::MoveThenTurn
    }

    fn measures_in_domain(&self) -> bool {
        true
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }
}

/// The new velocity from the velocities heard within r (by their perceived minimum-image
/// distance) and the agent's own.
impl<V: Vector> LocalForm<V> for Vicsek<V> {
    fn local_input(&self, t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        let r2 = self.params.r * self.params.r;
        let mut sum = own.velocity;
        for o in heard {
            if self
                .domain
                .displacement(own.position, o.position)
                .length_squared()
                < r2
            {
                sum += o.velocity;
            }
        }
        self.heading(own.agent, t, own.velocity, sum)
    }
}

/// The dimension check of a planar model: `Ok` in 2D.
///
/// # Errors
/// `dim` other than 2, naming the model.
pub fn planar(model: &str, dim: usize) -> Result<(), ParamError> {
    check::require(
        dim == 2,
        "dim",
        dim,
        &format!("is not 2, and {model} is a planar model"),
        "set dim: 2",
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    #[test]
    fn noise_is_uniform_in_the_interval() {
        let model = Vicsek::<DVec2>::new(
            VicsekParams {
                v0: 0.03,
                r: 1.0,
                eta: 2.0,
            },
            1.0,
            5,
            Domain::Open,
        )
        .unwrap();
        let draws: Vec<f64> = (0..20_000).map(|k| model.noise(3, f64::from(k))).collect();
        assert!(draws.iter().all(|x| (-1.0..1.0).contains(x)));
        let mean = draws.iter().sum::<f64>() / draws.len() as f64;
        let var = draws.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / draws.len() as f64;
        // uniform on [−1, 1]: mean 0, variance 1/3 (4σ bounds)
        assert!(
            mean.abs() < 4.0 * (1.0 / 3.0 / 20_000.0_f64).sqrt(),
            "{mean}"
        );
        assert!((var - 1.0 / 3.0).abs() < 0.01, "{var}");
    }
}
