//! **Control**: every agent's input u_i from what it perceives ([`Perception`]): the protocol's
//! [`Protocol::controls`] of the true state (on a torus, its [`LocalForm`] with each neighbour at
//! its nearest image), or its [`LocalForm`] of what each agent heard, computed for
//! `CONTROL_BLOCK` receivers at a time ([`LocalForm::local_inputs`]).

use flock_graph::ProximityNet;
use flock_math::interrupt::cuts_short;
use flock_math::{Domain, Vector};
use flock_protocols::{LocalForm, Perceived, Protocol, Swarm};

use crate::agents::map_agents_mut;
use crate::conditions::Stage;
use crate::conditions::links::Link;
use crate::step::communicate::{CONTROL_BLOCK, Counts, Perception, Received, Scratch};
use crate::step::perceive::Percepts;

/// The control stage at time `t`: every agent's input from its `perception`, into `inputs`; a
/// protocol that [takes every perception at once](LocalForm::takes_all) is given them gathered
/// in `percepts`.
pub(crate) fn control<V: Vector>(
    protocol: &dyn Protocol<V>,
    t: f64,
    perception: Perception<'_, V>,
    inputs: &mut [V],
    percepts: &mut Percepts<V>,
) -> Option<Received<V>> {
    match perception {
        Perception::Truth { domain, swarm, net } => {
            controls_in(protocol, domain, t, (swarm, net), inputs, percepts);
            None
        }
        Perception::Heard(mut heard) => {
            let Some(local) = protocol.local_form() else {
                unreachable!("agents hear through the conditions for a protocol with a local form");
            };
            if local.takes_all() {
                let received = percepts.of_heard(*heard);
                local.local_inputs(t, percepts.perceptions(), inputs);
                return Some(received);
            }
            let mut links = core::mem::take(&mut heard.links);
            let counts = control_blocks(inputs, &mut links, |start, inputs, links, w| {
                let counts = heard.block(start, inputs.len(), links, &mut w.scratch);
                w.out.clear();
                w.out.resize(w.scratch.block.receivers.len(), V::ZERO);
                local.local_inputs(t, w.scratch.block.perceptions(), &mut w.out);
                for (&r, &u) in w.scratch.block.receivers.iter().zip(w.out.iter()) {
                    inputs[r] = u;
                }
                counts
            });
            Some(Received::new(links, counts))
        }
    }
}

impl<V: Vector> Stage<V> {
    /// After the control stage: the links kept given back with the readings of the update
    /// (`received`, when agents heard through the conditions), and no input for the agents that
    /// do not move.
    pub(crate) fn controlled(&mut self, received: Option<Received<V>>, inputs: &mut [V]) {
        if let Some(Received { links, counts }) = received {
            self.links = links;
            self.readings.links_lost = ratio(counts.lost as f64, counts.candidates);
            self.readings.information_age = ratio(counts.age as f64 * self.h, counts.used);
        }
        for (i, u) in inputs.iter_mut().enumerate() {
            if !self.moves(i) {
                *u = V::ZERO;
            }
        }
    }
}

/// `x / n`, 0 when `n` is 0.
fn ratio(x: f64, n: usize) -> f64 {
    if n == 0 { 0.0 } else { x / n as f64 }
}

/// A worker's buffers: the communicate stage's scratch and the block's inputs.
#[derive(Default)]
struct Worker<V> {
    scratch: Scratch<V>,
    out: Vec<V>,
}

