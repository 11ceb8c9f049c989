//! **What every agent perceives**, all at once ([`Percepts`]): the communicate stage's output
//! gathered for the whole swarm, for a controller that takes every agent's perception in one
//! call ([`LocalForm::takes_all`](flock_protocols::LocalForm::takes_all): a function written
//! outside the library) and for a step split in two around a controller outside the loop
//! ([`Simulation::perceive`](crate::Simulation::perceive), [`Simulation::act`](crate::Simulation::act)).
//!
//! Under conditions it is formed block by block of receivers, exactly as the control stage forms
//! them (`Heard::block`, the same blocks, so the same draws and the same links); in the ideal
//! run, from the true state and its net (or the protocol's fixed graph), each neighbour at its
//! image nearest the agent.

use flock_graph::{Graph, ProximityNet};
use flock_math::{Domain, Vector};
use flock_protocols::{Perceived, Perceptions, Swarm};

use crate::step::communicate::{CONTROL_BLOCK, Counts, Heard, Received, Scratch};

/// What every agent perceives at a control update, agents as the simulation stores them
/// (in original order unless its protocol follows the numbering; each [`Perceived::agent`] is
/// the original index): agent i perceives itself as `owns[i]` and heard
/// `heard[ends[i − 1]..ends[i]]`, in ascending agent index. An agent that does not move (a
/// removed agent) perceives its true state and hears no one; its input is not applied.
#[derive(Clone, Debug, Default)]
pub struct Percepts<V> {
    owns: Vec<Perceived<V>>,
    heard: Vec<Perceived<V>>,
    ends: Vec<usize>,
}

impl<V: Copy> Percepts<V> {
    /// Every agent's perception, as a protocol's [`LocalForm`](flock_protocols::LocalForm)
    /// reads a block.
    #[must_use]
    pub fn perceptions(&self) -> Perceptions<'_, V> {
        Perceptions {
            owns: &self.owns,
            heard: &self.heard,
            ends: &self.ends,
        }
    }

    /// The number of agents.
    #[must_use]
    pub fn len(&self) -> usize {
        self.owns.len()
    }

    /// Whether there is no agent.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.owns.is_empty()
    }

    fn clear(&mut self) {
        self.owns.clear();
        self.heard.clear();
        self.ends.clear();
    }

    /// Appends an agent that perceives `own` and the states `heard`.
    fn push(&mut self, own: Perceived<V>, heard: impl IntoIterator<Item = Perceived<V>>) {
        self.owns.push(own);
        self.heard.extend(heard);
        self.ends.push(self.heard.len());
    }
}

impl<V: Vector> Percepts<V> {
    /// The perceptions of the true state `swarm`: agent i's own state and those of its
    /// neighbours in `graph` (a fixed graph, node k agent k) or else in the net, each at its
    /// image nearest the agent, in ascending original index.
    pub fn of_truth(
        &mut self,
        domain: &Domain<V>,
        swarm: &Swarm<V>,
        net: &ProximityNet,
        graph: Option<&Graph>,
    ) {
        self.clear();
        let (q, p) = (&swarm.positions, &swarm.velocities);
        let numbering = net.numbering();
        let perceived = |i: usize, position: V| Perceived {
            agent: numbering.original(i) as u32,
            position,
            velocity: p[i],
        };
        let candidates = graph.unwrap_or_else(|| net.graph());
        for i in 0..swarm.len() {
            let heard = candidates.neighbours(i).iter().map(|&j| {
                let j = j as usize;
                perceived(j, domain.image_near(q[i], q[j]))
            });
            self.push(perceived(i, q[i]), heard);
        }
    }

    /// The perceptions of every agent through the conditions, formed in the blocks of the
    /// control stage (their draws and links those of a step controlled block by block); an
    /// agent that does not move perceives its true state. Returns the links kept and the counts,
    /// for the conditions.
    pub(crate) fn of_heard(&mut self, mut heard: Heard<'_, V>) -> Received<V> {
        self.clear();
        let swarm = heard.swarm;
        let n = swarm.len();
        let mut links = core::mem::take(&mut heard.links);
        let mut scratch = Scratch::default();
        let mut counts = Counts::default();
        for start in (0..n).step_by(CONTROL_BLOCK) {
            let len = CONTROL_BLOCK.min(n - start);
            let kept = (!links.is_empty()).then(|| &mut links[start..start + len]);
            counts = counts + heard.block(start, len, kept, &mut scratch);
            let block = &scratch.block;
            let mut listed = block.receivers.iter().enumerate().peekable();
            for r in 0..len {
                match listed.next_if(|&(_, &place)| place == r) {
                    Some((m, _)) => {
                        let from = if m == 0 { 0 } else { block.ends[m - 1] };
                        let own = block.owns[m];
                        self.push(own, block.heard[from..block.ends[m]].iter().copied());
                    }
                    None => {
                        let i = start + r;
                        let own = Perceived {
                            agent: heard.original(i),
                            position: swarm.positions[i],
                            velocity: swarm.velocities[i],
                        };
                        self.push(own, []);
                    }
                }
            }
        }
        Received::new(links, counts)
    }
}

/// A step begun: fail and sense done, and, at a control update, what the agents perceive.
#[derive(Debug)]
pub(crate) enum Sensed<V> {
    /// No control update at this step (sampled control): the inputs are held.
    Held,
    /// Every agent's perception is in the simulation's [`Percepts`]: the true state's (`truth`),
    /// or what was heard through the conditions, whose links and counts `received` holds.
    Perceived {
        truth: bool,
        received: Option<Received<V>>,
    },
}
