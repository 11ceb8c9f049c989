//! What the papers say of the figures the fixtures reproduce: each figure's caption, as the seed
//! prints it, and the statements its text makes, each beside the measure of our run that checks it
//! ([`paper_figure`], shown by the gallery page of `flocking figures`).

use flocking::RunSummary;

use crate::metrics::Metrics;

/// A figure of a paper: its caption and the statements its text makes about it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PaperFigure {
    /// The caption, as the paper prints it.
    pub caption: &'static str,
    /// What the paper states of the run, each with the measure that checks it.
    pub statements: &'static [Statement],
}

/// One statement of a paper and the measure of our run that checks it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Statement {
    /// The paper's words (or numbers).
    pub paper: &'static str,
    /// What of our run to set beside them.
    pub ours: Measure,
}

/// A number of a finished run, from its summary and its `metrics.csv`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Measure {
    /// C and K̃ at the final time.
    FinalFlocking,
    /// C*, the share of the largest component, at the final time.
    FinalGiantComponent,
    /// The least C* once the flock has formed (C = 1), and when: a split.
    LeastGiantComponent,
    /// Whether an agent was inside an obstacle at any record, and the least clearance.
    NeverInside,
    /// The time after which the net stays connected (C = 1 at every later record).
    ConnectedFrom,
    /// The components at the final time and the velocity mismatch within them.
    Fragments,
    /// The share of the final lattice's triangles that are equilateral, and its edges within
    /// ±10 % of d.
    Triangles,
    /// A diagnostic of the protocol at the final time, by its `metrics.csv` name.
    Diagnostic(&'static str),
    /// The least distance between two agents at the final time.
    MinDistance,
}

impl Measure {
    /// The measure of the run with summary `summary` and records `metrics` as text.
    #[must_use]
    pub fn of(self, summary: &RunSummary, metrics: &Metrics) -> String {
        let m = &summary.metrics;
        let t = metrics.time();
        let column = |name: &str| metrics.column(name).unwrap_or_default();
        match self {
            Self::FinalFlocking => format!(
                "C = {:.3}, K̃ = {:.1e} at t = {} s",
                m.connectivity,
                m.velocity_mismatch,
                seconds(summary.t)
            ),
            Self::FinalGiantComponent => format!(
                "C* = {:.2} at t = {} s ({} of {} agents in the largest flock)",
                m.giant_component,
                seconds(summary.t),
                (m.giant_component * summary.agents as f64).round(),
                summary.agents
            ),
            Self::LeastGiantComponent => {
                let (c, giant) = (column("connectivity"), column("giant_component"));
                let Some(formed) = c.iter().position(|&c| c >= 1.0) else {
                    return format!("never one flock; final C = {:.2}", m.connectivity);
                };
                let (k, least) = (formed..giant.len()).map(|k| (k, giant[k])).fold(
                    (formed, f64::INFINITY),
                    |a, b| if b.1 < a.1 { b } else { a },
                );
                format!(
                    "one flock at t = {} s, then least C* = {least:.2} at t = {} s; final C = {:.2}",
                    seconds(t[formed]),
                    seconds(t[k]),
                    m.connectivity
                )
            }
            Self::NeverInside => {
                let inside = column("inside_obstacles")
                    .iter()
                    .copied()
                    .fold(0.0, f64::max);
                let clearance = column("obstacle_clearance")
                    .iter()
                    .copied()
                    .fold(f64::INFINITY, f64::min);
                format!(
                    "at most {inside} agents inside an obstacle at any record; least clearance {clearance:.2}"
                )
            }
            Self::ConnectedFrom => {
                let c = column("connectivity");
                match c.iter().rposition(|&c| c < 1.0) {
                    None => "connected at every record".to_owned(),
                    Some(k) if k + 1 < c.len() => format!(
                        "connected from t = {} s on (C = {:.2} at t = 0)",
                        seconds(t[k + 1]),
                        c[0]
                    ),
                    Some(_) => "not connected at the end".to_owned(),
                }
            }
            Self::Fragments => format!(
                "{} components (C = {:.2}, C* = {:.2}), velocity mismatch within them {:.1e}",
                m.components,
                m.connectivity,
                m.giant_component,
                summary.component_velocity_mismatch
            ),
            Self::Triangles => {
                let lattice = &summary.lattice;
                format!(
                    "{} of {} triangles equilateral ({:.0} %), {:.0} % of {} edges within ±10 % of d",
                    lattice.equilateral_triangles,
                    lattice.triangles,
                    100.0 * lattice.equilateral_fraction(),
                    100.0 * lattice.near_fraction(),
                    lattice.edges
                )
            }
            Self::Diagnostic(name) => summary
                .diagnostics
                .iter()
                .find(|(n, _)| *n == name)
                .map_or_else(
                    || format!("{name}: not recorded"),
                    |(_, v)| {
                        format!(
                            "{} = {v:.3e} at t = {} s",
                            name.replace('_', " "),
                            seconds(summary.t)
                        )
                    },
                ),
            Self::MinDistance => format!(
                "min distance {:.3} at t = {} s",
                m.min_distance,
                seconds(summary.t)
            ),
        }
    }
}

/// A time in seconds to a hundredth, without round-off digits.
fn seconds(t: f64) -> String {
    format!("{}", (t * 100.0).round() / 100.0)
}

