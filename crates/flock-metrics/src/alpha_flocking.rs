//! Whether a run performed α-flocking: TAC 2006 Definition 5 (seed 002, "What constitutes
//! flocking?") judged on recorded metrics over a time window.
//!
//! Definition 5: a group performs *α-flocking* over [t₀, t_f] if, for all t in it, with an
//! interaction range r = (1 + ε₀) d,
//!
//! 1. the group remains a quasi-flock (the net G(q(t)) has a giant component),
//! 2. the group remains cohesive,
//! 3. the deviation energy remains small, E(q(t)) ≤ ε₁ d², i.e. Ẽ ≤ ε₁,
//! 4. the velocity mismatch remains small, K(v(t)) ≤ ε₂ n, i.e. K̃ ≤ ε₂;
//!
//! and *strict α-flocking* if a) the net remains connected (a flock), b) Ẽ ≤ ε₁ and c) K̃ ≤ ε₂.
//!
//! [`FlockingVerdict::judge`] checks these conditions at every record of the window
//! ([`FlockingCriteria`]; the metrics must have been measured on the proximity net of range r,
//! as [`FlockMetrics::measure`] does — r = 1.2 d, ε₀ = 0.2 in the papers). The definition leaves
//! four things to the reader, fixed here and settable:
//!
//! - **ε₁** ("a relatively small number"): 0.01 by default. Ẽ ≤ 0.01 means a root mean square
//!   edge-length error of at most 0.1 d (the quasi α-lattice of uncertainty δ = 0.1 d of
//!   [`LatticeSummary`](crate::LatticeSummary)): Ẽ is already relative to the lattice's scale d.
//! - **ε₂, relative to the group's speed.** K̃ has the units of a speed squared, so a fixed ε₂
//!   would judge a flock by its units: at 0.11 m/s, K̃ = 0.0064 m²/s² is a velocity spread as
//!   large as the speed itself, at 25 m/s a tiny one. Condition 4 is judged as K̃(t) ≤ ε₂ s(t)²:
//!   the spread √(2K̃) of the velocities about their mean p_c may be at most √(2ε₂) ≈ 14 % of a
//!   speed s, the group's speed s = ‖p_c‖ ([`FlockMetrics::group_speed`]). A group that has come
//!   to rest (a rendezvous: ‖p_c‖ → 0) has no speed to compare with, and a scale of ‖p_c‖ would
//!   ask it for an exact rest: a group slower than √(2ε₂) v̂ — than the spread a flock at the
//!   speed of its approach may have — counts as at rest, and its spread is compared with that
//!   speed, s = v̂(t), the largest root-mean-square speed v_rms = √(‖p_c‖² + 2K̃) of the agents at
//!   any record up to t. ε₂ = 0.01 by default, dimensionless; at ‖p_c‖ = 1 m/s, the papers' group
//!   speeds, the test is the papers' absolute K̃ ≤ 0.01 m²/s².
//! - **"giant component"**: C* ≥ 0.9 by default — seed 004 (eq. 7) calls a net of density δ₀ = C*
//!   with 0 < 1 − δ₀ ≪ 1 a quasi-flock, and its six-obstacle run ends at δ₀ = 0.97.
//! - **"cohesive"** (all agents within a ball of radius R around q_c): over a finite window every
//!   trajectory is bounded, so cohesion needs a number. By default the cohesion radius R(t) may
//!   not grow by more than 10 % above its value at the start of the window (agents leaving the
//!   group make it grow without bound); [`Cohesion::Radius`] bounds R(t) by a given radius instead.
//!
//! A strict α-flock is here an α-flock that is also connected (condition a) **and collision-free**:
//! no pair closer than the collision distance (by default d/4, [`MetricParams`](crate::MetricParams))
//! at any record of the window. The definition's "flock" is a group of agents kept apart by the
//! α-lattice; agents that have merged (closer than 10⁻³ d, where the α-force along the σ-norm's
//! gradient vanishes and cannot separate them) or keep colliding satisfy Ẽ ≤ ε₁ only because a
//! few short edges weigh little in a mean, and are not one. A strict verdict thus implies the
//! α-flocking verdict, never contradicts it.
//!
//! Flocking is a property of a group: a window with a record of fewer than two agents (one agent
//! left, or every agent removed by faults) has no verdict (neither condition holds, the display
//! says "undefined").

