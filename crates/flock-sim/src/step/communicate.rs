//! **Communicate**: what each agent perceives at a control update, the value this stage returns
//! ([`Perception`]). Without a condition on perception every agent perceives the true state and
//! its net ([`Perception::Truth`]). Otherwise each moving agent i hears its candidates (fixed
//! graph neighbours, within the communication range if one is given; or, for a protocol of the
//! proximity net, the agents within the communication range, by default the interaction range,
//! at their true positions; less the failed agents not heard), each packet delayed by τ
//! (+ jitter) in the delay line, lost by the loss model ([`links`](crate::conditions::links)),
//! dropped or replaced by the last value received ([`Perception::Heard`]).
//!
//! What agents hear is formed block by block of receivers (`Heard::block`), each block a CSR
//! of perceived states ([`Perceptions`]) that the control stage turns into inputs while it is
//! still in cache; the perception of all agents is these blocks end to end.

use core::ops::Range;

use flock_graph::{Graph, Numbering, ProximityNet};
use flock_math::stream::{Purpose, link_word_count, word_uniform, word_up_to};
use flock_math::{Domain, Vector};
use flock_protocols::{Perceived, Perceptions, Protocol, Swarm};

use crate::conditions::links::{Held, Link, lost};
use crate::conditions::stage::keeps_links;
use crate::conditions::{Communication, Delayed, Loss, Stage, WhenLost};

/// What the agents perceive at a control update.
pub enum Perception<'a, V> {
    /// Every agent perceives the true state and its proximity net (the ideal run, and
    /// conditions that change no one's perception).
    Truth {
        /// Open space or the periodic box.
        domain: &'a Domain<V>,
        /// The true state.
        swarm: &'a Swarm<V>,
        /// Its proximity net.
        net: &'a ProximityNet,
    },
    /// Each agent perceives what reaches it through the conditions.
    Heard(Box<Heard<'a, V>>),
}

/// The communicate stage of step `k`: what the agents perceive of the true state `swarm`, whose
/// net is `net`, through the conditions of `stage` (none: the truth). A protocol with no local
/// form perceives the truth (conditions on perception are refused for it,
/// [`check_local_form`](crate::checks::check_local_form)).
pub(crate) fn communicate<'a, V: Vector>(
    stage: Option<&'a mut Stage<V>>,
    protocol: &'a dyn Protocol<V>,
    domain: &'a Domain<V>,
    swarm: &'a Swarm<V>,
    net: &'a ProximityNet,
    k: u64,
) -> Perception<'a, V> {
    match stage {
        Some(stage) if stage.perceives && protocol.local_form().is_some() => {
            let graph = protocol.interaction_graph();
            Perception::Heard(Box::new(Heard::new(stage, graph, domain, swarm, net, k)))
        }
        _ => Perception::Truth { domain, swarm, net },
    }
}

/// What the agents hear at step `k` through the conditions: the candidates, the delay line and
/// the links, from which `Heard::block` forms each receiver's perception.
pub struct Heard<'a, V> {
    stage: &'a Stage<V>,
    domain: &'a Domain<V>,
    pub(crate) swarm: &'a Swarm<V>,
    numbering: &'a Numbering,
    /// Whom each receiver may hear: its fixed graph, or the net of the communication range.
    candidates: &'a Graph,
    k: u64,
    comm: Communication,
    /// A communication range cutting a fixed graph's links.
    graph_range: Option<f64>,
    /// The neighbours' states of the delay, all of the same step, and the receivers' own.
    delayed: (&'a [V], &'a [V]),
    own_states: (&'a [V], &'a [V]),
    /// Every candidate heard but for losses (no faults).
    all_heard: bool,
    loss_by_length: bool,
    /// The candidates' lists heard as they are (no faults, ranges or self-links to leave out).
    unfiltered: bool,
    /// The loss probability of links that are memoryless: each packet lost or not by its link's
    /// own word of the step, heard as sent `delay` steps ago, nothing kept of the link.
    memoryless: Option<f64>,
    /// The links the receivers keep, taken from the stage for this update (given back with
    /// the counts by the control stage: [`Stage::controlled`]).
    pub(crate) links: Vec<Vec<Link<V>>>,
}

