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
//! three things to the reader, fixed here and settable:
//!
//! - **ε₁, ε₂** ("relatively small numbers"): 0.01 each by default. Ẽ ≤ 0.01 means a root mean
//!   square edge-length error of at most 0.1 d (the quasi α-lattice of uncertainty δ = 0.1 d of
//!   [`LatticeSummary`](crate::LatticeSummary)); K̃ = ½ mean ‖p_i − p_c‖² ≤ 0.01 means a root mean
//!   square velocity mismatch of at most 0.14 m/s, against group speeds of 1–10 m/s in the papers'
//!   simulations.
//! - **"giant component"**: C* ≥ 0.9 by default — seed 004 (eq. 7) calls a net of density δ₀ = C*
//!   with 0 < 1 − δ₀ ≪ 1 a quasi-flock, and its six-obstacle run ends at δ₀ = 0.97.
//! - **"cohesive"** (all agents within a ball of radius R around q_c): over a finite window every
//!   trajectory is bounded, so cohesion needs a number. By default the cohesion radius R(t) may
//!   not grow by more than 10 % above its value at the start of the window (agents leaving the
//!   group make it grow without bound); [`Cohesion::Radius`] bounds R(t) by a given radius instead.

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
    /// ε₂: K̃ = K / n ≤ ε₂.
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
    /// Condition 1: C* ≥ the criteria's giant share at every record.
    pub quasi_flock: bool,
    /// Condition 2: the cohesion test at every record.
    pub cohesive: bool,
    /// Conditions 3 and b: Ẽ ≤ ε₁ at every record.
    pub small_deviation: bool,
    /// Conditions 4 and c: K̃ ≤ ε₂ at every record.
    pub small_mismatch: bool,
    /// Condition a: one component at every record.
    pub connected: bool,
    /// Whether some record of the window is of a flock without agents (every agent removed by
    /// faults): its metrics are undefined, and so is the verdict (neither condition holds).
    pub empty: bool,
}

impl FlockingVerdict {
    /// Judges the records `(t, metrics)` (in time order) of the criteria's window; `None` when the
    /// window holds no record. A NaN metric fails its condition.
    #[must_use]
    pub fn judge(records: &[(f64, FlockMetrics)], criteria: &FlockingCriteria) -> Option<Self> {
        let (first, last) = (records.first()?.0, records.last()?.0);
        let (from, to) = match criteria.window {
            Window::LastFraction(f) => (last - f * (last - first), last),
            Window::Between { from, to } => (from, to),
        };
        let in_window: Vec<&(f64, FlockMetrics)> = records
            .iter()
            .filter(|(t, _)| (from..=to).contains(t))
            .collect();
        let (start, end) = (in_window.first()?.0, in_window.last()?.0);
        let window: Vec<&FlockMetrics> = in_window.iter().map(|(_, m)| m).collect();
        let initial_cohesion_radius = window[0].cohesion_radius;
        let max_of = |f: fn(&FlockMetrics) -> f64| window.iter().map(|&m| f(m)).fold(0.0, worst);
        let max_cohesion_radius = max_of(|m| m.cohesion_radius);
        let max_deviation_energy = max_of(|m| m.deviation_energy);
        let max_velocity_mismatch = max_of(|m| m.velocity_mismatch);
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
            quasi_flock: min_giant_share >= criteria.giant_share,
            cohesive: max_cohesion_radius <= radius_bound,
            small_deviation: max_deviation_energy <= criteria.epsilon1,
            small_mismatch: max_velocity_mismatch <= criteria.epsilon2,
            connected: window.iter().all(|m| m.components == 1),
            empty: window.iter().any(|m| m.is_empty_flock()),
        })
    }

    /// α-flocking: quasi-flock, cohesive, Ẽ ≤ ε₁ and K̃ ≤ ε₂ over the window (conditions 1–4).
    #[must_use]
    pub const fn is_alpha_flocking(&self) -> bool {
        !self.empty
            && self.quasi_flock
            && self.cohesive
            && self.small_deviation
            && self.small_mismatch
    }

    /// Strict α-flocking: connected, Ẽ ≤ ε₁ and K̃ ≤ ε₂ over the window (conditions a–c).
    #[must_use]
    pub const fn is_strict(&self) -> bool {
        !self.empty && self.connected && self.small_deviation && self.small_mismatch
    }
}

/// The larger of two values, NaN winning (a NaN metric then fails its test).
fn worst(acc: f64, x: f64) -> f64 {
    if x.is_nan() || x > acc { x } else { acc }
}

impl fmt::Display for FlockingVerdict {
    /// One line: `α-flocking over [75.00, 100.00] s (26 records): yes, strict: yes — min C* = 1.000,
    /// R ≤ 20.00 (from 20.00), Ẽ ≤ 1.0e-4, K̃ ≤ 1.0e-6`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let yes = |b: bool| if b { "yes" } else { "no" };
        if self.empty {
            return write!(
                f,
                "α-flocking over [{:.2}, {:.2}] s ({} records): undefined, strict: undefined — no agent is left at some record (every agent removed by faults): its metrics are undefined",
                self.from, self.to, self.records
            );
        }
        write!(
            f,
            "α-flocking over [{:.2}, {:.2}] s ({} records): {}, strict: {} — min C* = {:.3}, \
             R ≤ {:.2} (from {:.2}), Ẽ ≤ {:.1e}, K̃ ≤ {:.1e}",
            self.from,
            self.to,
            self.records,
            yes(self.is_alpha_flocking()),
            yes(self.is_strict()),
            self.min_giant_share,
            self.max_cohesion_radius,
            self.initial_cohesion_radius,
            self.max_deviation_energy,
            self.max_velocity_mismatch
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

    #[test]
    fn only_the_window_is_judged() {
        // disordered for t < 75, a strict α-flock from t = 75 (the last quarter)
        let records = run(|t| {
            if t < 75.0 {
                FlockMetrics {
                    components: 3,
                    giant_component: 0.5,
                    velocity_mismatch: 2.0,
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
        assert_eq!(verdict.max_components, 3);
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
        let at = |deviation_energy, velocity_mismatch| {
            judge(&run(|_| FlockMetrics {
                deviation_energy,
                velocity_mismatch,
                ..flock()
            }))
        };
        let verdict = at(0.01, 0.01);
        assert!(verdict.is_alpha_flocking() && verdict.is_strict());
        let verdict = at(0.0101, 0.01);
        assert!(!verdict.small_deviation && !verdict.is_alpha_flocking() && !verdict.is_strict());
        let verdict = at(0.01, 0.0101);
        assert!(!verdict.small_mismatch && !verdict.is_alpha_flocking() && !verdict.is_strict());
        let verdict = at(f64::NAN, 0.0);
        assert!(verdict.max_deviation_energy.is_nan() && !verdict.small_deviation);
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
             R ≤ 30.00 (from 30.00), Ẽ ≤ 1.0e-3, K̃ ≤ 1.0e-4"
        );
    }
}
