//! What the papers say of the figures the fixtures reproduce ([`paper_figure`], shown by the
//! gallery page of `flocking figures`): each figure's caption and the statements its text makes,
//! quoted from the seeds (`seeds/*.txt`: 000 the ACC 2004 submission, 001 Tanner, Jadbabaie &
//! Pappas 2003, 002 the TAC 2006 slides, 004 the CDS 03-006 report) beside the measure of our run
//! that checks each; the fixture's parameters, each marked as the paper's or ours; and, where our
//! run does not reproduce the figure, one sentence saying so with the measured numbers.

use flocking::RunSummary;

use crate::data::metric_series::Metrics;

/// A figure of a paper: its caption, the statements its text makes about it, the fixture's
/// parameters and whether our run reproduces it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PaperFigure {
    /// The caption, quoted from the seed.
    pub caption: &'static str,
    /// What the paper states of the run, each with the measure that checks it.
    pub statements: &'static [Statement],
    /// The fixture's parameters, each the paper's or ours (as its header comment says, checked
    /// against the seed), in groups some figures share.
    pub parameters: &'static [&'static [Parameter]],
    /// Why our run does not reproduce the figure, with the measured numbers (`None` when it does).
    pub not_reproduced: Option<&'static str>,
}

/// One statement of a paper and the measure of our run that checks it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Statement {
    /// The paper's words, quoted from the seed with the seed and section.
    pub paper: &'static str,
    /// What of our run to set beside them.
    pub ours: Measure,
}

/// A parameter of a fixture and where its value comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parameter {
    /// The parameter and its value, e.g. "d = 7, r = 1.2 d".
    pub text: &'static str,
    /// Whether the seed gives it.
    pub source: Source,
}

/// Where a parameter's value comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// The seed states it.
    Paper,
    /// The seed does not state it: we chose it.
    Ours,
}

impl Source {
    /// "the paper" or "ours".
    #[must_use]
    pub const fn label(self) -> &'static str {
        match self {
            Self::Paper => "the paper",
            Self::Ours => "ours",
        }
    }
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
    /// The first record from which the proximity net's edge set no longer changes
    /// ([`RunSummary::topology_invariant_from`]).
    TopologyInvariant,
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
                let triangles = match (
                    lattice.equilateral_triangles,
                    lattice.triangles,
                    lattice.equilateral_fraction(),
                ) {
                    (Some(equilateral), Some(all), Some(fraction)) => format!(
                        "{equilateral} of {all} triangles equilateral ({:.0} %)",
                        100.0 * fraction
                    ),
                    _ => format!("triangles not counted ({})", lattice.too_dense()),
                };
                format!(
                    "{triangles}, {:.0} % of {} edges within ±10 % of d",
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
            Self::TopologyInvariant => {
                let from = summary.topology_invariant_from;
                if from < summary.t {
                    format!(
                        "edge set unchanged from t = {} s to the end (t = {} s)",
                        seconds(from),
                        seconds(summary.t)
                    )
                } else {
                    format!(
                        "edge set still changing at t = {} s: the last record changed it",
                        seconds(from)
                    )
                }
            }
        }
    }
}

