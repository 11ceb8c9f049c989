//! The order of a group as the collective-motion literature judges it: the polarisation and the
//! milling averaged over a window of records ([`OrderVerdict`]), and the collective state they
//! name ([`OrderState`], the thresholds of Tunstrøm et al. 2013).
//!
//! The models that set their agents' velocities (Vicsek et al. 1995, Reynolds's boids, Couzin et
//! al. 2002) have no lattice and no energy to decrease; their papers measure the order of the
//! headings — Vicsek's v_a, Couzin's p_group and m_group — averaged over time once the run has
//! settled. TAC 2006 Definition 5 means nothing for them (its Ẽ compares edges with a distance d
//! they do not keep, its collisions a distance d/4 they do not have).

use core::fmt;

use crate::{FlockMetrics, FlockingCriteria};

/// A collective state named from the polarisation O_p and the milling (rotation) O_r by the
/// thresholds of Tunstrøm, Katz, Ioannou, Huepe, Lutz & Couzin, "Collective states,
/// multistability and transitional behavior in schooling fish", PLoS Comput. Biol. 9(2),
/// e1002915 (2013): polarised when O_p > 0.65 and O_r < 0.35, milling when O_r > 0.65 and
/// O_p < 0.35, a swarm when both are below 0.35, transitional otherwise.
///
/// # Example
/// ```
/// use flock_metrics::OrderState;
///
/// assert_eq!(OrderState::of(0.98, 0.02), OrderState::Polarised);
/// assert_eq!(OrderState::of(0.10, 0.90), OrderState::Milling);
/// assert_eq!(OrderState::of(0.10, 0.05), OrderState::Swarm);
/// assert_eq!(OrderState::of(0.50, 0.10), OrderState::Transitional);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrderState {
    /// Aligned: O_p > [`OrderState::HIGH`], O_r < [`OrderState::LOW`] (Vicsek's ordered phase).
    Polarised,
    /// Circling the centre: O_r > [`OrderState::HIGH`], O_p < [`OrderState::LOW`].
    Milling,
    /// Disordered: O_p and O_r below [`OrderState::LOW`].
    Swarm,
    /// Neither (between the states, or switching between them within the window).
    Transitional,
}

impl OrderState {
    /// The least O_p of a polarised group and the least O_r of a milling one (Tunstrøm et al.).
    pub const HIGH: f64 = 0.65;
    /// The largest O_p and O_r of a swarm, and the largest other parameter of a polarised or
    /// milling group (Tunstrøm et al.).
    pub const LOW: f64 = 0.35;

    /// The state of a group of polarisation `p` and milling `m`; NaN falls in no state but
    /// [`OrderState::Transitional`].
    #[must_use]
    pub fn of(p: f64, m: f64) -> Self {
        if p > Self::HIGH && m < Self::LOW {
            Self::Polarised
        } else if m > Self::HIGH && p < Self::LOW {
            Self::Milling
        } else if p < Self::LOW && m < Self::LOW {
            Self::Swarm
        } else {
            Self::Transitional
        }
    }

    /// The state's name: `polarised (ordered)`, `milling`, `swarm (disordered)`, `transitional`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Polarised => "polarised (ordered)",
            Self::Milling => "milling",
            Self::Swarm => "swarm (disordered)",
            Self::Transitional => "transitional",
        }
    }
}

/// The thresholds of [`OrderState`], as a verdict's text states them.
pub const ORDER_THRESHOLDS: &str = "polarised O_p > 0.65 and O_r < 0.35, milling O_r > 0.65 and O_p < 0.35, swarm both < 0.35, transitional otherwise (Tunstrøm et al. 2013)";

/// The order parameters of a window of records: their means, the least share of the largest
/// group and the most colliding pairs.
///
/// # Example
/// ```
/// use flock_metrics::{FlockMetrics, FlockingCriteria, OrderState, OrderVerdict};
///
/// let mill = FlockMetrics {
///     connectivity: 1.0,
///     giant_component: 1.0,
///     components: 1,
///     cohesion_radius: 8.0,
///     deviation_energy: 0.4,
///     velocity_mismatch: 4.5,
///     min_distance: 0.9,
///     collisions: 3,
///     polarisation: 0.1,
///     milling: 0.9,
///     nearest_neighbour_mean: 1.1,
///     nearest_neighbour_min: 0.9,
///     group_speed: 0.3,
/// };
/// let records: Vec<(f64, FlockMetrics)> = (0..=300).map(|k| (f64::from(k), mill)).collect();
/// let order = OrderVerdict::judge(&records, &FlockingCriteria::default()).unwrap();
/// assert_eq!((order.from, order.records), (225.0, 76));
/// assert_eq!(order.state(), Some(OrderState::Milling));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrderVerdict {
    /// The time of the first record of the window.
    pub from: f64,
    /// The time of its last record.
    pub to: f64,
    /// The number of records in the window.
    pub records: usize,
    /// The mean polarisation O_p over the window (Vicsek's v_a, Couzin's p_group).
    pub polarisation: f64,
    /// The mean milling O_r over the window (Couzin's m_group).
    pub milling: f64,
    /// The least share C* of the agents in the largest group of the proximity net.
    pub min_giant_share: f64,
    /// The most pairs closer than the collision distance at a record of the window.
    pub max_collisions: usize,
    /// Whether some record has no agent, or a single one: the order of a group of fewer than
    /// two agents is undefined.
    pub undefined: bool,
}