use core::fmt;

use crate::FlockMetrics;

/// The records over which Definition 5 is checked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Window {
    /// The last fraction f ∈ (0, 1] of the recorded time span: t ≥ t_f − f (t_f − t_first).
    LastFraction(f64),
    /// The records with `from` ≤ t ≤ `to`.
    Between {
        /// t₀.
        from: f64,
        /// t_f.
        to: f64,
    },
}

impl Default for Window {
    /// The last quarter of the run.
    fn default() -> Self {
        Self::LastFraction(0.25)
    }
}

/// What "the group remains cohesive" means over the window.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cohesion {
    /// R(t) ≤ (1 + `growth`) R(t₀) at every record: the group does not spread out.
    NonGrowing {
        /// The allowed relative growth of the cohesion radius.
        growth: f64,
    },
    /// R(t) ≤ this radius at every record.
    Radius(f64),
}

impl Default for Cohesion {
    /// [`Cohesion::NonGrowing`] with 10 % growth.
    fn default() -> Self {
        Self::NonGrowing { growth: 0.1 }
    }
}

/// The thresholds of Definition 5 and the window (see the [module](self) for the defaults).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlockingCriteria {
    /// The records judged.
    pub window: Window,
    /// ε₁: Ẽ = E / d² ≤ ε₁.
    pub epsilon1: f64,
    /// ε₂ (dimensionless): K̃ ≤ ε₂ s², s the group's speed ‖p_c‖, or for a group at rest
    /// (‖p_c‖ < √(2ε₂) v̂) the largest root-mean-square speed v̂ of its agents so far (see the
    /// [module](self)).
    pub epsilon2: f64,
    /// The least C* = |giant component| / n of a quasi-flock.
    pub giant_share: f64,
    /// The cohesion test.
    pub cohesion: Cohesion,
}

impl Default for FlockingCriteria {
    /// Last quarter, ε₁ = ε₂ = 0.01, C* ≥ 0.9, R growing by at most 10 %.
    fn default() -> Self {
        Self {
            window: Window::default(),
            epsilon1: 0.01,
            epsilon2: 0.01,
            giant_share: 0.9,
            cohesion: Cohesion::default(),
        }
    }
}

impl FlockingCriteria {
    /// The times (t₀, t_f) of the window of records spanning [`first`, `last`].
    #[must_use]
    pub fn bounds(&self, first: f64, last: f64) -> (f64, f64) {
        match self.window {
            Window::LastFraction(f) => (last - f * (last - first), last),
            Window::Between { from, to } => (from, to),
        }
    }
}

/// Definition 5 evaluated over a window: the extreme values of the metrics there and the verdict
/// on each condition.
///
/// # Example
/// ```
/// use flock_metrics::{FlockMetrics, FlockingCriteria, FlockingVerdict};
///
/// let settled = FlockMetrics {
///     connectivity: 1.0,
///     giant_component: 1.0,
///     components: 1,
///     cohesion_radius: 20.0,
///     deviation_energy: 1e-4,
///     velocity_mismatch: 1e-6,
///     min_distance: 6.5,
///     collisions: 0,
///     polarisation: 1.0,
///     milling: 0.0,
///     nearest_neighbour_mean: 7.0,
///     nearest_neighbour_min: 6.5,
///     group_speed: 1.0,
/// };
/// let records: Vec<(f64, FlockMetrics)> = (0..=100).map(|k| (f64::from(k), settled)).collect();
/// let verdict = FlockingVerdict::judge(&records, &FlockingCriteria::default()).unwrap();
/// assert_eq!((verdict.from, verdict.to, verdict.records), (75.0, 100.0, 26));
/// assert!(verdict.is_alpha_flocking() && verdict.is_strict());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlockingVerdict {
    /// The time of the first record of the window, t₀.
    pub from: f64,
    /// The time of its last record, t_f.
    pub to: f64,
    /// The number of records in the window.
    pub records: usize,
    /// min C* over the window.
    pub min_giant_share: f64,
    /// The largest number of components.
    pub max_components: usize,
    /// R(t₀).
    pub initial_cohesion_radius: f64,
    /// max R.
    pub max_cohesion_radius: f64,
    /// max Ẽ.
    pub max_deviation_energy: f64,
    /// max K̃.
    pub max_velocity_mismatch: f64,
    /// The group's speed ‖p_c‖ at the end of the window.
    pub group_speed: f64,
    /// v̂(t_f): the largest root-mean-square speed of the agents at any record up to the end of
    /// the window, √(‖p_c‖² + 2 K̃), the scale of a group at rest.
    pub approach_speed: f64,
    /// max over the window of K̃(t) / s(t)², the velocity mismatch relative to the group's speed
    /// (or, at rest, to v̂), judged against ε₂.
    pub max_relative_mismatch: f64,
    /// The most pairs closer than the collision distance at a record of the window.
    pub max_collisions: usize,
    /// Condition 1: C* ≥ the criteria's giant share at every record.
    pub quasi_flock: bool,
    /// Condition 2: the cohesion test at every record.
    pub cohesive: bool,
    /// Conditions 3 and b: Ẽ ≤ ε₁ at every record.
    pub small_deviation: bool,
    /// Conditions 4 and c: K̃ ≤ ε₂ s² at every record.
    pub small_mismatch: bool,
    /// Condition a: one component at every record.
    pub connected: bool,
    /// No pair closer than the collision distance at any record (asked of a strict α-flock).
    pub collision_free: bool,
    /// Whether some record of the window is of a flock without agents (every agent removed by
    /// faults): its metrics are undefined, and so is the verdict (neither condition holds).
    pub empty: bool,
    /// Whether some record of the window is of a single agent (its least distance to another
    /// agent is +∞): a group of one is no flock, and the verdict is undefined.
    pub lone: bool,
}