/// The counts of one control update, summed over the receivers.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Counts {
    /// Candidate links.
    pub(crate) candidates: usize,
    /// Candidate links whose packet was lost.
    pub(crate) lost: usize,
    /// The ages (steps) of the states used.
    pub(crate) age: u64,
    /// States used.
    pub(crate) used: usize,
}

impl core::ops::Add for Counts {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            candidates: self.candidates + o.candidates,
            lost: self.lost + o.lost,
            age: self.age + o.age,
            used: self.used + o.used,
        }
    }
}

/// Receivers are controlled in blocks of this many consecutive agents, their inputs computed
/// together ([`LocalForm::local_inputs`]: the pair terms of a block go through one batch).
pub(crate) const CONTROL_BLOCK: usize = 64;

/// What the control stage gives back to the conditions of a run whose agents heard through
/// them: the links the receivers keep, and the counts of the update.
#[derive(Debug)]
pub(crate) struct Received<V> {
    pub(crate) links: Vec<Vec<Link<V>>>,
    pub(crate) counts: Counts,
}

impl<V> Received<V> {
    /// The links the receivers keep and the counts of the update.
    pub(crate) const fn new(links: Vec<Vec<Link<V>>>, counts: Counts) -> Self {
        Self { links, counts }
    }
}

/// The perceptions of a block of receivers, a CSR: the moving receivers' own perceived states,
/// the states each heard (`heard[ends[r − 1]..ends[r]]`) and their places in the block.
#[derive(Default)]
pub(crate) struct Block<V> {
    pub(crate) owns: Vec<Perceived<V>>,
    pub(crate) heard: Vec<Perceived<V>>,
    pub(crate) ends: Vec<usize>,
    /// The place in the block of each receiver listed.
    pub(crate) receivers: Vec<usize>,
}

impl<V> Block<V> {
    /// The block's perceptions, as a protocol's [`LocalForm`](flock_protocols::LocalForm) reads
    /// them.
    pub(crate) fn perceptions(&self) -> Perceptions<'_, V> {
        Perceptions {
            owns: &self.owns,
            heard: &self.heard,
            ends: &self.ends,
        }
    }
}

/// What a worker reuses from block to block (the buffers keep their capacity): one receiver's
/// candidates `js`, the words of its links' jitter and loss draws, last step's links `old`, and
/// the block's perceptions.
#[derive(Default)]
pub(crate) struct Scratch<V> {
    js: Vec<u32>,
    words: [Vec<u32>; 2],
    old: Vec<Link<V>>,
    pub(crate) block: Block<V>,
}

impl<'a, V: Vector> Heard<'a, V> {
    /// What the agents hear at step `k` through `stage`, the candidates those of the fixed
    /// `graph` if any, else of the communication range's net, built here, or of `net`.
    fn new(
        stage: &'a mut Stage<V>,
        graph: Option<&'a Graph>,
        domain: &'a Domain<V>,
        swarm: &'a Swarm<V>,
        net: &'a ProximityNet,
        k: u64,
    ) -> Self {
        if let Some(range) = stage.own_range.filter(|_| graph.is_none()) {
            // its lists in ascending original index, as the simulation's net lists them
            stage.net.share_numbering(net);
            stage
                .search
                .build_in(domain, &swarm.positions, range, &mut stage.net);
        }
        let links = core::mem::take(&mut stage.links);
        let stage: &'a Stage<V> = stage;
        let candidates = graph.unwrap_or(if stage.own_range.is_some() {
            stage.net.graph()
        } else {
            net.graph()
        });
        let comm = stage.conditions.communication.unwrap_or_default();
        let graph_range = comm.range.filter(|_| graph.is_some());
        let own_lag = if comm.delayed == Delayed::All {
            stage.delay
        } else {
            0
        };
        let all_heard = stage.conditions.faults.is_none();
        let memoryless = match comm.loss {
            Loss::None => Some(0.0),
            Loss::Bernoulli { p } => Some(p),
            Loss::Distance { .. } | Loss::GilbertElliott { .. } => None,
        }
        .filter(|_| stage.jitter == 0 && !comm.symmetric && !keeps_links(&stage.conditions));
        Self {
            stage,
            domain,
            swarm,
            numbering: net.numbering(),
            candidates,
            k,
            comm,
            graph_range,
            delayed: stage.history.slot(k, stage.delay),
            own_states: stage.history.slot(k, own_lag),
            all_heard,
            loss_by_length: matches!(comm.loss, Loss::Distance { .. }),
            // a proximity net lists no agent as its own neighbour
            unfiltered: all_heard && graph_range.is_none() && graph.is_none(),
            memoryless,
            links,
        }
    }