impl OrderVerdict {
    /// The order over the window of `criteria` (only its window is read) of the records
    /// `(t, metrics)` in time order; `None` when the window holds no record.
    #[must_use]
    pub fn judge(records: &[(f64, FlockMetrics)], criteria: &FlockingCriteria) -> Option<Self> {
        let (from, to) = criteria.bounds(records.first()?.0, records.last()?.0);
        let window: Vec<&(f64, FlockMetrics)> = records
            .iter()
            .filter(|(t, _)| (from..=to).contains(t))
            .collect();
        let (first, last) = (window.first()?.0, window.last()?.0);
        let count = window.len() as f64;
        let mean =
            |f: fn(&FlockMetrics) -> f64| window.iter().map(|(_, m)| f(m)).sum::<f64>() / count;
        Some(Self {
            from: first,
            to: last,
            records: window.len(),
            polarisation: mean(|m| m.polarisation),
            milling: mean(|m| m.milling),
            min_giant_share: window
                .iter()
                .map(|(_, m)| m.giant_component)
                .fold(f64::INFINITY, f64::min),
            max_collisions: window.iter().map(|(_, m)| m.collisions).max().unwrap_or(0),
            undefined: window
                .iter()
                .any(|(_, m)| m.is_empty_flock() || m.is_lone_agent()),
        })
    }

    /// The collective state of the mean polarisation and milling ([`OrderState::of`]); `None`
    /// when undefined.
    #[must_use]
    pub fn state(&self) -> Option<OrderState> {
        (!self.undefined).then(|| OrderState::of(self.polarisation, self.milling))
    }
}

impl fmt::Display for OrderVerdict {
    /// `over [225.00, 300.00] s (76 records): O_p = 0.102, O_r = 0.897 (means), largest group
    /// ≥ 1.000 of the agents`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "over [{:.2}, {:.2}] s ({} records): O_p = {:.3}, O_r = {:.3} (means), largest group ≥ {:.3} of the agents",
            self.from, self.to, self.records, self.polarisation, self.milling, self.min_giant_share
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(polarisation: f64, milling: f64) -> FlockMetrics {
        FlockMetrics {
            connectivity: 1.0,
            giant_component: 1.0,
            components: 1,
            cohesion_radius: 8.0,
            deviation_energy: 0.4,
            velocity_mismatch: 4.5,
            min_distance: 0.9,
            collisions: 0,
            polarisation,
            milling,
            nearest_neighbour_mean: 1.1,
            nearest_neighbour_min: 0.9,
            group_speed: 3.0 * polarisation,
        }
    }

    #[test]
    fn the_thresholds_bracket_each_state() {
        let (high, low) = (OrderState::HIGH, OrderState::LOW);
        let above = |x: f64| x + 1e-9;
        let below = |x: f64| x - 1e-9;
        assert_eq!(
            OrderState::of(above(high), below(low)),
            OrderState::Polarised
        );
        assert_eq!(OrderState::of(high, below(low)), OrderState::Transitional);
        assert_eq!(OrderState::of(above(high), low), OrderState::Transitional);
        assert_eq!(OrderState::of(below(low), above(high)), OrderState::Milling);
        assert_eq!(OrderState::of(below(low), high), OrderState::Transitional);
        assert_eq!(OrderState::of(below(low), below(low)), OrderState::Swarm);
        assert_eq!(OrderState::of(low, below(low)), OrderState::Transitional);
        assert_eq!(OrderState::of(f64::NAN, 0.0), OrderState::Transitional);
    }

    #[test]
    fn the_window_means_name_the_state() {
        // polarised for the first half, milling from t = 60 on: the last quarter mills
        let records: Vec<(f64, FlockMetrics)> = (0..=100)
            .map(|k| {
                let t = f64::from(k);
                (
                    t,
                    if t < 60.0 {
                        at(0.95, 0.05)
                    } else {
                        at(0.2, 0.8)
                    },
                )
            })
            .collect();
        let order = OrderVerdict::judge(&records, &FlockingCriteria::default()).expect("records");
        assert_eq!((order.from, order.to, order.records), (75.0, 100.0, 26));
        assert_eq!(order.state(), Some(OrderState::Milling));
        approx::assert_relative_eq!(order.polarisation, 0.2, max_relative = 1e-12);
        // a window that straddles the switch averages the two: transitional
        let straddle = FlockingCriteria {
            window: crate::Window::Between {
                from: 40.0,
                to: 80.0,
            },
            ..FlockingCriteria::default()
        };
        let order = OrderVerdict::judge(&records, &straddle).expect("records");
        assert_eq!(order.state(), Some(OrderState::Transitional));
    }

    /// Issue 49: one Vicsek particle on a torus showed a milling of 0.68. Whatever its
    /// parameters read, a group of one has no collective state.
    #[test]
    fn issue_49_one_agent_has_no_collective_state() {
        let lone = FlockMetrics {
            min_distance: f64::INFINITY,
            ..at(1.0, 0.68)
        };
        let records = [(0.0, lone), (1.0, lone)];
        let order = OrderVerdict::judge(&records, &FlockingCriteria::default()).expect("records");
        assert!(order.undefined && order.state().is_none());
        let none = [(0.0, FlockMetrics::EMPTY)];
        let order = OrderVerdict::judge(&none, &FlockingCriteria::default()).expect("records");
        assert!(order.state().is_none());
    }
}
