//! What a scenario's `conditions` section says: every part optional and off by default, each
//! parameter in SI units, validated with the field's dotted path ([`Conditions::validate`]).

use flock_protocols::error::{ParamError, check};

/// The real conditions of a run. `Conditions::default()` (every part `None`) is the ideal run.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct Conditions {
    /// Delay, a communication range and packet loss between agents.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub communication: Option<Communication>,
    /// Noise on the states agents measure of themselves (and send to others).
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub sensing: Option<Sensing>,
    /// A controller that runs at its own rate, holding its input between updates.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub control: Option<SampledControl>,
    /// Limits and lag of the delivered acceleration.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub actuation: Option<Actuation>,
    /// Wind and process noise.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub disturbance: Option<Disturbance>,
    /// Agents that fail.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub faults: Option<Faults>,
}

/// Whose states the delay applies to.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Delayed {
    /// Agent i uses its own current state and its neighbours' states from t − τ (robotsim).
    #[default]
    Neighbours,
    /// Agent i's own state is delayed too: u_i(t) is computed from the states at t − τ
    /// (Olfati-Saber & Murray, IEEE TAC 49(9), 2004: ẋ = −L x(t − τ)).
    All,
}

/// Packet loss on each directed link j → i, drawn at every control update.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Loss {
    /// Every packet arrives.
    #[default]
    None,
    /// Each packet is lost with probability `p`, independently.
    Bernoulli {
        /// The loss probability, in [0, 1].
        p: f64,
    },
    /// A two-state (good/bad) Markov chain per link: good → bad at rate `p_fail` per second,
    /// bad → good at rate `p_recover` per second; packets are lost in the bad state. Long-run
    /// loss fraction p_fail / (p_fail + p_recover).
    GilbertElliott {
        /// Transition rate good → bad (1/s), ≥ 0.
        p_fail: f64,
        /// Transition rate bad → good (1/s), > 0.
        p_recover: f64,
    },
    /// p(ℓ) = p₀ (ℓ / ℓ₀)², capped at 1, for a link of length ℓ.
    Distance {
        /// The loss probability p₀ at the reference distance, in [0, 1].
        p0: f64,
        /// The reference distance ℓ₀ (m), > 0.
        l0: f64,
    },
}

/// What a receiver does when a neighbour's packet is lost.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum WhenLost {
    /// The neighbour is left out of this control update.
    #[default]
    Drop,
    /// The last state received from it is used, while it is at most `max_age` seconds old.
    Hold {
        /// The oldest information used (s), ≥ 0.
        max_age: f64,
    },
}

/// Delay, communication range and packet loss.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct Communication {
    /// The delay τ (s): a whole number of integration steps, ≥ 0.
    pub delay: f64,
    /// The jitter (s): each packet is delayed by τ plus a whole number of steps drawn uniformly
    /// in [0, jitter], ≥ 0.
    pub jitter: f64,
    /// Whose states are delayed.
    pub delayed: Delayed,
    /// The communication range (m): agents farther apart hear nothing. `None`: the protocol's
    /// interaction range r.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub range: Option<f64>,
    /// Packet loss per directed link.
    pub loss: Loss,
    /// Whether both directions of a link are lost together (true) or independently (false).
    pub symmetric: bool,
    /// What a receiver does with a lost packet.
    pub when_lost: WhenLost,
}

impl Default for Communication {
    fn default() -> Self {
        Self {
            delay: 0.0,
            jitter: 0.0,
            delayed: Delayed::Neighbours,
            range: None,
            loss: Loss::None,
            symmetric: false,
            when_lost: WhenLost::Drop,
        }
    }
}

/// The noise process of a measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Noise {
    /// Independent Gaussian noise at every sensor update, standard deviations `sigma_q` (m) on
    /// each position coordinate and `sigma_p` (m/s) on each velocity coordinate.
    White {
        /// σ_q (m), ≥ 0.
        sigma_q: f64,
        /// σ_p (m/s), ≥ 0.
        sigma_p: f64,
    },
    /// An Ornstein–Uhlenbeck process per coordinate (GPS-like, a correlated random walk pulled
    /// back to 0) with stationary standard deviations `sigma_q`, `sigma_p` and correlation time
    /// `correlation_time` (s), sampled exactly at each sensor update.
    OrnsteinUhlenbeck {
        /// Stationary σ_q (m), ≥ 0.
        sigma_q: f64,
        /// Stationary σ_p (m/s), ≥ 0.
        sigma_p: f64,
        /// Correlation time θ (s), > 0.
        correlation_time: f64,
    },
}