impl FlockingVerdict {
    /// Judges the records `(t, metrics)` (in time order) of the criteria's window; `None` when the
    /// window holds no record. A NaN metric fails its condition. The records before the window
    /// count only in the approach speed v̂.
    #[must_use]
    pub fn judge(records: &[(f64, FlockMetrics)], criteria: &FlockingCriteria) -> Option<Self> {
        let (from, to) = criteria.bounds(records.first()?.0, records.last()?.0);
        // v̂ at each record: the running maximum of the root-mean-square speed (NaN winning)
        let mut peak = 0.0;
        let scaled: Vec<(f64, &FlockMetrics, f64)> = records
            .iter()
            .take_while(|(t, _)| *t <= to)
            .map(|(t, m)| {
                peak = worst(peak, m.rms_speed());
                (*t, m, peak)
            })
            .filter(|(t, _, _)| *t >= from)
            .collect();
        let (start, end) = (scaled.first()?.0, scaled.last()?.0);
        let window: Vec<&FlockMetrics> = scaled.iter().map(|&(_, m, _)| m).collect();
        let initial_cohesion_radius = window[0].cohesion_radius;
        let max_of = |f: fn(&FlockMetrics) -> f64| window.iter().map(|&m| f(m)).fold(0.0, worst);
        let max_cohesion_radius = max_of(|m| m.cohesion_radius);
        let max_deviation_energy = max_of(|m| m.deviation_energy);
        let max_velocity_mismatch = max_of(|m| m.velocity_mismatch);
        let max_relative_mismatch = scaled
            .iter()
            .map(|&(_, m, v)| relative(m, v, criteria.epsilon2))
            .fold(0.0, worst);
        let min_giant_share =
            window
                .iter()
                .map(|m| m.giant_component)
                .fold(
                    f64::INFINITY,
                    |acc, x| if x.is_nan() || x < acc { x } else { acc },
                );
        let radius_bound = match criteria.cohesion {
            Cohesion::NonGrowing { growth } => (1.0 + growth) * initial_cohesion_radius,
            Cohesion::Radius(radius) => radius,
        };
        let max_collisions = window.iter().map(|m| m.collisions).max().unwrap_or(0);
        Some(Self {
            from: start,
            to: end,
            records: window.len(),
            min_giant_share,
            max_components: window.iter().map(|m| m.components).max().unwrap_or(0),
            initial_cohesion_radius,
            max_cohesion_radius,
            max_deviation_energy,
            max_velocity_mismatch,
            group_speed: window[window.len() - 1].group_speed,
            approach_speed: scaled[scaled.len() - 1].2,
            max_relative_mismatch,
            max_collisions,
            quasi_flock: min_giant_share >= criteria.giant_share,
            cohesive: max_cohesion_radius <= radius_bound,
            small_deviation: max_deviation_energy <= criteria.epsilon1,
            small_mismatch: max_relative_mismatch <= criteria.epsilon2,
            connected: window.iter().all(|m| m.components == 1),
            collision_free: max_collisions == 0,
            empty: window.iter().any(|m| m.is_empty_flock()),
            lone: window.iter().any(|m| m.is_lone_agent()),
        })
    }