/// The figure a fixture's stem reproduces (`tac2006_fig11_…`), if it names one of the seeds'.
#[must_use]
pub fn paper_figure(stem: &str) -> Option<PaperFigure> {
    let mut parts = stem.split('_');
    let key = (parts.next()?, parts.next()?);
    PAPER_FIGURES
        .iter()
        .find(|(paper, figure, _)| (*paper, *figure) == key)
        .map(|&(_, _, figure)| figure)
}

const TAC_FLOCKING: &[Statement] = &[Statement {
    paper: "Algorithm 2 flocks: C → 1, Ẽ and K̃ → 0 (Fig. 18(a), Theorem 3)",
    ours: Measure::FinalFlocking,
}];

/// (paper, figure, what it says) of every figure a fixture reproduces.
const PAPER_FIGURES: &[(&str, &str, PaperFigure)] = &[
    (
        "tac2006",
        "fig10",
        PaperFigure {
            caption: "Figure 10: 2-D flocking for n = 150 agents.",
            statements: TAC_FLOCKING,
        },
    ),
    (
        "tac2006",
        "fig11",
        PaperFigure {
            caption: "Figure 11: 2-D flocking for n = 100 with a dynamic topology.",
            statements: TAC_FLOCKING,
        },
    ),
    (
        "tac2006",
        "fig12",
        PaperFigure {
            caption: "Figure 12: The fragmentation phenomenon for 40 agents applying Algorithm 1.",
            statements: &[Statement {
                paper: "regular fragmentation: several flocks, each moving rigidly (Fig. 18(b))",
                ours: Measure::Fragments,
            }],
        },
    ),
    (
        "tac2006",
        "fig13",
        PaperFigure {
            caption: "Figure 13: Snapshots of 3-D flocking/automated rendezvous using Algorithm 2 \
                      for n = 50 UAVs.",
            statements: TAC_FLOCKING,
        },
    ),
    (
        "tac2006",
        "fig14",
        PaperFigure {
            caption: "Figure 14: The split/rejoin maneuver for n = 150 agents.",
            statements: &[
                Statement {
                    paper: "the flock splits around the obstacles and rejoins",
                    ours: Measure::LeastGiantComponent,
                },
                Statement {
                    paper: "no agent enters an obstacle",
                    ours: Measure::NeverInside,
                },
            ],
        },
    ),
    (
        "tac2006",
        "fig16",
        PaperFigure {
            caption: "Figure 16: The squeezing maneuver for n = 150 agents.",
            statements: &[
                Statement {
                    paper: "the flock squeezes through the gap and stays one flock",
                    ours: Measure::LeastGiantComponent,
                },
                Statement {
                    paper: "no agent enters an obstacle",
                    ours: Measure::NeverInside,
                },
            ],
        },
    ),
    (
        "tr2003",
        "fig7",
        PaperFigure {
            caption: "Figure 7: Consecutive snapshots of flocking for a cluster of n = 100 agents \
                      in presence of m = 6 obstacles and split/rejoin/squeezing maneuvers.",
            statements: &[
                Statement {
                    paper: "split/rejoin maneuvers upon reaching all obstacles",
                    ours: Measure::LeastGiantComponent,
                },
                Statement {
                    paper: "(the obstacles are avoided)",
                    ours: Measure::NeverInside,
                },
                Statement {
                    paper: "density of the limiting flock δ₀ ≈ 0.97 (3 of 100 agents not in the \
                            main flock)",
                    ours: Measure::FinalGiantComponent,
                },
                Statement {
                    paper: "all agents (approximately) move with the same velocity",
                    ours: Measure::FinalFlocking,
                },
            ],
        },
    ),
    (
        "tr2003",
        "fig9",
        PaperFigure {
            caption: "Figure 9: Consecutive snapshots of conformation of a flock from a net for a \
                      cluster of n = 100 agents in presence of a sink at (qd, pd) = (0, 0).",
            statements: &[
                Statement {
                    paper: "the net becomes connected after 4 seconds",
                    ours: Measure::ConnectedFrom,
                },
                Statement {
                    paper: "a planar graph that dominantly consists of equilateral triangular faces",
                    ours: Measure::Triangles,
                },
                Statement {
                    paper: "a relatively low normalized defect factor",
                    ours: Measure::Diagnostic("normalised_defect_factor"),
                },
            ],
        },
    ),
    (
        "acc2004",
        "fig4",
        PaperFigure {
            caption: "Figure 4: Consecutive snapshots of conformation of a flock from a net via \
                      flocking of n = 100 agents in presence of a sink at (0,0).",
            statements: &[
                Statement {
                    paper: "an initially disconnected net evolves into a flock",
                    ours: Measure::ConnectedFrom,
                },
                Statement {
                    paper: "the topology of the flock is asymptotically invariant",
                    ours: Measure::FinalFlocking,
                },
            ],
        },
    ),
    (
        "tanner2003",
        "fig3",
        PaperFigure {
            caption: "Figures 3–8: snapshots of the system's evolution within 100 simulation \
                      seconds (Fig. 3: initial configuration; Fig. 8: steady state).",
            statements: &[
                Statement {
                    paper: "the velocity vectors converge: a common heading direction",
                    ours: Measure::Diagnostic("velocity_disagreement"),
                },
                Statement {
                    paper: "a tight formation; linked agents never collide (Theorem IV.4)",
                    ours: Measure::Diagnostic("min_linked_distance"),
                },
                Statement {
                    paper: "the formation's shape is set by the potentials",
                    ours: Measure::MinDistance,
                },
            ],
        },
    ),
];