impl Noise {
    /// No noise: white noise of zero deviations (the measurement is exact).
    pub const NONE: Self = Self::White {
        sigma_q: 0.0,
        sigma_p: 0.0,
    };

    /// [`Noise::NONE`] (serde's default of [`Sensing::noise`]).
    #[must_use]
    pub const fn none() -> Self {
        Self::NONE
    }

    /// Whether this is [`Noise::NONE`].
    #[must_use]
    pub fn is_none(&self) -> bool {
        *self == Self::NONE
    }
}

/// Noise on what each agent measures of its own state; the measured state is what it uses for
/// itself and what it sends to the others.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Sensing {
    /// The noise process; by default none ([`Noise::NONE`], white noise of zero deviations): a
    /// sensor at `rate` that measures exactly. Always written back (a sweep's path
    /// `conditions.sensing.noise.White.sigma_q` goes through it).
    #[cfg_attr(feature = "serde", serde(default = "Noise::none"))]
    pub noise: Noise,
    /// The sensor rate (Hz): the measurement is refreshed every 1/rate seconds (a whole number
    /// of steps) and held between. `None`: at every step.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub rate: Option<f64>,
}

/// A controller that runs every 1/rate seconds (a whole number of steps) and holds its input
/// between updates (zero-order hold), while the integrator keeps its own step.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct SampledControl {
    /// The control rate (Hz), > 0.
    pub rate: f64,
}

/// What the actuators deliver of the commanded acceleration u_i.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct Actuation {
    /// The largest acceleration (m/s²): u_i is clipped to this norm. `None`: no limit.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub max_acceleration: Option<f64>,
    /// The largest speed (m/s): ‖p_i‖ is clipped to it after each step. `None`: no limit.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub max_speed: Option<f64>,
    /// The time constant τ_a (s) of a first-order lag ȧ = (u − a)/τ_a on the delivered
    /// acceleration a. `None`: delivered at once.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub lag: Option<f64>,
}

/// Wind: a force per unit mass (m/s²), its mean plus Ornstein–Uhlenbeck gusts.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Wind {
    /// The mean w (m/s²), one component per dimension.
    pub mean: Vec<f64>,
    /// The gusts' stationary standard deviation per component (m/s²), ≥ 0.
    #[cfg_attr(feature = "serde", serde(default))]
    pub gust: f64,
    /// The gusts' correlation time (s), > 0 when `gust` > 0.
    #[cfg_attr(feature = "serde", serde(default = "one_second"))]
    pub correlation_time: f64,
    /// Whether each agent has its own gusts (true) or every agent feels the same (false).
    #[cfg_attr(feature = "serde", serde(default))]
    pub per_agent: bool,
}

#[cfg(feature = "serde")]
const fn one_second() -> f64 {
    1.0
}

/// Wind and additive process noise on the velocity.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct Disturbance {
    /// The wind. `None`: still air.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub wind: Option<Wind>,
    /// σ (m/s per √s): each step adds σ √h ξ to every velocity component (Euler–Maruyama).
    pub process_noise: f64,
}

/// How a failed agent behaves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum FaultMode {
    /// Gone from the run: nobody hears it, it no longer moves, the metrics leave it out.
    #[default]
    Removed,
    /// It stops where it is (p = 0, no input) and is still seen by the others.
    Frozen,
    /// It flies on under its own control but nobody hears it.
    Silent,
}

/// One agent failing at a given time.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Failure {
    /// The agent's index.
    pub agent: usize,
    /// When it fails (s), ≥ 0.
    pub time: f64,
}

