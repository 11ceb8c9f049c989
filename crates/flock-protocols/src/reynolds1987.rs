//! Reynolds's boids (C. W. Reynolds, "Flocks, herds and schools: a distributed behavioral model",
//! SIGGRAPH 1987: separation, alignment, cohesion) in the form the agent-based modelling
//! frameworks benchmark: JuliaDynamics' ABMFrameworksComparison, `Flocking/DECLARATION.md`
//! (Agents.jl, MASON, NetLogo and Mesa implement it), whose rule and defaults this follows.

use flock_graph::ProximityNet;
use flock_math::interrupt::{BLOCK, cuts_short};
use flock_math::{Domain, Vector};

mod birds;

use crate::error::{ParamError, check};
use crate::swarm::heading_mismatch;
use crate::{LocalForm, Perceived, Protocol, Swarm, Update};
use birds::Birds;
use flock_math::stream::{Purpose, Streams};

/// Birds from which the sweep draws its activation order on one thread while it sorts them on
/// another.
const JOINED_FROM: usize = 1 << 14;

/// The parameters of the boids, named as the declaration names them, with its defaults (the same
/// for its "small" and "large" workloads but for `visual_distance`: 5 small, 15 large). A
/// scenario may leave out any of them.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
pub struct BoidsParams {
    /// The speed s > 0: each step a boid moves s h along its heading (declaration: 1).
    pub speed: f64,
    /// The weight of the mean offset to the neighbours (cohesion; declaration: 0.03).
    pub cohere_factor: f64,
    /// Neighbours closer than this are pushed away (declaration: 1).
    pub separation: f64,
    /// The weight of the separation vector (declaration: 0.015).
    pub separate_factor: f64,
    /// The weight of the neighbours' mean heading (alignment; declaration: 0.05).
    pub match_factor: f64,
    /// A boid sees the others within this distance, boundary included (declaration: 5 small).
    pub visual_distance: f64,
}

impl Default for BoidsParams {
    fn default() -> Self {
        Self {
            speed: 1.0,
            cohere_factor: 0.03,
            separation: 1.0,
            separate_factor: 0.015,
            match_factor: 0.05,
            visual_distance: 5.0,
        }
    }
}

/// The boids of the ABM frameworks' benchmark.
///
/// Each step, the boids are activated one by one in a random order drawn anew ([`Purpose::Activation`]
/// streams of the run's seed); the activated boid i, with unit heading v_i = p_i / s, sums over
/// the N boids j within its visual distance (‖q_j − q_i‖ ≤ visual_distance, minimum image on a
/// torus; positions and headings as they are at its activation, so the boids activated before it
/// have already moved):
///
/// - cohesion c = Σ (q_j − q_i), alignment m = Σ v_j,
/// - separation s = −Σ (q_j − q_i) over those closer than `separation`,
///
/// and sets v_i ← w / ‖w‖ with w = (v_i + c f_c / N + s f_s / N + m f_m / N) / 2 (N ≥ 1), then moves
/// q_i ← q_i + s h v_i (wrapped into the box). The output u_i is the new velocity s v_i
/// ([`Update::TurnThenMove`]), so the loop's move repeats exactly the move of the sweep.
///
/// The declaration's own code (Agents.jl) forms q_j − q_i without the minimum image, so near the
/// wrap its cohesion points the long way round; here every offset is the minimum image, as the
/// declaration asks of the neighbour search.
///
/// On a torus the sweep finds who is in sight itself, in a grid of cells over the box sorted once
/// a step (`birds::Birds::in_cells`), and sums cell by cell around the boid, within a cell in
/// ascending original index: an order of space, the same whatever the storage order. In open
/// space it reads the proximity net, in ascending original index. The net is built at the visual
/// distance plus 2 s h, the most two boids can close in a step, so that it holds every pair that
/// comes within sight during the sweep; the metrics' connectivity is of that net, which a
/// simulation builds on a torus only when a measurement reads it
/// ([`Protocol::controls_read_net`]). Under conditions that change what boids perceive (delay,
/// loss, noise, faults), every boid turns on what it perceived at the start of the step (its
/// [`LocalForm`]): the activation order then plays no part.
#[derive(Clone, Debug, PartialEq)]
pub struct Boids<V> {
    params: BoidsParams,
    step: f64,
    streams: Streams,
    domain: Domain<V>,
}

