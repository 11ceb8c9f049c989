//! The [`Protocol`] trait: every flocking algorithm computes all agents' inputs from a read-only
//! state; a distributed one also has a [`LocalForm`], u_i from what agent i alone perceives.

use flock_graph::{Graph, ProximityNet};
use flock_math::Vector;

use crate::Swarm;

/// A distributed flocking protocol: u_i as a function of the state of agent i and of its neighbours
/// in the proximity net, plus the energy function its stability theorem uses.
///
/// The trait is object safe: a protocol chosen at run time is a `Box<dyn Protocol<V> + Send>`
/// ([`DynProtocol`]), itself a protocol, so one simulation (`flock_sim::Simulation`) type serves
/// every algorithm.
pub trait Protocol<V: Vector>: Sync {
    /// The interaction range r that defines N_i = { j : ‖q_j − q_i‖ < r }.
    #[must_use]
    fn interaction_range(&self) -> f64;

    /// Writes u_i for every agent into `inputs` (length n), from the state at time `t` and its net
    /// (built with [`Protocol::interaction_range`]). Bit-identical whatever the thread count.
    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]);

    /// The energy (Hamiltonian) of the closed-loop system whose non-increase the theory proves.
    #[must_use]
    fn energy(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64;

    /// The protocol's own diagnostics of the state at time `t`, each with its column name
    /// (`obstacle_clearance`, `velocity_disagreement`, …): the same names in the same order at
    /// every state of a run. None by default.
    ///
    /// The state is as the simulation stores it: in original order unless the protocol
    /// [follows the numbering](Protocol::follows_numbering), whose values must then not depend on
    /// the order of the agents (minima, counts).
    #[must_use]
    fn diagnostics(
        &self,
        _t: f64,
        _swarm: &Swarm<V>,
        _net: &ProximityNet,
    ) -> Vec<(&'static str, f64)> {
        Vec::new()
    }

    /// Whether [`Protocol::controls`] and [`Protocol::energy`] read the net's stored distances
    /// ([`ProximityNet::distances`]); true unless a protocol says otherwise. When false, a
    /// simulation (`flock_sim::Simulation`) keeps its nets without them
    /// ([`ProximityNet::without_distances`]): 8 bytes less per directed edge.
    #[must_use]
    fn uses_net_distances(&self) -> bool {
        true
    }

    /// Whether [`Protocol::controls`] reads the net's graph; true unless a protocol says
    /// otherwise. When false, a simulation (`flock_sim::Simulation`) without conditions or
    /// vehicles does not rebuild its net after each step but when a measurement reads it: a
    /// protocol that finds its neighbours itself (the boids on a torus) steps without it.
    #[must_use]
    fn controls_read_net(&self) -> bool {
        true
    }

    /// Whether the protocol follows a net's [`Numbering`](flock_graph::Numbering): given the state
    /// stored in any order and the net built from it with its numbering, [`Protocol::controls`]
    /// gives each agent the bits it gets in original order, and [`Protocol::energy`] the same
    /// bits. A simulation (`flock_sim::Simulation`) then stores the agents in space order when
    /// they are numbered at random. False unless a protocol says otherwise (the protocols with
    /// sums over all agents in their controls, or a graph fixed by agent index, keep their order).
    #[must_use]
    fn follows_numbering(&self) -> bool {
        false
    }

    /// The fixed graph the protocol interacts on, node k agent k, for a protocol that does not
    /// follow the numbering (the Tanner law's neighbouring graph); `None` for the protocols of
    /// the proximity net. A simulation (`flock_sim::Simulation`) measures connectivity on it — C, C*
    /// and the components — instead of on the proximity net.
    #[must_use]
    fn interaction_graph(&self) -> Option<&Graph> {
        None
    }

    /// The protocol's [`LocalForm`]: u_i from agent i's own perceived state and what it received
    /// from the agents it hears. `None` (the default) for a protocol that is not distributed, or
    /// whose form is only known for the whole swarm (a centralised controller, a protocol given
    /// as a function of all states): conditions that make agents perceive different worlds
    /// (delay of the neighbours only, packet loss, a communication range, silent faults) are
    /// then refused for it.
    #[must_use]
    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        None
    }

    /// What the protocol's output u_i is, and so how the loop applies it ([`Update`]): an
    /// acceleration by default.
    #[must_use]
    fn update(&self) -> Update {
        Update::Acceleration
    }

    /// Whether [`Protocol::controls`] measures every displacement in the run's
    /// [`Domain`](flock_math::Domain) itself (the minimum image on a torus), as the models of
    /// periodic boxes do. False by default: on a torus the simulation then computes each
    /// agent's input from the protocol's [`LocalForm`] with every neighbour at its image nearest
    /// the agent.
    #[must_use]
    fn measures_in_domain(&self) -> bool {
        false
    }
}

/// What a protocol's output u_i is, and how the loop of a run applies it after the control
/// step (the "integrate" stage of fail → sense → communicate → control → actuate → integrate).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Update {
    /// A commanded acceleration of a double integrator q̇ = p, ṗ = u (TAC 2006 eq. 1), integrated
    /// by the run's integrator (`flock_sim::Integrator`).
    #[default]
    Acceleration,
    /// The agent's next velocity, set at once, and then the move with it: p ← u_i,
    /// q ← q + h p (the boids of the ABM frameworks, Couzin et al. 2002).
    TurnThenMove,
    /// The move with the present velocity, then the new velocity: q ← q + h p, p ← u_i
    /// (Vicsek et al. 1995, eq. 1 with x_i(t + 1) = x_i(t) + v_i(t) Δt, then eq. 2).
    MoveThenTurn,
}