/// Agents that fail, at given times or at random.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct Faults {
    /// Agents that fail at given times.
    pub at: Vec<Failure>,
    /// The failure rate per agent per second (each working agent fails within a step h with
    /// probability 1 − e^(−rate h)), ≥ 0.
    pub rate: f64,
    /// How failed agents behave.
    pub mode: FaultMode,
}

/// Checks that `seconds` is a whole number of steps `h` (to 1e-9 relative) and returns it.
///
/// # Errors
/// When it is not, saying the two nearest whole numbers of steps.
pub fn whole_steps(field: &str, seconds: f64, h: f64) -> Result<u64, ParamError> {
    check::non_negative(field, seconds)?;
    let steps = (seconds / h).round();
    if (steps * h - seconds).abs() > 1e-9 * seconds.max(h) {
        let below = (seconds / h).floor();
        return Err(ParamError::new(
            field,
            seconds,
            format!("is not a whole number of steps of {h} s"),
            format!(
                "write {} or {} (or change `step`)",
                steps_text(below, h),
                steps_text(below + 1.0, h)
            ),
        ));
    }
    Ok(steps as u64)
}

/// `k` steps of `h` seconds as the shortest decimal within round-off of k h: 6 steps of 0.01 s
/// are `0.06`, not the `0.060000000000000005` of the product.
fn steps_text(k: f64, h: f64) -> String {
    let seconds = k * h;
    (0..17)
        .map(|digits| format!("{seconds:.digits$}"))
        .find(|text| {
            text.parse::<f64>()
                .is_ok_and(|x| (x - seconds).abs() <= 1e-9 * h)
        })
        .unwrap_or_else(|| seconds.to_string())
}

/// Checks that a rate (Hz) gives a period that is a whole number ≥ 1 of steps `h`, and returns
/// that number of steps.
///
/// # Errors
/// A rate that is not positive, or whose period is not a whole number of steps, or shorter
/// than one step.
pub fn period_steps(field: &str, rate: f64, h: f64) -> Result<u64, ParamError> {
    check::positive(field, rate)?;
    let steps = whole_steps(field, 1.0 / rate, h).map_err(|e| ParamError {
        value: format!("{rate:?}"),
        why: format!(
            "gives a period 1/{rate} s that {}",
            e.why.trim_start_matches("is ")
        ),
        fix: format!(
            "choose a rate whose period is a whole number of steps of {h} s, such as {}",
            1.0 / (h * (1.0 / (rate * h)).round().max(1.0))
        ),
        ..e
    })?;
    check::require(
        steps >= 1,
        field,
        rate,
        &format!("is faster than the integration step {h} s"),
        &format!("use a rate of at most {} Hz, or a smaller `step`", 1.0 / h),
    )?;
    Ok(steps)
}

impl Conditions {
    /// Whether no condition is set: the ideal run.
    #[must_use]
    pub fn is_ideal(&self) -> bool {
        *self == Self::default()
    }

    /// Whether a condition draws random numbers: jitter, packet loss, sensing noise, wind gusts,
    /// process noise, random failures.
    #[must_use]
    pub fn draws_at_random(&self) -> bool {
        let communication = self
            .communication
            .is_some_and(|c| c.jitter > 0.0 || c.loss != Loss::None);
        let faults = self.faults.as_ref().is_some_and(|f| f.rate > 0.0);
        communication || self.draws_normals() || faults
    }

    /// Whether a condition draws random numbers per link: jitter, packet loss that is not
    /// symmetric (drawn from the receiver's words, [`Streams::link_words`]).
    ///
    /// [`Streams::link_words`]: flock_math::stream::Streams::link_words
    #[must_use]
    pub fn draws_per_link(&self) -> bool {
        self.communication
            .is_some_and(|c| c.jitter > 0.0 || c.loss_per_link())
    }

    /// Whether a condition draws normal random numbers: sensing noise, wind gusts, process
    /// noise.
    #[must_use]
    pub fn draws_normals(&self) -> bool {
        let disturbance = self.disturbance.as_ref().is_some_and(|d| {
            d.process_noise > 0.0 || d.wind.as_ref().is_some_and(|w| w.gust > 0.0)
        });
        self.sensing.is_some() || disturbance
    }