    /// Whether the window's records are of a group the conditions apply to: some agent, and two
    /// at least, at every record.
    #[must_use]
    pub const fn is_defined(&self) -> bool {
        !self.empty && !self.lone
    }

    /// α-flocking: quasi-flock, cohesive, Ẽ ≤ ε₁ and K̃ ≤ ε₂ s² over the window (conditions 1–4).
    #[must_use]
    pub const fn is_alpha_flocking(&self) -> bool {
        self.is_defined()
            && self.quasi_flock
            && self.cohesive
            && self.small_deviation
            && self.small_mismatch
    }

    /// Strict α-flocking: an α-flock that is also connected (conditions a–c) and collision-free
    /// over the window.
    #[must_use]
    pub const fn is_strict(&self) -> bool {
        self.is_alpha_flocking() && self.connected && self.collision_free
    }

    /// The velocities agree and the group stays together, the flocking of Cucker & Smale (IEEE
    /// TAC 52(5), 2007: the velocities converge to a common one and the diameter stays bounded):
    /// cohesive and K̃ ≤ ε₂ s² over the window (conditions 2 and 4).
    #[must_use]
    pub const fn is_velocity_flocking(&self) -> bool {
        self.is_defined() && self.cohesive && self.small_mismatch
    }

    /// Why the verdict is undefined, if it is.
    #[must_use]
    pub const fn undefined_reason(&self) -> Option<&'static str> {
        if self.empty {
            Some(
                "no agent is left at some record (every agent removed by faults): its metrics are undefined",
            )
        } else if self.lone {
            Some("a single agent at some record: flocking is a property of a group of two or more")
        } else {
            None
        }
    }

    /// `K̃ ≤ 6.4e-3 (≤ 0.30 s²; ‖p_c‖ = 5.5e-2, v̂ = 1.9e-1)`: the largest velocity mismatch,
    /// the largest relative to the speed scale s, and the group's and the approach's speeds at the
    /// end of the window.
    #[must_use]
    pub fn mismatch_text(&self) -> String {
        format!(
            "K̃ ≤ {:.1e} (≤ {:.2} s²; ‖p_c‖ = {:.1e}, v̂ = {:.1e})",
            self.max_velocity_mismatch,
            self.max_relative_mismatch,
            self.group_speed,
            self.approach_speed
        )
    }
}

/// K̃ / s² of a record: s = ‖p_c‖ while the group moves (‖p_c‖ ≥ √(2ε₂) v̂), s = `approach` (v̂)
/// once it has come to rest; 0 when K̃ vanishes.
fn relative(m: &FlockMetrics, approach: f64, epsilon2: f64) -> f64 {
    let (mismatch, speed) = (m.velocity_mismatch, m.group_speed);
    let scale = if speed >= (2.0 * epsilon2).sqrt() * approach {
        speed
    } else {
        approach
    };
    if mismatch == 0.0 {
        0.0
    } else {
        mismatch / (scale * scale)
    }
}

/// The larger of two values, NaN winning (a NaN metric then fails its test).
fn worst(acc: f64, x: f64) -> f64 {
    if x.is_nan() || x > acc { x } else { acc }
}