impl<V: Vector> Boids<V> {
    /// The boids moving by `step` per activation (the declaration's step is 1), their activation
    /// order drawn from the streams of `seed`, in `domain` (the declaration's: a periodic box).
    ///
    /// # Errors
    /// `speed`, `visual_distance` or `step` not positive and finite; a factor or `separation`
    /// negative.
    pub fn new(
        params: BoidsParams,
        step: f64,
        seed: u64,
        domain: Domain<V>,
    ) -> Result<Self, ParamError> {
        check::positive("speed", params.speed)?;
        check::positive("visual_distance", params.visual_distance)?;
        check::positive("step", step)?;
        for (name, value) in [
            ("cohere_factor", params.cohere_factor),
            ("separation", params.separation),
            ("separate_factor", params.separate_factor),
            ("match_factor", params.match_factor),
        ] {
            check::non_negative(name, value)?;
        }
        Ok(Self {
            params,
            step,
            streams: Streams::new(seed),
            domain,
        })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> BoidsParams {
        self.params
    }

    /// The order in which the boids are activated at time `t`: a Fisher–Yates shuffle whose k-th
    /// swap draws from its own keyed stream.
    #[must_use]
    pub fn activation_order(&self, t: f64, n: usize) -> Vec<u32> {
        let k = (t / self.step).round() as u64;
        let mut order: Vec<u32> = (0..n as u32).collect();
        for i in (1..n).rev() {
            let j = self
                .streams
                .draws(Purpose::Activation, i as u64, k)
                .up_to(i as u64) as usize;
            order.swap(i, j);
        }
        order
    }

    /// The squared visual distance and the squared separation: the rule's two tests.
    fn squared_distances(&self) -> (f64, f64) {
        let p = &self.params;
        (
            p.visual_distance * p.visual_distance,
            p.separation * p.separation,
        )
    }

    /// The new unit heading of a boid at `q` with heading `v` from its candidates `others`
    /// (position, heading), those within sight counted in the order given.
    fn turn(&self, q: V, v: V, others: impl Iterator<Item = (V, V)>) -> V {
        let (sight, apart) = self.squared_distances();
        let mut sums = Sums::ZERO;
        for (qj, vj) in others {
            let offset = self.domain.displacement(q, qj);
            sums.add_in_sight(offset, vj, sight, apart);
        }
        self.heading(v, &sums)
    }

    /// The new unit heading w / ‖w‖ of a boid with heading `v`, from the sums over the boids in
    /// its sight.
    fn heading(&self, v: V, sums: &Sums<V>) -> V {
        let p = &self.params;
        let n = f64::from(sums.count.max(1));
        let w = (v
            + sums.cohere / n * p.cohere_factor
            + sums.separate / n * p.separate_factor
            + sums.matching / n * p.match_factor)
            / 2.0;
        w / w.length()
    }
}

/// The rule's sums over the boids in sight: cohesion c, separation s, alignment m and their
/// number N.
#[derive(Clone, Copy, Debug)]
struct Sums<V> {
    cohere: V,
    separate: V,
    matching: V,
    count: u32,
}

impl<V: Vector> Sums<V> {
    const ZERO: Self = Self {
        cohere: V::ZERO,
        separate: V::ZERO,
        matching: V::ZERO,
        count: 0,
    };

