//! What a checkpoint keeps of the conditions ([`ConditionsState`]): with it, a resumed run
//! continues with the bits of the uninterrupted one, since every random draw is keyed by step
//! ([`stream`](flock_math::stream)) and this is all the state the conditions carry between steps.

use flock_graph::Numbering;
use flock_math::Vector;
use flock_math::stream::Streams;

use super::links::{Held, Link};
use super::stage::{Readings, Stage};
use crate::permutation::permute_in_place;
use flock_protocols::error::ParamError;

/// One link kept by a receiver: the sender, the Gilbert–Elliott state (bad, step drawn) and
/// the last state received (position, velocity, step measured).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[allow(missing_docs)]
pub struct LinkState {
    pub sender: u32,
    pub channel: Option<(bool, u64)>,
    pub held: Option<(Vec<f64>, Vec<f64>, u64)>,
}

/// The state of the conditions between two steps, vectors flattened (`dim` coordinates each).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ConditionsState {
    /// The scenario seed.
    pub seed: u64,
    /// The dimension of the vectors.
    pub dim: usize,
    /// Whether a step has been taken (the noise, gusts and history are initialised).
    pub started: bool,
    /// The sensor noise offsets (position, velocity) per agent.
    pub noise: (Vec<f64>, Vec<f64>),
    /// The delay line, slot by slot (positions, velocities); its newest slot is the measured
    /// state, held between sensor updates. (Checkpoints written before it held that state also
    /// kept a `measured` field, the same numbers, which is not read.)
    pub history: Vec<(Vec<f64>, Vec<f64>)>,
    /// The links each receiver keeps, by receiver.
    pub links: Vec<Vec<LinkState>>,
    /// The held commanded inputs.
    pub inputs: Vec<f64>,
    /// The delivered (lagged) accelerations; empty when the run delivers the inputs of each
    /// step (no lag, no sampled control), whose older checkpoints' values are not read.
    pub delivered: Vec<f64>,
    /// The wind gusts (one shared, or one per agent).
    pub gust: Vec<f64>,
    /// The failed agents.
    pub failed: Vec<bool>,
    /// The last readings: links lost, information age, at acceleration limit, at speed limit.
    pub readings: [f64; 4],
}

fn flat<V: Vector>(v: &[V]) -> Vec<f64> {
    v.iter()
        .flat_map(|x| (0..V::DIM).map(move |d| x.coord(d)))
        .collect()
}

fn vectors<V: Vector>(field: &str, x: &[f64], len: usize) -> Result<Vec<V>, ParamError> {
    if let Some(bad) = x.iter().find(|v| !v.is_finite()) {
        return Err(ParamError::new(
            field,
            bad,
            "is not finite: no run keeps such a state",
            "restore the state of a run of the same agents, dimension and conditions",
        ));
    }
    if x.len() != len * V::DIM {
        return Err(ParamError::new(
            field,
            x.len(),
            format!(
                "holds {} numbers where {len} vectors of {} are expected",
                x.len(),
                V::DIM
            ),
            "restore the state of a run of the same agents, dimension and conditions",
        ));
    }
    Ok(x.chunks_exact(V::DIM)
        .map(|c| V::from_fn(|d| c[d]))
        .collect())
}

impl<V: Vector> Stage<V> {
    /// The state to checkpoint, agent by agent in original order (the agents stored as
    /// `numbering` says), with the run's `inputs` (held between control updates).
    #[must_use]
    pub fn state(&self, numbering: &Numbering, inputs: &[V]) -> ConditionsState {
        // one row per agent, in original order
        let ordered = |x: &[V]| flat(&numbering.rows_in_original_order(x, 1));
        let noise = numbering.rows_in_original_order(&self.noise, 1);
        let (nq, np): (Vec<V>, Vec<V>) = noise.iter().copied().unzip();
        let r = self.readings;
        ConditionsState {
            seed: self.streams.seed(),
            dim: V::DIM,
            started: self.started,
            noise: (flat(&nq), flat(&np)),
            history: self
                .history
                .slots
                .iter()
                .map(|(q, p)| (ordered(q), ordered(p)))
                .collect(),
            links: numbering
                .rows_in_original_order(&self.links, 1)
                .iter()
                .map(|ls| {
                    ls.iter()
                        .map(|l| LinkState {
                            sender: l.sender,
                            channel: l.channel,
                            held: l
                                .held
                                .map(|h| (flat(&[h.position]), flat(&[h.velocity]), h.stamp)),
                        })
                        .collect()
                })
                .collect(),
            inputs: ordered(inputs),
            delivered: ordered(&self.delivered),
            gust: if self.gusts_per_agent() {
                ordered(&self.gust)
            } else {
                flat(&self.gust)
            },
            failed: numbering
                .rows_in_original_order(&self.failed, 1)
                .into_owned(),
            readings: [
                r.links_lost,
                r.information_age,
                r.at_acceleration_limit,
                r.at_speed_limit,
            ],
        }
    }