impl fmt::Display for FlockingVerdict {
    /// One line: `α-flocking over [75.00, 100.00] s (26 records): yes, strict: yes — min C* = 1.000,
    /// R ≤ 20.00 (from 20.00), Ẽ ≤ 1.0e-4, K̃ ≤ 1.0e-6 (≤ 0.00 s²; ‖p_c‖ = 1.0e0, v̂ = 1.0e0),
    /// colliding pairs ≤ 0`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let yes = |b: bool| if b { "yes" } else { "no" };
        if let Some(reason) = self.undefined_reason() {
            return write!(
                f,
                "α-flocking over [{:.2}, {:.2}] s ({} records): undefined, strict: undefined — {reason}",
                self.from, self.to, self.records
            );
        }
        write!(
            f,
            "α-flocking over [{:.2}, {:.2}] s ({} records): {}, strict: {} — min C* = {:.3}, \
             R ≤ {:.2} (from {:.2}), Ẽ ≤ {:.1e}, {}, colliding pairs ≤ {}",
            self.from,
            self.to,
            self.records,
            yes(self.is_alpha_flocking()),
            yes(self.is_strict()),
            self.min_giant_share,
            self.max_cohesion_radius,
            self.initial_cohesion_radius,
            self.max_deviation_energy,
            self.mismatch_text(),
            self.max_collisions
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flock() -> FlockMetrics {
        FlockMetrics {
            connectivity: 1.0,
            giant_component: 1.0,
            components: 1,
            cohesion_radius: 30.0,
            deviation_energy: 1e-3,
            velocity_mismatch: 1e-4,
            min_distance: 6.0,
            collisions: 0,
            polarisation: 1.0,
            milling: 0.0,
            nearest_neighbour_mean: 7.0,
            nearest_neighbour_min: 6.0,
            group_speed: 1.0,
        }
    }

    /// Records at t = 0, 1, …, 100 from `metric(t)`.
    fn run(metric: impl Fn(f64) -> FlockMetrics) -> Vec<(f64, FlockMetrics)> {
        (0..=100)
            .map(|k| {
                let t = f64::from(k);
                (t, metric(t))
            })
            .collect()
    }

    fn judge(records: &[(f64, FlockMetrics)]) -> FlockingVerdict {
        FlockingVerdict::judge(records, &FlockingCriteria::default()).expect("records")
    }

    /// Issue 27: a record of a flock without agents makes the verdict undefined, never strict.
    #[test]
    fn issue_27_an_empty_flock_is_not_judged_a_flock() {
        let records = run(|t| {
            if t < 90.0 {
                flock()
            } else {
                FlockMetrics::EMPTY
            }
        });
        let verdict = judge(&records);
        assert!(verdict.empty);
        assert!(!verdict.is_alpha_flocking() && !verdict.is_strict());
        assert!(verdict.to_string().contains("undefined"), "{verdict}");
    }

    /// Issue 49: one agent was judged "α-flocking … no, strict: yes" (its cohesion radius about a
    /// circular mean beside it grew by round-off); a group of one has no verdict, and a verdict
    /// never calls strict what it does not call an α-flock.
    #[test]
    fn issue_49_one_agent_has_no_verdict() {
        let lone = FlockMetrics {
            min_distance: f64::INFINITY,
            nearest_neighbour_mean: f64::INFINITY,
            nearest_neighbour_min: f64::INFINITY,
            deviation_energy: 0.0,
            velocity_mismatch: 0.0,
            cohesion_radius: 0.0,
            ..flock()
        };
        let verdict = judge(&run(|_| lone));
        assert!(verdict.lone && !verdict.is_defined());
        assert!(!verdict.is_alpha_flocking() && !verdict.is_strict());
        assert!(
            verdict.to_string().contains("undefined, strict: undefined"),
            "{verdict}"
        );
        // strict implies α-flocking whatever the records: a group spreading out while connected
        let spreading = judge(&run(|t| FlockMetrics {
            cohesion_radius: t,
            ..flock()
        }));
        assert!(spreading.connected && !spreading.cohesive);
        assert!(!spreading.is_alpha_flocking() && !spreading.is_strict());
    }

    #[test]
    fn only_the_window_is_judged() {
        // disordered for t < 75, a strict α-flock from t = 75 (the last quarter)
        let records = run(|t| {
            if t < 75.0 {
                FlockMetrics {
                    components: 3,
                    giant_component: 0.5,
                    velocity_mismatch: 2.0,
                    collisions: 4,
                    ..flock()
                }
            } else {
                flock()
            }
        });
        let verdict = judge(&records);
        assert_eq!(
            (verdict.from, verdict.to, verdict.records),
            (75.0, 100.0, 26)
        );
        assert!(
            verdict.is_strict() && verdict.is_alpha_flocking(),
            "{verdict}"
        );
        let earlier = FlockingCriteria {
            window: Window::Between {
                from: 70.0,
                to: 80.0,
            },
            ..FlockingCriteria::default()
        };
        let verdict = FlockingVerdict::judge(&records, &earlier).expect("records");
        assert_eq!(
            (verdict.from, verdict.to, verdict.records),
            (70.0, 80.0, 11)
        );
        assert_eq!((verdict.max_components, verdict.max_collisions), (3, 4));
        assert!(!verdict.quasi_flock && !verdict.connected && !verdict.small_mismatch);
    }

    #[test]
    fn quasi_flock_is_alpha_flocking_but_not_strict() {
        // three stragglers out of 100 (C* = 0.97, seed 004's final density) that do not drift away
        let records = run(|_| FlockMetrics {
            components: 4,
            giant_component: 0.97,
            ..flock()
        });
        let verdict = judge(&records);
        assert!(verdict.quasi_flock && verdict.cohesive && !verdict.connected);
        assert!(verdict.is_alpha_flocking() && !verdict.is_strict());
    }

    #[test]
    fn a_group_that_spreads_out_is_not_cohesive() {
        // fragments moving apart: R grows linearly, 30 → 45 m over the last quarter
        let records = run(|t| FlockMetrics {
            components: 2,
            giant_component: 0.95,
            cohesion_radius: 0.6 * t - 15.0,
            ..flock()
        });
        let verdict = judge(&records);
        assert_eq!(verdict.initial_cohesion_radius, 30.0);
        assert_eq!(verdict.max_cohesion_radius, 45.0);
        assert!(verdict.quasi_flock && !verdict.cohesive && !verdict.is_alpha_flocking());
        let bounded = FlockingCriteria {
            cohesion: Cohesion::Radius(50.0),
            ..FlockingCriteria::default()
        };
        let verdict = FlockingVerdict::judge(&records, &bounded).expect("records");
        assert!(verdict.cohesive && verdict.is_alpha_flocking());
    }

    #[test]
    fn each_threshold_is_a_condition() {
        // at a group speed of 1 the mismatch K̃ is at ε₂ ‖p_c‖² = ε₂: bracketed at 0.999 and 1.001
        let at_limit = 0.01;
        let at = |deviation_energy, velocity_mismatch| {
            judge(&run(|_| FlockMetrics {
                deviation_energy,
                velocity_mismatch,
                ..flock()
            }))
        };
        let verdict = at(0.01, 0.999 * at_limit);
        assert!(
            verdict.is_alpha_flocking() && verdict.is_strict(),
            "{verdict}"
        );
        let verdict = at(0.0101, 0.0);
        assert!(!verdict.small_deviation && !verdict.is_alpha_flocking() && !verdict.is_strict());
        let verdict = at(0.01, 1.001 * at_limit);
        assert!(!verdict.small_mismatch && !verdict.is_alpha_flocking() && !verdict.is_strict());
        let verdict = at(f64::NAN, 0.0);
        assert!(verdict.max_deviation_energy.is_nan() && !verdict.small_deviation);
    }

    /// Issue 50: 200 unicycles at 0.11 m/s with K̃ = 6.4·10⁻³ m²/s² — a velocity spread as
    /// large as the speed — passed the absolute ε₂ = 0.01 m²/s². Judged relative to the agents'
    /// speed they fail, and the verdict does not depend on the unit of speed.
    #[test]
    fn the_velocity_mismatch_is_judged_relative_to_the_group_s_speed() {
        let at = |speed: f64, mismatch: f64| {
            judge(&run(|_| FlockMetrics {
                group_speed: speed,
                velocity_mismatch: mismatch,
                ..flock()
            }))
        };
        let slow = at(0.11, 6.4e-3);
        assert!(!slow.small_mismatch && !slow.is_alpha_flocking(), "{slow}");
        assert!(slow.max_relative_mismatch > 0.2, "{slow}");
        // the same K̃ in a flock at 25 m/s is a spread of 0.5 % of its speed
        assert!(at(25.0, 6.4e-3).is_strict());
        // the same flock in other units (km/h: speeds × 3.6, K̃ × 3.6²): the same verdict
        for (speed, mismatch) in [(0.11, 6.4e-3), (0.11, 1e-5), (3.0, 0.05), (3.0, 0.2)] {
            let (a, b) = (at(speed, mismatch), at(3.6 * speed, 12.96 * mismatch));
            assert_eq!(a.small_mismatch, b.small_mismatch, "{a} / {b}");
            approx::assert_relative_eq!(
                a.max_relative_mismatch,
                b.max_relative_mismatch,
                max_relative = 1e-12
            );
        }
        assert!(at(3.0, 0.05).small_mismatch && !at(3.0, 0.2).small_mismatch);
    }

    /// A rendezvous ends at rest (‖p_c‖ → 0, below √(2ε₂) v̂): its mismatch is judged against the
    /// speed of its approach v̂, the largest root-mean-square speed before and in the window, and
    /// not against its vanishing group speed (the sinks of ACC 2004 Fig. 4 and CDS 03-006 Fig. 9
    /// decay with ‖p_c‖² and K̃ alike).
    #[test]
    fn a_rendezvous_is_judged_against_the_speed_of_its_approach() {
        let rendezvous = |mismatch: f64| {
            judge(&run(|t| {
                if t < 50.0 {
                    // approaching at 2 m/s
                    FlockMetrics {
                        group_speed: 2.0,
                        velocity_mismatch: 0.5,
                        ..flock()
                    }
                } else {
                    FlockMetrics {
                        group_speed: 0.0,
                        velocity_mismatch: mismatch,
                        ..flock()
                    }
                }
            }))
        };
        // v̂² = 4 + 1 = 5: K̃ ≤ 0.05
        let settled = rendezvous(1e-3);
        assert!(settled.is_strict(), "{settled}");
        approx::assert_relative_eq!(settled.approach_speed, 5f64.sqrt());
        assert!(rendezvous(0.049).small_mismatch && !rendezvous(0.051).small_mismatch);
        // at rest without spread: no mismatch at all
        assert!(rendezvous(0.0).small_mismatch);
        // decaying to rest with K̃ ≈ ‖p_c‖²/2: judged against v̂, not against ‖p_c‖
        let decaying = judge(&run(|t| FlockMetrics {
            group_speed: 2.0 * (-t / 10.0).exp(),
            velocity_mismatch: 2.0 * (-t / 5.0).exp(),
            ..flock()
        }));
        assert!(decaying.small_mismatch, "{decaying}");
    }

    /// Issue 50: merged agents (two pairs 0.1 mm apart after settling) were called a strict
    /// α-flock. A pair closer than the collision distance at any record of the window fails
    /// "strict"; one before the window (a random start) does not.
    #[test]
    fn colliding_agents_are_not_a_strict_flock() {
        let colliding = |from: f64| {
            judge(&run(|t| FlockMetrics {
                collisions: usize::from(t >= from) * 2,
                min_distance: if t >= from { 1e-4 } else { 6.0 },
                ..flock()
            }))
        };
        let merged = colliding(60.0);
        assert!(merged.is_alpha_flocking() && !merged.collision_free && !merged.is_strict());
        assert_eq!(merged.max_collisions, 2);
        assert!(
            merged.to_string().contains("colliding pairs ≤ 2"),
            "{merged}"
        );
        let late = colliding(99.0);
        assert!(!late.is_strict());
        let before = run(|t| FlockMetrics {
            collisions: usize::from(t < 70.0) * 5,
            ..flock()
        });
        assert!(judge(&before).is_strict());
    }

    #[test]
    fn a_single_bad_record_fails_the_window() {
        let verdict = judge(&run(|t| {
            if t == 90.0 {
                FlockMetrics {
                    components: 2,
                    giant_component: 0.5,
                    ..flock()
                }
            } else {
                flock()
            }
        }));
        assert_eq!(verdict.min_giant_share, 0.5);
        assert!(!verdict.quasi_flock && !verdict.connected && !verdict.is_alpha_flocking());
    }

    #[test]
    fn empty_window_gives_no_verdict() {
        let criteria = FlockingCriteria {
            window: Window::Between {
                from: 200.0,
                to: 300.0,
            },
            ..FlockingCriteria::default()
        };
        assert_eq!(FlockingVerdict::judge(&run(|_| flock()), &criteria), None);
        assert_eq!(
            FlockingVerdict::judge(&[], &FlockingCriteria::default()),
            None
        );
    }

    #[test]
    fn display_is_one_line() {
        let verdict = judge(&run(|_| flock()));
        assert_eq!(
            verdict.to_string(),
            "α-flocking over [75.00, 100.00] s (26 records): yes, strict: yes — min C* = 1.000, \
             R ≤ 30.00 (from 30.00), Ẽ ≤ 1.0e-3, K̃ ≤ 1.0e-4 (≤ 0.00 s²; ‖p_c‖ = 1.0e0, \
             v̂ = 1.0e0), colliding pairs ≤ 0"
        );
    }
}