    /// The original index of the agent stored at `j`.
    pub(crate) fn original(&self, j: usize) -> u32 {
        self.numbering.original(j) as u32
    }

    /// The perceptions of the moving receivers among the `len` agents from `start`, into
    /// `w.block`, with `links` their kept links (`None`: links keep nothing); a receiver that
    /// does not move forgets its links. Returns the block's counts.
    pub(crate) fn block(
        &self,
        start: usize,
        len: usize,
        mut links: Option<&mut [Vec<Link<V>>]>,
        w: &mut Scratch<V>,
    ) -> Counts {
        let Scratch {
            js,
            words,
            old,
            block,
        } = w;
        block.heard.clear();
        block.owns.clear();
        block.ends.clear();
        block.receivers.clear();
        let mut counts = Counts::default();
        self.draw_words(start..start + len, words);
        // where the words of the next moving receiver start
        let mut at = 0;
        for r in 0..len {
            let i = start + r;
            let links_i = links.as_deref_mut().map(|l| &mut l[r]);
            if !self.stage.moves(i) {
                if let Some(links_i) = links_i {
                    links_i.clear();
                }
                continue;
            }
            let its_words = words.each_ref().map(|w| w.get(at..).unwrap_or_default());
            at += link_word_count(self.candidates.neighbours(i).len());
            let (own, received) = self.receive(i, links_i, js, its_words, old, &mut block.heard);
            counts = counts + received;
            block.owns.push(own);
            block.ends.push(block.heard.len());
            block.receivers.push(r);
        }
        // the receivers' offsets above follow the receivers `draw_words` drew for
        debug_assert!(
            words.iter().all(|w| w.is_empty() || w.len() == at),
            "every moving receiver's words read where they were drawn"
        );
        counts
    }

    /// The words of the jitter and loss draws of the links into the moving receivers of
    /// `block`, into `words`, receiver after receiver (the candidates of each counted before
    /// any leaves the list: the first words are the same); a purpose not drawn leaves its
    /// words empty.
    fn draw_words(&self, block: Range<usize>, words: &mut [Vec<u32>; 2]) {
        let receivers = block.filter(|&i| self.stage.moves(i)).map(|i| {
            (
                u64::from(self.original(i)),
                self.candidates.neighbours(i).len(),
            )
        });
        let [jitter_words, loss_words] = words;
        for (purpose, drawn, words) in [
            (Purpose::Jitter, self.stage.jitter > 0, jitter_words),
            (Purpose::Loss, self.comm.loss_per_link(), loss_words),
        ] {
            words.clear();
            if drawn {
                self.stage
                    .streams
                    .link_words(purpose, self.k, receivers.clone(), words);
            }
        }
    }