    /// Counts a boid at `offset` with heading `vj` if it is within sight (`sight`, a squared
    /// distance, boundary included), in the separation too if closer than `apart` (squared).
    #[inline]
    fn add_in_sight(&mut self, offset: V, vj: V, sight: f64, apart: f64) {
        let d2 = offset.length_squared();
        if d2 > sight {
            return;
        }
        self.count += 1;
        self.cohere += offset;
        if d2 < apart {
            self.separate -= offset;
        }
        self.matching += vj;
    }
}

impl<V: Vector> Protocol<V> for Boids<V> {
    /// The visual distance plus 2 s h (see [`Boids`]).
    fn interaction_range(&self) -> f64 {
        self.params.visual_distance + 2.0 * self.params.speed * self.step
    }

    fn uses_net_distances(&self) -> bool {
        false
    }

    /// On a torus the sweep finds who is in sight in its own cells.
    fn controls_read_net(&self) -> bool {
        !self.domain.is_periodic()
    }

    /// The sequential sweep in the step's random order, each boid reading the others as they are
    /// at its activation: on the torus in the cells around it (`birds::Birds::sums_in_sight`), in open
    /// space on the net.
    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let s = self.params.speed;
        let sorted = || {
            let headings: Vec<V> = swarm.velocities.iter().map(|&p| p / s).collect();
            match self.domain {
                Domain::Periodic { size } => {
                    let reach = self.params.visual_distance + s * self.step;
                    Birds::in_cells(size, reach, &swarm.positions, &headings)
                }
                Domain::Open => Birds::in_order(&swarm.positions, &headings),
            }
        };
        let drawn = || self.activation_order(t, swarm.len());
        // the order drawn while the birds are sorted, on two threads for a large flock
        let (order, mut birds) = if swarm.len() >= JOINED_FROM {
            flock_math::parallel::join(drawn, sorted)
        } else {
            (drawn(), sorted())
        };
        let distances = self.squared_distances();
        let ahead = birds.reads_ahead();
        let mut read = 0;
        for (k, &i) in order.iter().enumerate() {
            // one sequential sweep: checked for an interrupt every block of boids
            if k % BLOCK == 0 && cuts_short() {
                return;
            }
            if ahead {
                read ^= birds.read_ahead(&order, k);
            }
            let i = i as usize;
            let Some(slot) = birds.slot(i) else {
                // a boid in no cell (a non-finite position) sees no one
                let own = swarm.velocities[i] / s;
                inputs[i] = self.turn(swarm.positions[i], own, core::iter::empty()) * s;
                continue;
            };
            let heading = match self.domain {
                Domain::Periodic { .. } => {
                    let sums = birds.sums_in_sight(&self.domain, slot, distances);
                    self.heading(birds.slots[slot].v, &sums)
                }
                Domain::Open => {
                    let slots = &birds.slots;
                    let others = net.graph().neighbours(i).iter();
                    let others = others.map(|&j| (slots[j as usize].q, slots[j as usize].v));
                    self.turn(slots[slot].q, slots[slot].v, others)
                }
            };
            let p = heading * s;
            inputs[i] = p;
            birds.slots[slot].v = heading;
            birds.move_by(&self.domain, slot, p * self.step);
        }
        core::hint::black_box(read);
    }

    /// The heading mismatch n − ‖Σ_i p̂_i‖ (p̂_i = p_i/‖p_i‖): the model decreases no
    /// energy.
    fn energy(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        heading_mismatch(&swarm.velocities, net.numbering())
    }

    fn update(&self) -> Update {
        Update::TurnThenMove
    }

    fn measures_in_domain(&self) -> bool {
        true
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }
}

/// The rule on what the boid perceived at the start of the step (no activation order).
impl<V: Vector> LocalForm<V> for Boids<V> {
    fn local_input(&self, _t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        let s = self.params.speed;
        let others = heard.iter().map(|o| (o.position, o.velocity / s));
        self.turn(own.position, own.velocity / s, others) * s
    }
}

#[cfg(test)]
mod tests;