    /// Restores a checkpointed state (agents in original order) into this stage (built from the
    /// same conditions) and the run's `inputs`, of agents stored as `numbering` says.
    ///
    /// # Errors
    /// A state of another dimension, number of agents, delay or wind (field `conditions_state.…`).
    pub fn restore(
        &mut self,
        s: ConditionsState,
        numbering: &Numbering,
        inputs: &mut Vec<V>,
    ) -> Result<(), ParamError> {
        self.restore_as_stored(s, inputs)?;
        if !numbering.is_identity() && self.started {
            permute_in_place(inputs, |s| numbering.original(s));
            self.permute(|s| numbering.original(s));
        }
        Ok(())
    }

    /// [`Stage::restore`] into agents stored in original order.
    fn restore_as_stored(
        &mut self,
        s: ConditionsState,
        inputs: &mut Vec<V>,
    ) -> Result<(), ParamError> {
        let n = self.failed.len();
        let within = |e: ParamError| e.within("conditions_state");
        let check_len = |field: &str, got: usize, want: usize| {
            if got == want {
                Ok(())
            } else {
                Err(ParamError::new(
                    field,
                    got,
                    format!("has {got} entries where this run has {want}"),
                    "restore the state of a run of the same agents and conditions",
                )
                .within("conditions_state"))
            }
        };
        check_len("dim", s.dim, V::DIM)?;
        check_len("failed", s.failed.len(), n)?;
        check_len("links", s.links.len(), self.links.len())?;
        check_len("history", s.history.len(), self.history.slots.len())?;
        let noise_len = self.noise.len();
        let nq: Vec<V> = vectors("noise", &s.noise.0, noise_len).map_err(within)?;
        let np: Vec<V> = vectors("noise", &s.noise.1, noise_len).map_err(within)?;
        self.noise = nq.into_iter().zip(np).collect();
        // a run whose agents perceive the truth keeps no agent's state in it (read by none)
        let width = self.history.agents();
        if width > 0 {
            for (slot, (q, p)) in self.history.slots.iter_mut().zip(&s.history) {
                slot.0 = vectors("history", q, width).map_err(within)?;
                slot.1 = vectors("history", p, width).map_err(within)?;
            }
        }
        let mut links = Vec::with_capacity(n);
        for ls in &s.links {
            let mut kept = Vec::with_capacity(ls.len());
            for l in ls {
                if l.sender as usize >= n {
                    return Err(ParamError::new(
                        "links",
                        l.sender,
                        format!("names a sender of {n} agents"),
                        "restore the state of a run of the same agents and conditions",
                    )
                    .within("conditions_state"));
                }
                let held = match &l.held {
                    Some((q, p, stamp)) => Some(Held {
                        position: vectors::<V>("links", q, 1).map_err(within)?[0],
                        velocity: vectors::<V>("links", p, 1).map_err(within)?[0],
                        stamp: *stamp,
                    }),
                    None => None,
                };
                kept.push(Link {
                    sender: l.sender,
                    channel: l.channel,
                    held,
                });
            }
            links.push(kept);
        }
        self.links = links;
        *inputs = vectors("inputs", &s.inputs, n).map_err(within)?;
        if !self.delivered.is_empty() {
            self.delivered = vectors("delivered", &s.delivered, n).map_err(within)?;
        }
        self.gust = vectors("gust", &s.gust, self.gust.len()).map_err(within)?;
        self.failed = s.failed;
        self.started = s.started;
        self.streams = Streams::new(s.seed);
        let [
            links_lost,
            information_age,
            at_acceleration_limit,
            at_speed_limit,
        ] = s.readings;
        self.readings = Readings {
            links_lost,
            information_age,
            at_acceleration_limit,
            at_speed_limit,
        };
        Ok(())
    }
}
