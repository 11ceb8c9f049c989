//! Where the agents are stored: in original order, or — agents numbered at random, for a
//! protocol that follows the numbering — in the order of the neighbour search's cells, so that
//! neighbours are near in memory, re-sorted every [`RESORT_EVERY`] steps, every per-agent array
//! of the run moving with its agent ([`Simulation::stored_by_cell`]).

use flock_math::Vector;
use flock_math::parallel::fill_indexed;
use flock_protocols::{Protocol, Swarm};

use crate::Simulation;
use crate::conditions::Stage;
use crate::permutation::permute_in_place;
use crate::simulation::empty_net;
use crate::vehicle::Fleet;

/// Steps between two re-sorts of agents stored in space order.
const RESORT_EVERY: u64 = 16;

/// Moves every per-agent array of a run with its agent, index s getting what index `from(s)`
/// held: the swarm, gathered into the inputs and swapped in when the inputs are free between
/// steps (the ideal run's: one vector per agent, recomputed at every step), otherwise permuted in
/// place as the inputs held under conditions, the conditions' state and the vehicles' states are
/// (no array is held twice).
fn move_agents<V: Vector>(
    swarm: &mut Swarm<V>,
    inputs: &mut Vec<V>,
    stage: Option<&mut Stage<V>>,
    fleet: Option<&mut Fleet<V>>,
    from: impl Fn(usize) -> usize + Copy + Sync,
) {
    let spare = stage.is_none() && inputs.len() == swarm.len();
    for x in [&mut swarm.positions, &mut swarm.velocities] {
        if spare {
            fill_indexed(inputs, |s| x[from(s)]);
            core::mem::swap(x, inputs);
        } else {
            permute_in_place(x, from);
        }
    }
    if let Some(stage) = stage {
        permute_in_place(inputs, from);
        stage.permute(from);
    }
    if let Some(fleet) = fleet {
        fleet.permute(from);
    }
}

impl<V: Vector, P: Protocol<V>> Simulation<V, P> {
    /// Puts the agents stored by cell back in original order, with their conditions' and
    /// vehicles' states, and leaves an empty net (its numbering gone) that
    /// [`Simulation::rebuild_net`] must rebuild.
    pub(crate) fn back_to_original_order(&mut self) {
        if self.stored_by_cell() {
            let numbering = self.net.numbering();
            // index k now holds agent k, which was stored at `stored(k)`
            move_agents(
                &mut self.swarm,
                &mut self.inputs,
                self.conditions.as_deref_mut(),
                self.fleet.as_deref_mut(),
                |k| numbering.stored(k),
            );
        }
        self.net = empty_net(&self.protocol);
    }

    /// Builds the net of the current state; agents stored in space order are re-sorted every
    /// [`RESORT_EVERY`] steps first, and agents in original order found scattered in memory are
    /// sorted, when the protocol follows the numbering. (Agents once sorted wait for the next
    /// re-sort even if still scattered, e.g. thousands in one cell: no sort at every step.)
    pub(crate) fn rebuild_net(&mut self) {
        self.net_stale = false;
        let r = self.protocol.interaction_range();
        let sorts =
            self.protocol.follows_numbering() && self.protocol.interaction_graph().is_none();
        let sorted = !self.net.numbering().is_identity();
        if sorts && sorted && self.steps.is_multiple_of(RESORT_EVERY) {
            self.sort_by_cell();
        }
        self.search
            .build_in(&self.domain, &self.swarm.positions, r, &mut self.net);
        if sorts && !sorted && self.net.is_scattered() {
            self.sort_by_cell();
            self.search
                .build_in(&self.domain, &self.swarm.positions, r, &mut self.net);
        }
    }

    /// Whether the net is rebuilt after each step: unless the protocol's controls do not read it
    /// ([`Protocol::controls_read_net`]) and nothing else of the step does (no conditions, no
    /// vehicles, no stages of RK4, agents in original order).
    pub(crate) fn keeps_net(&self) -> bool {
        self.protocol.controls_read_net()
            || self.protocol.follows_numbering()
            || self.conditions.is_some()
            || self.fleet.is_some()
            || self.rk.is_some()
    }

    /// Rebuilds a net left of an earlier state ([`Simulation::keeps_net`]).
    pub(crate) fn refresh_net(&mut self) {
        if self.net_stale {
            self.rebuild_net();
        }
    }

    /// Stores the agents in the order of the search's cells (agents with a non-finite position
    /// last, in their storage order) and renumbers the nets, which must then be rebuilt.
    fn sort_by_cell(&mut self) {
        let q = &self.swarm.positions;
        let r = self.protocol.interaction_range();
        let cells = self.search.cell_order_in(&self.domain, q, r);
        let completed: Vec<u32>;
        let order = if cells.len() == q.len() {
            cells
        } else {
            let lost = (0..q.len()).filter(|&i| !q[i].is_finite());
            completed = cells
                .iter()
                .copied()
                .chain(lost.map(|i| i as u32))
                .collect();
            &completed
        };
        move_agents(
            &mut self.swarm,
            &mut self.inputs,
            self.conditions.as_deref_mut(),
            self.fleet.as_deref_mut(),
            |s| order[s] as usize,
        );
        self.net.permute(order);
        if let Some(rk) = self.rk.as_mut() {
            rk.net.share_numbering(&self.net);
        }
    }
}
