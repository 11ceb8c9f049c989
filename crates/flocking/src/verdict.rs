//! The verdict a run gets: success as its model's papers measure it, judged on the records of a
//! window (by default the last quarter of the run), in `flocking.txt`, the summary and `runs.csv`.
//!
//! | model | verdict | [`VerdictKind`] |
//! | --- | --- | --- |
//! | Olfati-Saber's algorithms, the 2003 protocols, Tanner et al., consensus | TAC 2006 Definition 5: α-flock, strict α-flock ([`FlockingVerdict`]) | `Definition5` |
//! | Cucker & Smale 2007 | flocking: the velocities agree (K̃ ≤ ε₂ s², relative to the group's speed) and the group stays together (R does not grow) | `CuckerSmale` |
//! | Vicsek et al. 1995, boids | the collective state of the mean polarisation and milling: polarised (ordered), milling, swarm (disordered), transitional ([`OrderState`], Tunstrøm et al. 2013) | `Order` |
//! | Couzin et al. 2002 | the paper's four states: swarm, torus, dynamic parallel, highly parallel ([`CollectiveState`]) | `Couzin` |
//! | Vásárhelyi et al. 2018 | flocking as its order parameters score it: polarised, one group, no pair within r^coll | `Vasarhelyi` |
//!
//! Definition 5 compares edges with the lattice distance d and counts collisions at d/4: for
//! models without an α-lattice these mean nothing, and their papers judge them by other measures
//! (Vicsek's v_a, Couzin's p_group and m_group, Cucker & Smale's convergence of velocities,
//! Vásárhelyi's φ^corr, φ^coll and the flock's cohesion).

use core::fmt;

use flock_metrics::{
    Cohesion, FlockMetrics, FlockingCriteria, FlockingVerdict, ORDER_THRESHOLDS, OrderState,
    OrderVerdict, Window,
};
use flock_protocols::CollectiveState;

use crate::scenario::Algorithm;

/// Which verdict a model gets (see the [module](self)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VerdictKind {
    /// TAC 2006 Definition 5.
    Definition5,
    /// Cucker & Smale's flocking.
    CuckerSmale,
    /// The order state of the headings, for the model named.
    Order(&'static str),
    /// Couzin et al.'s four states.
    Couzin,
    /// Vásárhelyi et al.'s flocking.
    Vasarhelyi,
}

impl VerdictKind {
    /// The verdict of the model of `algorithm`.
    #[must_use]
    pub const fn of(algorithm: &Algorithm) -> Self {
        match algorithm {
            Algorithm::CuckerSmale(_) => Self::CuckerSmale,
            Algorithm::Vicsek(_) => Self::Order("Vicsek et al. 1995"),
            Algorithm::Boids(_) => Self::Order("boids (Reynolds 1987)"),
            Algorithm::Couzin(_) => Self::Couzin,
            Algorithm::Vasarhelyi(_) => Self::Vasarhelyi,
            _ => Self::Definition5,
        }
    }

    /// Whether the model keeps an α-lattice at a distance d with an energy that its theorem
    /// makes non-increasing, so that the deviation energy Ẽ, the lattice, the topology and H
    /// mean something (Definition 5's models); the classic models have none.
    #[must_use]
    pub const fn has_lattice(self) -> bool {
        matches!(self, Self::Definition5)
    }

    /// Whether pairs closer than the collision distance are collisions for the model: d/4 of the
    /// α-lattice (Definition 5's models), r^coll (Vásárhelyi et al.); the point particles of
    /// Vicsek, boids, Couzin and Cucker–Smale may come arbitrarily close.
    #[must_use]
    pub const fn counts_collisions(self) -> bool {
        matches!(self, Self::Definition5 | Self::Vasarhelyi)
    }
}

/// A run's verdict (see the [module](self)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Verdict {
    /// TAC 2006 Definition 5.
    Definition5(FlockingVerdict),
    /// Cucker & Smale's flocking: conditions 2 and 4 of Definition 5
    /// ([`FlockingVerdict::is_velocity_flocking`]).
    CuckerSmale(FlockingVerdict),
    /// The order state of the headings of the model named.
    Order(&'static str, OrderVerdict),
    /// Couzin et al.'s state of the mean p_group and m_group.
    Couzin(OrderVerdict),
    /// Vásárhelyi et al.'s flocking.
    Vasarhelyi(OrderVerdict),
}