    /// Checks every parameter for a run of `agents` agents in `dim` dimensions at step `h`;
    /// fields are named from `conditions`, e.g. `conditions.communication.loss.p`.
    ///
    /// # Errors
    /// The first parameter outside its domain: a probability outside [0, 1], a negative σ or
    /// time, a delay or period that is not a whole number of steps, a wind of the wrong
    /// dimension, an agent index out of range.
    pub fn validate(&self, agents: usize, dim: usize, h: f64) -> Result<(), ParamError> {
        let within = |prefix: &'static str| move |e: ParamError| e.within(prefix);
        if let Some(c) = &self.communication {
            c.validate(h).map_err(within("conditions.communication"))?;
        }
        if let Some(s) = &self.sensing {
            s.validate(h).map_err(within("conditions.sensing"))?;
        }
        if let Some(c) = &self.control {
            period_steps("rate", c.rate, h).map_err(within("conditions.control"))?;
        }
        if let Some(a) = &self.actuation {
            a.validate().map_err(within("conditions.actuation"))?;
        }
        if let Some(d) = &self.disturbance {
            d.validate(dim).map_err(within("conditions.disturbance"))?;
        }
        if let Some(f) = &self.faults {
            f.validate(agents).map_err(within("conditions.faults"))?;
        }
        Ok(())
    }
}

impl Communication {
    /// Whether each packet's loss is drawn on its own (from the receiver's words,
    /// [`Streams::link_words`]): a loss that is not symmetric.
    ///
    /// [`Streams::link_words`]: flock_math::stream::Streams::link_words
    #[must_use]
    pub fn loss_per_link(&self) -> bool {
        self.loss != Loss::None && !self.symmetric
    }

    fn validate(&self, h: f64) -> Result<(), ParamError> {
        whole_steps("delay", self.delay, h)?;
        whole_steps("jitter", self.jitter, h)?;
        if let Some(range) = self.range {
            check::length("range", range)?;
        }
        match self.loss {
            Loss::None => {}
            Loss::Bernoulli { p } => probability("loss.p", p)?,
            Loss::GilbertElliott { p_fail, p_recover } => {
                check::non_negative("loss.p_fail", p_fail)?;
                check::positive("loss.p_recover", p_recover)?;
            }
            Loss::Distance { p0, l0 } => {
                probability("loss.p0", p0)?;
                check::length("loss.l0", l0)?;
            }
        }
        if let WhenLost::Hold { max_age } = self.when_lost {
            check::non_negative("when_lost.max_age", max_age)?;
        }
        Ok(())
    }
}

impl Sensing {
    fn validate(&self, h: f64) -> Result<(), ParamError> {
        let (sigma_q, sigma_p) = match self.noise {
            Noise::White { sigma_q, sigma_p } => (sigma_q, sigma_p),
            Noise::OrnsteinUhlenbeck {
                sigma_q,
                sigma_p,
                correlation_time,
            } => {
                check::positive("noise.correlation_time", correlation_time)?;
                (sigma_q, sigma_p)
            }
        };
        check::non_negative("noise.sigma_q", sigma_q)?;
        check::non_negative("noise.sigma_p", sigma_p)?;
        if let Some(rate) = self.rate {
            period_steps("rate", rate, h)?;
        }
        Ok(())
    }
}

impl Actuation {
    fn validate(&self) -> Result<(), ParamError> {
        for (field, value) in [
            ("max_acceleration", self.max_acceleration),
            ("max_speed", self.max_speed),
            ("lag", self.lag),
        ] {
            if let Some(value) = value {
                check::positive(field, value)?;
            }
        }
        Ok(())
    }
}

impl Disturbance {
    fn validate(&self, dim: usize) -> Result<(), ParamError> {
        check::non_negative("process_noise", self.process_noise)?;
        if let Some(wind) = &self.wind {
            check::require(
                wind.mean.len() == dim,
                "wind.mean",
                &wind.mean,
                &format!("has {} components in a {dim}D scenario", wind.mean.len()),
                &format!("give {dim} components"),
            )?;
            check::coordinates("wind.mean", &wind.mean)?;
            check::non_negative("wind.gust", wind.gust)?;
            check::positive("wind.correlation_time", wind.correlation_time)?;
        }
        Ok(())
    }
}