/// A time in seconds to a hundredth, without round-off digits.
pub(crate) fn seconds(t: f64) -> String {
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

/// A parameter the seed gives.
const fn paper(text: &'static str) -> Parameter {
    Parameter {
        text,
        source: Source::Paper,
    }
}

/// A parameter we chose.
const fn ours(text: &'static str) -> Parameter {
    Parameter {
        text,
        source: Source::Ours,
    }
}

/// Algorithm 2 of the TAC 2006 slides (seed 002).
const TAC_FLOCKING: &[Statement] = &[Statement {
    paper: "“Algorithm 2 creates flocking” (TAC 2006 slides, seed 002, “Free-space Flocking \
            Algorithms”)",
    ours: Measure::FinalFlocking,
}];

/// The parameters of the TAC 2006 slides' “Simulation Results” (seed 002) every fixture of theirs
/// uses.
const TAC_PARAMETERS: &[Parameter] = &[
    paper("d = 7, r = 1.2 d, ε = 0.1 (σ-norm)"),
    paper("h = 0.2 for φ_α"),
    paper("step 0.01 s (the slides: between 0.01 and 0.03 s)"),
];

/// The parameters the seed gives of Algorithm 3's figures (TAC 2006 Fig. 14–17) besides
/// [`TAC_PARAMETERS`].
const TAC_OBSTACLE_PARAMETERS: &[Parameter] = &[
    paper("n = 150"),
    ours(
        "Algorithm 3, 2D: the captions do not say them (the slides show these maneuvers in their obstacle-avoidance part)",
    ),
    paper("d′ = 0.6 d, r′ = 1.2 d′"),
    paper("h = 0.9 for φ_β"),
];

/// Our parameters of Algorithm 3's figures (TAC 2006 Fig. 14–17) but their obstacles.
const TAC_OBSTACLE_OURS: &[Parameter] = &[
    ours(
        "a = 5, b = 20: φ_α's repulsion bound b raised from 5, without which pairs merge in \
         this gain ordering (sweeps/tac2006_fig14_gain_ordering.ron, b = 5)",
    ),
    ours(
        "c₁^α = 3, c₂^α = 2, c₁^γ = 3.5, c₂^γ = 0.5, c₁^β = 30, c₂^β = 2√c₁^β: the \
         ordering c₁^α < c₁^γ < c₁^β of our SPEC.md (the seed states no gains and no ordering), \
         values ours",
    ),
    ours("γ-agent in uniform motion at (3, 0) m/s"),
    ours("start: positions uniform in [−50, 50]², at rest"),
];

/// (paper, figure, what it says) of every figure a fixture reproduces.
const PAPER_FIGURES: &[(&str, &str, PaperFigure)] = &[
    (
        "tac2006",
        "fig9a",
        PaperFigure {
            caption: "“Figure 9: Trapped α-agents due to conflicting objectives: (a) a non-convex \
                      obstacle and (b) a convex obstacle.” (seed 002)",
            statements: &[Statement {
                paper: "“Algorithm 3 attempts to take a direct route” / “May be blocked by \
                            some obstacles” (seed 002)",
                ours: Measure::FinalGiantComponent,
            }],
            parameters: &[
                &[
                    paper(
                        "Algorithm 3 (the slides' text: “Algorithm 3 attempts to take a direct route”)",
                    ),
                    ours("2D: the caption does not say it"),
                    paper("d′ = 0.6 d, r′ = 1.2 d′, h = 0.9 for φ_β"),
                ],
                TAC_PARAMETERS,
                &[
                    ours("n = 30, start: positions uniform in [−30, 0] × [−15, 15]"),
                    ours("obstacle: a cup of three boxes opening towards the flock"),
                    ours("a static γ-agent at (100, 0), behind the cup"),
                    ours("c₁^α = 3, c₂^α = 2, c₁^γ = 1, c₂^γ = 0.3, c₁^β = 30"),
                    ours("duration 100 s"),
                ],
            ],
            // reproduced in kind: the paper's trap with an obstacle and gains of ours (above)
            not_reproduced: None,
        },
    ),
    (
        "tac2006",
        "fig10",
        PaperFigure {
            caption: "“Figure 10: 2-D flocking for n = 150 agents.” (seed 002)",
            statements: TAC_FLOCKING,
            parameters: &[
                &[
                    paper("n = 150, 2D"),
                    ours("Algorithm 2: the caption does not say it"),
                ],
                TAC_PARAMETERS,
                &[
                    ours("a = b = 5"),
                    ours("γ-agent in uniform motion at (1, 0.5) m/s"),
                    ours("c₁ = 0.01, c₂ = 0.4"),
                    ours("start: Gaussian cloud (σ = 50), velocities uniform in [−2, 2]²"),
                    ours("duration 120 s"),
                ],
            ],
            not_reproduced: None,
        },
    ),
    (
        "tac2006",
        "fig11",
        PaperFigure {
            caption: "“Figure 11: 2-D flocking for n = 100 with a dynamic topology.” (seed 002)",
            statements: &[
                TAC_FLOCKING[0],
                Statement {
                    paper: "“Figure 18: The C, R, Ẽ, K̃ curves for simulations in Fig. 11 and \
                            Fig. 12: (a) flocking …” (seed 002)",
                    ours: Measure::ConnectedFrom,
                },
            ],
            parameters: &[
                &[
                    paper("n = 100, 2D, a dynamic topology"),
                    ours("Algorithm 2: the caption does not say it"),
                ],
                TAC_PARAMETERS,
                &[
                    ours("a = b = 5"),
                    ours("γ-agent in uniform motion at (1, 0.5) m/s"),
                    ours("c₁ = 0.02, c₂ = 0.4"),
                    ours("start: Gaussian cloud (σ = 50), velocities uniform in [−2, 2]²"),
                    ours("duration 100 s"),
                ],
            ],
            not_reproduced: None,
        },
    ),
    (
        "tac2006",
        "fig12",
        PaperFigure {
            caption: "“Figure 12: The fragmentation phenomenon for 40 agents applying Algorithm \
                      1.” (seed 002)",
            statements: &[
                Statement {
                    paper: "“Algorithm 1 embodies all 3 Reynolds' rules but rarely results in \
                            flocking” / “Instead, it often creates fragmentation” (seed 002, \
                            “Free-space Flocking Algorithms”)",
                    ours: Measure::FinalFlocking,
                },
                Statement {
                    paper: "“Figure 18: The C, R, Ẽ, K̃ curves for simulations in Fig. 11 and \
                            Fig. 12: … (b) regular fragmentation.” (seed 002)",
                    ours: Measure::Fragments,
                },
            ],
            parameters: &[
                &[
                    paper("Algorithm 1, n = 40"),
                    ours("2D: the caption does not say it"),
                ],
                TAC_PARAMETERS,
                &[
                    ours("a = b = 5"),
                    ours("start: a perturbed triangular lattice moving radially outward at 2 m/s"),
                    ours("duration 60 s"),
                ],
            ],
            not_reproduced: Some(
                "The split is built into the start (one lattice given a 2 m/s outward velocity): \
                 the 42 random starts tried scatter under Algorithm 1 into single agents and pairs \
                 instead of fragmenting into flocks.",
            ),
        },
    ),
    (
        "tac2006",
        "fig13",
        PaperFigure {
            caption: "“Figure 13: Snapshots of 3-D flocking/automated rendezvous using Algorithm \
                      2 for n = 50 UAVs.” (seed 002)",
            statements: TAC_FLOCKING,
            parameters: &[
                &[paper("Algorithm 2, n = 50, 3D, rendezvous")],
                TAC_PARAMETERS,
                &[
                    ours("a = b = 5"),
                    ours("a static rendezvous point at the origin"),
                    ours("c₁ = 0.02, c₂ = 0.4"),
                    ours("start: a ball of radius 40, velocities uniform in [−2, 2]³"),
                    ours("duration 100 s"),
                ],
            ],
            not_reproduced: None,
        },
    ),
    (
        "tac2006",
        "fig14",
        PaperFigure {
            caption: "“Figure 14: The split/rejoin maneuver for n = 150 agents.” (seed 002)",
            statements: &[Statement {
                paper: "“Figure 14: The split/rejoin maneuver for n = 150 agents.” (seed 002; \
                        the seed's text says nothing more of the figure)",
                ours: Measure::LeastGiantComponent,
            }],
            parameters: &[
                TAC_OBSTACLE_PARAMETERS,
                TAC_PARAMETERS,
                TAC_OBSTACLE_OURS,
                &[
                    ours(
                        "obstacle: one convex wedge, tip (110, 0), base x = 200–240, 30 m wide (the \
                         seed: obstacles “restricted to connected convex regions”)",
                    ),
                    ours("duration 170 s"),
                ],
            ],
            not_reproduced: None,
        },
    ),
    (
        "tac2006",
        "fig16",
        PaperFigure {
            caption: "“Figure 16: The squeezing maneuver for n = 150 agents.” (seed 002)",
            statements: &[Statement {
                paper: "“Figure 16: The squeezing maneuver for n = 150 agents.” (seed 002; the \
                        seed's text says nothing more of the figure)",
                ours: Measure::LeastGiantComponent,
            }],
            parameters: &[
                TAC_OBSTACLE_PARAMETERS,
                TAC_PARAMETERS,
                TAC_OBSTACLE_OURS,
                &[
                    ours(
                        "obstacles: two balls of radius 40 at (140, ±54), surfaces 28 = 4 d apart, \
                         their centres beyond the flock's half-width so that every agent is turned \
                         into the gap",
                    ),
                    ours("duration 250 s"),
                ],
            ],
            not_reproduced: None,
        },
    ),
    (
        "cdc2003",
        "fig7",
        PaperFigure {
            caption: "“Figure 7: Consecutive snapshots of flocking for a dynamic α-net with n = 100 \
                      agents in presence of m = 6 obstacles and performing split, rejoin, and \
                      squeezing maneuvers.” (CDC 2003, seed 003)",
            statements: &[
                Statement {
                    paper: "“Most agents asymptotically construct a large flock of 95 agents.” \
                            (CDC 2003, seed 003)",
                    ours: Measure::FinalGiantComponent,
                },
                Statement {
                    paper: "“Figure 7 shows snapshots of the split/rejoin maneuver and the \
                            squeezing maneuver” (CDC 2003, seed 003)",
                    ours: Measure::LeastGiantComponent,
                },
            ],
            parameters: &[&[
                paper("n = 100, m = 6 obstacles"),
                paper("the (α, α) protocol of eq. 14"),
                ours(
                    "a = 1, b = 5: the pair the paper plots in its Fig. 3 (it does not say which \
                     a, b its Fig. 7 ran with)",
                ),
                ours(
                    "everything the CDC paper leaves to the report: the report's d_α = 7, \
                      r = 1.2 d_α, balls of eq. 59 and ‖p_d‖ = 10",
                ),
                ours(
                    "as tr2003_fig7 before its action function changed: p_d = (10, 0), a \
                      per-agent pull c₁ = 0.05, c₂ = 1 to a γ-agent on y = 22.5, c₃ = 30, c₄ = 1, \
                      λ_d = 0.2",
                ),
                ours(
                    "the random start: seed 3, chosen as the first seed whose largest flock at \
                      t = 60 s is 95 (seeds 1–13 give 94–98)",
                ),
            ]],
            not_reproduced: Some(
                "Reproduced only by the choice of the random start: the paper's 95 (the report's \
                 97) lies within the 94–98 that seeds 1–13 give at t = 60 s, and our γ pull, which \
                 the paper does not have, reunites all 100 agents by t = 64 s; pairs closer than \
                 d/4 from 17 to 40 s, as CDS Fig. 7 had with a = 1, b = 5 (its a = 4, b = 80 \
                 keep pairs apart but leave 97–99 in the largest flock over seeds 1–13, never \
                 95).",
            ),
        },
    ),
    (
        "tr2003",
        "fig7",
        PaperFigure {
            caption: "“Figure 7: Consecutive snapshots of flocking for a cluster of n = 100 agents \
                      in presence of m = 6 obstacles and split/rejoin/squeezing maneuvers.” \
                      (CDS 03-006, seed 004)",
            statements: &[
                Statement {
                    paper: "“the location of obstacles are chosen such that split/rejoin \
                            maneuvers have to be performed upon reaching all obstacles” \
                            (CDS 03-006 § 11)",
                    ours: Measure::LeastGiantComponent,
                },
                Statement {
                    paper: "“the portion of the net that is vertically between O5 and O6 needs to \
                            squeeze through the space between the two obstacles” (CDS 03-006 § 11)",
                    ours: Measure::NeverInside,
                },
                Statement {
                    paper: "“the density of the limiting flock is approximately equal to δ0 = 0.97 \
                            (only 3 agents out of 100 agents are not part of the main flock)” \
                            (CDS 03-006 § 11)",
                    ours: Measure::FinalGiantComponent,
                },
                Statement {
                    paper: "“Clearly, all agents (approximately) move with the same velocity and \
                            heading angles.” (CDS 03-006 § 11)",
                    ours: Measure::FinalFlocking,
                },
            ],
            parameters: &[&[
                paper("n = 100, random initial positions, zero initial velocities"),
                paper("d_α = 7, r = 1.2 d_α"),
                paper("the six balls M_obs of eq. 59"),
                paper("‖p_d‖ = 10, c₃ ≫ 1, λ_d ∈ (0, 1]"),
                ours("p_d = (10, 0) (the report writes (0, 10))"),
                ours(
                    "the translational controller: per-agent feedback −c₁(q_i − q_r) − \
                     c₂(p_i − p_r) to a γ-agent on y = 22.5, c₁ = 0.05, c₂ = 1 (not the \
                     report's eq. 58)",
                ),
                ours(
                    "a = 4, b = 80: the γ pull c₃ a within half the α-repulsion's bound b (§ 11 \
                     gives no a, b; with its Fig. 4 pair a = 1, b = 5 pairs collide at the balls)",
                ),
                ours("c₃ = 10, c₄ = 1, λ_d = 0.2"),
                ours("start: positions uniform in [−150, −60] × [0, 40]"),
                ours("duration 60 s"),
            ]],
            not_reproduced: Some(
                "The flock is steered through the gap by a per-agent pull of ours, and 33 of the \
                 100 agents go round O5 and O6 rather than squeeze between them; Definition 5 \
                 fails over the last quarter (the three stragglers and the end of the rejoin: \
                 K̃ ≤ 2.8). C* = 0.97 matches the report's δ₀ ≈ 0.97 only at our 60 s cut (the \
                 report gives no duration): continued, the pull reunites all 100 agents from \
                 t = 68.9 s, and 3 of seeds 1–13 give 0.97 at 60 s.",
            ),
        },
    ),
    (
        "tr2003",
        "fig9",
        PaperFigure {
            caption: "“Figure 9: Consecutive snapshots of conformation of a flock from a net for a \
                      cluster of n = 100 agents in presence of a sink at (qd, pd) = (0, 0).” \
                      (CDS 03-006, seed 004)",
            statements: &[
                Statement {
                    paper: "“The net becomes connected after 4 seconds.” (CDS 03-006 § 11)",
                    ours: Measure::ConnectedFrom,
                },
                Statement {
                    paper: "“The final conformation in this case happens to be a planar graph that \
                            dominantly consists of equilateral triangular faces.” (CDS 03-006 § 11)",
                    ours: Measure::Triangles,
                },
                Statement {
                    paper: "“it has a relatively low normalized defect factor” (CDS 03-006 § 11)",
                    ours: Measure::Diagnostic("normalised_defect_factor"),
                },
                Statement {
                    paper: "“we expect that a net that is initially disconnected, after going \
                            through a finite number of switching events, asymptotically converges \
                            to a flock with an invariant topology” (CDS 03-006 § 11)",
                    ours: Measure::TopologyInvariant,
                },
            ],
            parameters: &[&[
                paper("n = 100, random initial positions, zero initial velocities"),
                paper("a sink at (q_d, p_d) = (0, 0)"),
                paper("f_i = −q_i − c₂ p_i (eq. 50: position gain 1)"),
                paper("d_α = 7, r = 1.2 d_α"),
                ours(
                    "a = 50, b = 250: the shape of the report's Fig. 4 pair (a = 1, b = 5) × 50, \
                     so that a lattice at spacing d bears the sink's pressure (§ 11 gives no a, b)",
                ),
                ours("c₂ = 1 (the report: c₂ > 0)"),
                ours("the influence map's flat part δ = d/r"),
                ours("start: positions uniform in [−40, 40]²"),
                ours("duration 60 s"),
            ]],
            not_reproduced: Some(
                "The lattice stands only because we scaled the report's action function × 50 \
                 (a = 50, b = 250): with its Fig. 4 pair a = 1, b = 5 the sink's gain 1 crushes it. \
                 And the net connects at t = 1.5 s, not “after 4 seconds”.",
            ),
        },
    ),
    (
        "acc2004",
        "fig4",
        PaperFigure {
            caption: "“Figure 4: Consecutive snapshots of conformation of a flock from a net via \
                      flocking of n = 100 agents in presence of a sink at (0,0).” (ACC 2004 \
                      submission, seed 000)",
            statements: &[
                Statement {
                    paper: "“Figure 4 shows an initially disconnected net that evolves into a flock \
                            after going through a finite number of switching events that add more \
                            edges to the initial net.” (ACC 2004, seed 000 § 5)",
                    ours: Measure::ConnectedFrom,
                },
                Statement {
                    paper: "“The topology of the flock is asymptotically invariant.” (ACC 2004, \
                            seed 000 § 5)",
                    ours: Measure::TopologyInvariant,
                },
            ],
            parameters: &[&[
                paper("n = 100, random initial positions, zero initial velocities"),
                paper("d_α = 7, r = 1.2 d_α"),
                paper("the PD sink f_i = −c₁ q_i − c₂ p_i of eq. 40"),
                paper("the C^k influence map of eq. 4"),
                ours("k = 2, flat part δ = d/r"),
                ours("a = 1, b = 5 (the CDS 03-006 report's Fig. 4 pair)"),
                ours(
                    "c₁ = 0.02, c₂ = 1, consensus gain 1 (with a = 1, b = 5 the lattice stands only \
                     for c₁ ≲ 0.05; see CDS Fig. 9)",
                ),
                ours("start: positions uniform in [−50, 50]²"),
                ours("duration 600 s, to an invariant topology"),
            ]],
            not_reproduced: None,
        },
    ),
    (
        "tanner2003",
        "fig3",
        PaperFigure {
            caption: "“Fig. 3. Initial configuration.” … “Fig. 8. Steady state.” (Tanner, \
                      Jadbabaie & Pappas 2003, seed 001 § V; Fig. 4–7: “Initial maneuvering may \
                      bring agents close.”, “Potential forces ensure cohesion.”, “Velocity vectors \
                      converge.”, “The group moves in the same direction.”)",
            statements: &[
                Statement {
                    paper: "“Simulation verifies that the system converges to an invariant set \
                            that corresponds to a tight formation and a common heading \
                            direction.” (seed 001 § V)",
                    ours: Measure::Diagnostic("velocity_disagreement"),
                },
                Statement {
                    paper: "“Interconnected agents cannot collide since this will result in \
                            V_i → ∞” (seed 001 § IV, proof of Theorem IV.4)",
                    ours: Measure::Diagnostic("min_linked_distance"),
                },
                Statement {
                    paper: "“The shape of the formation which the group converges to, is \
                            determined by the artificial potential functions.” (seed 001 § V)",
                    ours: Measure::MinDistance,
                },
            ],
            parameters: &[&[
                paper("N = 10, 2D, the law u_i of eq. 5 on a fixed connected graph"),
                paper("initial positions random in a ball of radius 2.5 m"),
                paper("initial velocities of random direction, magnitude in (0, 1) m/s"),
                paper("a random graph whose only requirement is connectedness"),
                paper("100 s"),
                ours("the pair potential V(z) = d²/z² + ln(z²/d²) − 1, d = 1"),
                ours("the graph: a random spanning tree drawn from seed 99"),
                ours("integrator RK4, step 0.01 s"),
            ]],
            not_reproduced: None,
        },
    ),
];