/// The counts of `f(start, inputs, links, scratch)` summed over the blocks of
/// [`CONTROL_BLOCK`] receivers from `start`, `f` setting each receiver's input in `inputs`,
/// with `links` their kept links (`None` when `links` is empty: links keep nothing). In
/// parallel with the `parallel` feature, each worker's scratch passed from block to block (`f`'s
/// result must not depend on what it held before).
fn control_blocks<V: Vector>(
    inputs: &mut [V],
    links: &mut [Vec<Link<V>>],
    f: impl Fn(usize, &mut [V], Option<&mut [Vec<Link<V>>]>, &mut Worker<V>) -> Counts + Sync + Send,
) -> Counts {
    // an interrupt that cuts the step short leaves the blocks not yet begun (the step is torn)
    let f = |start, u: &mut [V], l, w: &mut Worker<V>| {
        if cuts_short() {
            Counts::default()
        } else {
            f(start, u, l, w)
        }
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        let blocks = inputs
            .par_chunks_mut(CONTROL_BLOCK)
            .enumerate()
            .with_min_len(4);
        if links.is_empty() {
            blocks
                .map_init(Worker::default, |w, (b, u)| {
                    f(b * CONTROL_BLOCK, u, None, w)
                })
                .reduce(Counts::default, core::ops::Add::add)
        } else {
            blocks
                .zip(links.par_chunks_mut(CONTROL_BLOCK))
                .map_init(Worker::default, |w, ((b, u), l)| {
                    f(b * CONTROL_BLOCK, u, Some(l), w)
                })
                .reduce(Counts::default, core::ops::Add::add)
        }
    }
    #[cfg(not(feature = "parallel"))]
    {
        let mut w = Worker::default();
        let mut links = links.chunks_mut(CONTROL_BLOCK);
        inputs
            .chunks_mut(CONTROL_BLOCK)
            .enumerate()
            .map(|(b, u)| f(b * CONTROL_BLOCK, u, links.next(), &mut w))
            .fold(Counts::default(), core::ops::Add::add)
    }
}

/// Every agent's input at time `t`: [`Protocol::controls`] of the state, or on a torus, for a
/// protocol that does not measure in the domain itself, its [`LocalForm`] with every neighbour in
/// the net at its image nearest the agent ([`Domain::image_near`]), in ascending index; for a
/// form that [takes every perception at once](LocalForm::takes_all), its inputs of the true
/// perceptions gathered in `percepts`.
pub(crate) fn controls_in<V: Vector>(
    protocol: &dyn Protocol<V>,
    domain: &Domain<V>,
    t: f64,
    (swarm, net): (&Swarm<V>, &ProximityNet),
    inputs: &mut [V],
    percepts: &mut Percepts<V>,
) {
    match protocol.local_form() {
        Some(local) if local.takes_all() => {
            percepts.of_truth(domain, swarm, net, protocol.interaction_graph());
            local.local_inputs(t, percepts.perceptions(), inputs);
        }
        Some(local) if domain.is_periodic() && !protocol.measures_in_domain() => {
            local_controls(local, domain, t, swarm, net, inputs);
        }
        _ => protocol.controls(t, swarm, net, inputs),
    }
}

/// u_i = local_input(t, own, heard) with the true states, neighbours at their nearest image,
/// in the net's order (ascending original index), each agent named by its original index.
fn local_controls<V: Vector>(
    local: &dyn LocalForm<V>,
    domain: &Domain<V>,
    t: f64,
    swarm: &Swarm<V>,
    net: &ProximityNet,
    inputs: &mut [V],
) {
    let (q, p) = (&swarm.positions, &swarm.velocities);
    let numbering = net.numbering();
    let perceived = |i: usize, position: V| Perceived {
        agent: numbering.original(i) as u32,
        position,
        velocity: p[i],
    };
    // each worker's heard list, reused from agent to agent
    map_agents_mut(inputs, Vec::new, |i, u, heard| {
        // an interrupt that cuts the step short leaves the agents not yet begun
        if cuts_short() {
            return;
        }
        heard.clear();
        heard.extend(
            net.graph()
                .neighbours(i)
                .iter()
                .map(|&j| perceived(j as usize, domain.image_near(q[i], q[j as usize]))),
        );
        *u = local.local_input(t, &perceived(i, q[i]), heard);
    });
}