impl Faults {
    fn validate(&self, agents: usize) -> Result<(), ParamError> {
        check::non_negative("rate", self.rate)?;
        for (k, failure) in self.at.iter().enumerate() {
            check::require(
                failure.agent < agents,
                &format!("at[{k}].agent"),
                failure.agent,
                &format!("is not an agent of this run ({agents} agents)"),
                &format!("use an index from 0 to {}", agents.saturating_sub(1)),
            )?;
            check::non_negative(&format!("at[{k}].time"), failure.time)?;
        }
        Ok(())
    }
}

/// A probability in [0, 1].
fn probability(field: &str, p: f64) -> Result<(), ParamError> {
    check::finite(field, p)?;
    check::require(
        (0.0..=1.0).contains(&p),
        field,
        p,
        "is a probability outside [0, 1]",
        "give a value from 0 to 1",
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_is_ideal_and_valid() {
        assert!(Conditions::default().is_ideal());
        assert!(Conditions::default().validate(10, 2, 0.01).is_ok());
    }

    #[test]
    fn a_delay_must_be_a_whole_number_of_steps_and_the_error_says_what_to_write() {
        assert_eq!(whole_steps("delay", 0.1, 0.01), Ok(10));
        assert_eq!(whole_steps("delay", 0.0, 0.01), Ok(0));
        let e = whole_steps("delay", 0.105, 0.01).unwrap_err();
        assert_eq!(e.field, "delay");
        assert!(e.fix.contains("0.1") && e.fix.contains("0.11"), "{e}");
        // 6 × 0.01 is 0.060000000000000005 in floating point: the fix writes 0.06
        let e = whole_steps("delay", 0.055, 0.01).unwrap_err();
        assert_eq!(e.fix, "write 0.05 or 0.06 (or change `step`)");
        let e = whole_steps("delay", 0.0012, 0.0005).unwrap_err();
        assert_eq!(e.fix, "write 0.001 or 0.0015 (or change `step`)");
    }

    #[test]
    fn a_rate_gives_a_whole_period_of_steps() {
        assert_eq!(period_steps("rate", 10.0, 0.01), Ok(10));
        let e = period_steps("rate", 30.0, 0.01).unwrap_err();
        assert!(e.why.contains("1/30"), "{e}");
        let fast = period_steps("rate", 1000.0, 0.01).unwrap_err();
        assert!(
            fast.why.contains("whole number") || fast.why.contains("faster"),
            "{fast}"
        );
    }

    #[test]
    fn every_bad_value_is_named_by_its_path() {
        let bad = |conditions: Conditions| conditions.validate(5, 2, 0.01).unwrap_err().field;
        let communication = |c: Communication| Conditions {
            communication: Some(c),
            ..Conditions::default()
        };
        assert_eq!(
            bad(communication(Communication {
                loss: Loss::Bernoulli { p: 1.5 },
                ..Communication::default()
            })),
            "conditions.communication.loss.p"
        );
        assert_eq!(
            bad(communication(Communication {
                delay: -0.1,
                ..Communication::default()
            })),
            "conditions.communication.delay"
        );
        assert_eq!(
            bad(Conditions {
                sensing: Some(Sensing {
                    noise: Noise::White {
                        sigma_q: -1.0,
                        sigma_p: 0.0
                    },
                    rate: None
                }),
                ..Conditions::default()
            }),
            "conditions.sensing.noise.sigma_q"
        );
        assert_eq!(
            bad(Conditions {
                disturbance: Some(Disturbance {
                    wind: Some(Wind {
                        mean: vec![1.0, 0.0, 0.0],
                        gust: 0.0,
                        correlation_time: 1.0,
                        per_agent: false
                    }),
                    process_noise: 0.0
                }),
                ..Conditions::default()
            }),
            "conditions.disturbance.wind.mean"
        );
        assert_eq!(
            bad(Conditions {
                faults: Some(Faults {
                    at: vec![Failure {
                        agent: 5,
                        time: 1.0
                    }],
                    ..Faults::default()
                }),
                ..Conditions::default()
            }),
            "conditions.faults.at[0].agent"
        );
    }
}