impl Update {
    /// Whether u_i is a velocity (the discrete-time, constant-speed models): conditions on
    /// accelerations (actuation limits and lag, wind, process noise, speed limits) do not apply.
    #[must_use]
    pub const fn sets_velocity(self) -> bool {
        !matches!(self, Self::Acceleration)
    }
}

/// An agent's state as the agent computing its input perceives it: its own, as it measures it,
/// or a neighbour's, as it received it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perceived<V> {
    /// The agent's index (in original order).
    pub agent: u32,
    /// Its position q_j as perceived.
    pub position: V,
    /// Its velocity p_j as perceived.
    pub velocity: V,
}

/// A distributed protocol's input of one agent from what that agent perceives, and nothing else:
/// the form in which the protocols stay unaware of how the perception came about (delayed,
/// noisy, lossy).
///
/// Given the exact state (`own` the agent's true state, `heard` its neighbours in the net or the
/// fixed graph with their true states, in ascending agent index), [`LocalForm::local_input`] is
/// u_i of [`Protocol::controls`], bit for bit unless the protocol says otherwise.
pub trait LocalForm<V: Vector>: Sync {
    /// u_i at time `t` of agent `own.agent` from its perceived state and the states it received
    /// from the agents it hears, `heard`, in ascending agent index. For a protocol of the
    /// proximity net `heard` may hold agents beyond the interaction range r (every agent within
    /// the communication range): the protocol keeps those within r by their perceived distance.
    /// For a protocol of a fixed graph it holds the graph neighbours whose messages arrived.
    fn local_input(&self, t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V;

    /// [`LocalForm::local_input`] of a block of receivers at time `t`: `out[r]` for receiver r
    /// of `block`. A protocol whose pair terms batch across receivers computes them together,
    /// with the bits of `local_input`.
    fn local_inputs(&self, t: f64, block: Perceptions<'_, V>, out: &mut [V]) {
        for ((own, heard), u) in block.receivers().zip(out) {
            *u = self.local_input(t, own, heard);
        }
    }

    /// Whether [`LocalForm::local_inputs`] takes every agent's perception in one call rather
    /// than block by block: a controller outside the library (a Python function, a learned
    /// policy), whose calls cost more than the work of a block. False by default.
    #[must_use]
    fn takes_all(&self) -> bool {
        false
    }

    /// The state (q_r, p_r) at time `t` of the γ-agent the protocol tracks, known to every agent
    /// (TAC 2006 eq. 25: f_i^γ reads it); `None` (the default) for a protocol without one.
    #[must_use]
    fn reference(&self, _t: f64) -> Option<(V, V)> {
        None
    }

    /// The β-agents (q̂_ik, p̂_ik) that agent `own` senses from its perceived state (TAC 2006
    /// § VII: the projections on the obstacles within r′), appended to `out` in obstacle order;
    /// none (the default) for a protocol that does not avoid obstacles.
    fn beta_agents(&self, _own: &Perceived<V>, _out: &mut Vec<(V, V)>) {}
}

/// What a block of receivers perceives: receiver r perceives itself as `owns[r]` and heard
/// `heard[ends[r − 1]..ends[r]]` (from 0 for the first), in ascending agent index.
#[derive(Clone, Copy, Debug)]
pub struct Perceptions<'a, V> {
    /// Each receiver's own perceived state.
    pub owns: &'a [Perceived<V>],
    /// What the receivers heard, one after the other.
    pub heard: &'a [Perceived<V>],
    /// The end in `heard` of each receiver's states.
    pub ends: &'a [usize],
}

impl<'a, V> Perceptions<'a, V> {
    /// Each receiver's own perceived state and the states it heard, in order.
    pub fn receivers(
        self,
    ) -> impl Iterator<Item = (&'a Perceived<V>, &'a [Perceived<V>])> + Clone + 'a {
        let starts = core::iter::once(0).chain(self.ends.iter().copied());
        self.owns.iter().zip(
            starts
                .zip(self.ends)
                .map(|(start, &end)| &self.heard[start..end]),
        )
    }
}

/// A protocol chosen at run time.
pub type DynProtocol<V> = Box<dyn Protocol<V> + Send>;

/// A boxed protocol is the protocol it holds.
impl<V: Vector, P: Protocol<V> + ?Sized> Protocol<V> for Box<P> {
    fn interaction_range(&self) -> f64 {
        (**self).interaction_range()
    }

    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        (**self).controls(t, swarm, net, inputs);
    }

    fn energy(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        (**self).energy(t, swarm, net)
    }

    fn diagnostics(
        &self,
        t: f64,
        swarm: &Swarm<V>,
        net: &ProximityNet,
    ) -> Vec<(&'static str, f64)> {
        (**self).diagnostics(t, swarm, net)
    }

    fn uses_net_distances(&self) -> bool {
        (**self).uses_net_distances()
    }

    fn controls_read_net(&self) -> bool {
        (**self).controls_read_net()
    }

    fn follows_numbering(&self) -> bool {
        (**self).follows_numbering()
    }

    fn interaction_graph(&self) -> Option<&Graph> {
        (**self).interaction_graph()
    }

    fn update(&self) -> Update {
        (**self).update()
    }

    fn measures_in_domain(&self) -> bool {
        (**self).measures_in_domain()
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        (**self).local_form()
    }
}