    /// Receiver i's own perceived state and what it hears, appended to `heard`: candidates,
    /// each packet delayed, lost, dropped or replaced by the last value received.
    fn receive(
        &self,
        i: usize,
        mut links_i: Option<&mut Vec<Link<V>>>,
        js: &mut Vec<u32>,
        [jitter_words, loss_words]: [&[u32]; 2],
        old: &mut Vec<Link<V>>,
        heard: &mut Vec<Perceived<V>>,
    ) -> (Perceived<V>, Counts) {
        let (this, domain, k, comm) = (self.stage, self.domain, self.k, self.comm);
        let (delayed, positions) = (self.delayed, &self.swarm.positions);
        let own = Perceived {
            agent: self.original(i),
            position: self.own_states.0[i],
            velocity: self.own_states.1[i],
        };
        // the candidates heard, in ascending original index (a net's and a graph's lists
        // are): the list itself unless failed agents or a communication range leave some out
        let list = self.candidates.neighbours(i);
        let js: &[u32] = if self.unfiltered {
            list
        } else {
            js.clear();
            js.extend(list.iter().copied().filter(|&j| {
                j as usize != i
                    && (self.all_heard || this.is_heard(j as usize))
                    // a fixed graph's link is cut beyond an explicit communication range
                    && self.graph_range.is_none_or(|rc| {
                        domain
                            .displacement(positions[i], positions[j as usize])
                            .length_squared()
                            < rc * rc
                    })
            }));
            js
        };
        debug_assert!(js.is_sorted_by_key(|&j| self.original(j as usize)));
        let first = heard.len();
        // the loop after this one decides the same, one option at a time, at more cost; here
        // each candidate is written and kept if its packet arrives, without a branch on the
        // loss draw (lost packets come at random: the branch would be mispredicted)
        if let Some(p) = self.memoryless {
            debug_assert!(links_i.is_none(), "memoryless links keep nothing");
            heard.resize(first + js.len(), own);
            let mut end = first;
            for (m, &ju) in js.iter().enumerate() {
                let ju = ju as usize;
                heard[end] = Perceived {
                    agent: self.original(ju),
                    position: domain.image_near(own.position, delayed.0[ju]),
                    velocity: delayed.1[ju],
                };
                let dropped = loss_words.get(m).is_some_and(|&w| word_uniform(w) < p);
                end += usize::from(!dropped);
            }
            heard.truncate(end);
            let used = heard.len() - first;
            let counts = Counts {
                candidates: js.len(),
                lost: js.len() - used,
                age: used as u64 * k.min(this.delay),
                used,
            };
            return (own, counts);
        }
        old.clear();
        if let Some(links_i) = links_i.as_deref_mut() {
            old.append(links_i);
        }
        let n = positions.len();
        let (mut lost_count, mut age_sum) = (0usize, 0u64);
        // the link from i's m-th candidate takes word m of i's words of the step
        for (m, &ju) in js.iter().enumerate() {
            let (ju, j) = (ju as usize, self.original(ju as usize));
            // what i keeps of the link (Gilbert–Elliott's channel, the state held), when
            // links keep anything; senders by original index, ascending as the list
            let mut link = links_i.is_some().then(|| {
                old.binary_search_by_key(&j, |l| l.sender)
                    .map_or(Link::new(j), |s| old[s])
            });
            let lag = if this.jitter > 0 {
                this.delay + word_up_to(jitter_words[m], this.jitter)
            } else {
                this.delay
            };
            // a symmetric loss draws once for the unordered pair, both ends alike
            let draw = || {
                if comm.symmetric {
                    let (a, b) = (self.original(i) as usize, j as usize);
                    let pair = (a.min(b) * n + a.max(b)) as u64;
                    this.streams.uniform(Purpose::Loss, pair, k)
                } else {
                    word_uniform(loss_words[m])
                }
            };
            // the link's length, read by distance loss only
            let length = if self.loss_by_length {
                domain.displacement(positions[i], positions[ju]).length()
            } else {
                f64::NAN
            };
            let mut no_channel = None;
            let channel = link.as_mut().map_or(&mut no_channel, |l| &mut l.channel);
            let dropped = lost(&comm.loss, draw, k, this.h, length, channel);
            let stamp = k.saturating_sub(lag);
            let used = if dropped {
                lost_count += 1;
                match (comm.when_lost, link.and_then(|l| l.held)) {
                    (WhenLost::Hold { max_age }, Some(held))
                        if (k - held.stamp) as f64 * this.h <= max_age * (1.0 + 1e-12) =>
                    {
                        Some(held)
                    }
                    _ => None,
                }
            } else {
                let (position, velocity) = if lag == this.delay {
                    (delayed.0[ju], delayed.1[ju])
                } else {
                    this.history.at(k, lag, ju)
                };
                let held = Held {
                    position,
                    velocity,
                    stamp,
                };
                if let Some(link) = link.as_mut() {
                    link.held = Some(held);
                }
                Some(held)
            };
            if let Some(held) = used {
                age_sum += k - held.stamp.min(k);
                heard.push(Perceived {
                    agent: j,
                    position: domain.image_near(own.position, held.position),
                    velocity: held.velocity,
                });
            }
            if let (Some(links_i), Some(link)) = (links_i.as_deref_mut(), link) {
                links_i.push(link);
            }
        }
        let counts = Counts {
            candidates: js.len(),
            lost: lost_count,
            age: age_sum,
            used: heard.len() - first,
        };
        (own, counts)
    }
}