impl Verdict {
    /// The verdict of kind `kind` on the records `(t, metrics)` (in time order) of the criteria's
    /// window; `None` when the window holds no record.
    #[must_use]
    pub fn judge(
        kind: VerdictKind,
        records: &[(f64, FlockMetrics)],
        criteria: &FlockingCriteria,
    ) -> Option<Self> {
        Some(match kind {
            VerdictKind::Definition5 => {
                Self::Definition5(FlockingVerdict::judge(records, criteria)?)
            }
            VerdictKind::CuckerSmale => {
                Self::CuckerSmale(FlockingVerdict::judge(records, criteria)?)
            }
            VerdictKind::Order(model) => {
                Self::Order(model, OrderVerdict::judge(records, criteria)?)
            }
            VerdictKind::Couzin => Self::Couzin(OrderVerdict::judge(records, criteria)?),
            VerdictKind::Vasarhelyi => Self::Vasarhelyi(OrderVerdict::judge(records, criteria)?),
        })
    }

    /// Definition 5's two answers, α-flock and strict α-flock; `None` for the other verdicts.
    #[must_use]
    pub const fn alpha_flock(&self) -> Option<(bool, bool)> {
        match self {
            Self::Definition5(v) => Some((v.is_alpha_flocking(), v.is_strict())),
            _ => None,
        }
    }

    /// The verdict in a few words, the `verdict` column of `runs.csv`: `strict α-flock`,
    /// `α-flock`, `not an α-flock`, `flocking`, `not flocking`, a state's name
    /// (`polarised (ordered)`, `torus`, …) or `undefined` (fewer than two agents).
    #[must_use]
    pub fn state(&self) -> &'static str {
        const UNDEFINED: &str = "undefined";
        match self {
            Self::Definition5(v) if !v.is_defined() => UNDEFINED,
            Self::Definition5(v) if v.is_strict() => "strict α-flock",
            Self::Definition5(v) if v.is_alpha_flocking() => "α-flock",
            Self::Definition5(_) => "not an α-flock",
            Self::CuckerSmale(v) if !v.is_defined() => UNDEFINED,
            Self::CuckerSmale(v) => flocking(v.is_velocity_flocking()),
            Self::Order(_, order) => order.state().map_or(UNDEFINED, OrderState::name),
            Self::Couzin(order) => couzin_state(order).map_or(UNDEFINED, CollectiveState::name),
            Self::Vasarhelyi(order) if order.undefined => UNDEFINED,
            Self::Vasarhelyi(order) => flocking(vasarhelyi_flocking(order)),
        }
    }

    /// How the summary names the verdict: `Definition 5`, `Cucker–Smale`, `order`,
    /// `Couzin state`, `Vásárhelyi`.
    #[must_use]
    pub const fn label(&self) -> &'static str {
        match self {
            Self::Definition5(_) => "Definition 5",
            Self::CuckerSmale(_) => "Cucker–Smale",
            Self::Order(..) => "order",
            Self::Couzin(_) => "Couzin state",
            Self::Vasarhelyi(_) => "Vásárhelyi",
        }
    }

    /// The kind of this verdict.
    #[must_use]
    pub const fn kind(&self) -> VerdictKind {
        match self {
            Self::Definition5(_) => VerdictKind::Definition5,
            Self::CuckerSmale(_) => VerdictKind::CuckerSmale,
            Self::Order(model, _) => VerdictKind::Order(model),
            Self::Couzin(_) => VerdictKind::Couzin,
            Self::Vasarhelyi(_) => VerdictKind::Vasarhelyi,
        }
    }
}

/// `flocking` or `not flocking`.
const fn flocking(yes: bool) -> &'static str {
    if yes { "flocking" } else { "not flocking" }
}

/// Couzin et al.'s state of the window's mean p_group and m_group; `None` when undefined.
fn couzin_state(order: &OrderVerdict) -> Option<CollectiveState> {
    (!order.undefined).then(|| CollectiveState::of(order.polarisation, order.milling))
}

/// Vásárhelyi et al.'s flocking: polarised (Tunstrøm's thresholds on the mean O_p and O_r), one
/// group at every record (C* = 1, the net of range r_c) and no pair closer than the collision
/// distance r^coll at any record (φ^coll = 0).
fn vasarhelyi_flocking(order: &OrderVerdict) -> bool {
    order.state() == Some(OrderState::Polarised)
        && order.min_giant_share >= 1.0
        && order.max_collisions == 0
}

/// The window of `criteria` in words.
fn window_text(criteria: &FlockingCriteria) -> String {
    match criteria.window {
        Window::LastFraction(f) => format!("the last {:.0} % of the run", 100.0 * f),
        Window::Between { from, to } => format!("t in [{from}, {to}]"),
    }
}

/// The criteria of a verdict of kind `kind`, in words.
#[must_use]
pub fn criteria_text(kind: VerdictKind, criteria: &FlockingCriteria) -> String {
    let window = window_text(criteria);
    let cohesion = match criteria.cohesion {
        Cohesion::NonGrowing { growth } => {
            format!("R growing by at most {:.0} %", 100.0 * growth)
        }
        Cohesion::Radius(radius) => format!("R ≤ {radius}"),
    };
    let mismatch = format!(
        "K̃ ≤ ε₂ s² with ε₂ = {} (s the group's speed ‖p_c‖, or for a group at rest, ‖p_c‖ < √(2ε₂) v̂, the largest root-mean-square speed v̂ of its agents so far)",
        criteria.epsilon2
    );
    match kind {
        VerdictKind::Definition5 => format!(
            "TAC 2006 Definition 5 over {window}: C* ≥ {}, {cohesion}, Ẽ ≤ ε₁ = {}, {mismatch}; \
             strict: also connected (C = 1) and no pair closer than the collision distance at any record",
            criteria.giant_share, criteria.epsilon1
        ),
        VerdictKind::CuckerSmale => format!(
            "Cucker & Smale 2007 flocking over {window} (the velocities converge to a common one, \
             the group stays together): {mismatch}, {cohesion}"
        ),
        VerdictKind::Order(model) => format!(
            "{model}: the collective state of the mean polarisation O_p (v_a) and milling O_r over \
             {window}: {ORDER_THRESHOLDS}"
        ),
        VerdictKind::Couzin => format!(
            "Couzin et al. 2002's states from the mean p_group and m_group over {window}: torus \
             m ≥ {}, else highly parallel p ≥ {}, dynamic parallel p ≥ {}, swarm otherwise (our \
             borders: the paper draws none)",
            CollectiveState::TORUS,
            CollectiveState::HIGHLY_PARALLEL,
            CollectiveState::PARALLEL
        ),
        VerdictKind::Vasarhelyi => format!(
            "Vásárhelyi et al. 2018 flocking over {window}: polarised ({ORDER_THRESHOLDS}), one \
             group at every record (C* = 1 at the range r_c) and no pair closer than r^coll at any \
             record (φ^coll = 0)"
        ),
    }
}

impl fmt::Display for Verdict {
    /// One line, the first of `flocking.txt` (see [`FlockingVerdict`]'s for Definition 5).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let yes = |b: bool| if b { "yes" } else { "no" };
        match self {
            Self::Definition5(v) => write!(f, "{v}"),
            Self::CuckerSmale(v) => match v.undefined_reason() {
                Some(reason) => write!(
                    f,
                    "Cucker–Smale flocking over [{:.2}, {:.2}] s ({} records): undefined — {reason}",
                    v.from, v.to, v.records
                ),
                None => write!(
                    f,
                    "Cucker–Smale flocking over [{:.2}, {:.2}] s ({} records): {} — R ≤ {:.2} (from {:.2}), {}",
                    v.from,
                    v.to,
                    v.records,
                    yes(v.is_velocity_flocking()),
                    v.max_cohesion_radius,
                    v.initial_cohesion_radius,
                    v.mismatch_text()
                ),
            },
            Self::Order(model, order) => write!(f, "{model}: {} {order}", self.state()),
            Self::Couzin(order) => write!(f, "Couzin et al. 2002 state: {} {order}", self.state()),
            Self::Vasarhelyi(order) => write!(
                f,
                "Vásárhelyi et al. 2018: {} ({}) {order}, pairs closer than r^coll ≤ {}",
                self.state(),
                order.state().map_or("undefined", OrderState::name),
                order.max_collisions
            ),
        }
    }
}
