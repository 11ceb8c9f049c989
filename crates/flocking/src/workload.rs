//! The workloads of the agent-based modelling frameworks' boids benchmark (JuliaDynamics
//! ABMFrameworksComparison, `Flocking/DECLARATION.md`), timed as the frameworks time them: 100
//! steps of the model from a fresh random start, the median over seeds, so that our figures
//! stand beside their published ones; and the Vicsek model at its paper's density, timed the
//! same way. `flocking bench --workload` prints them.

use std::fmt;
use std::str::FromStr;
use std::time::{Duration, Instant};

use serde_json::json;

use crate::bench::BenchError;
use crate::error::ScenarioError;
use crate::estimate::{Estimate, Outputs};
use crate::scenario::{Algorithm, DomainSpec};
use crate::{DynSimulation, Scenario};

/// A workload: the boids benchmark's two, or Vicsek's model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Workload {
    /// 200 birds in a 100 × 100 periodic box, visual distance 5, 100 steps.
    BoidsSmall,
    /// 400 birds in a 150 × 150 periodic box, visual distance 15, 100 steps.
    BoidsLarge,
    /// The Vicsek model of `fixtures/vicsek1995_fig2a_n400.ron` (Vicsek et al. 1995 Fig. 2(a):
    /// 400 particles at density 4, r = 1, v₀ = 0.03, η = 2), 100 steps.
    Vicsek,
}

impl Workload {
    /// Every workload, in the order of [`Self::NAMES`].
    pub const ALL: [Self; 3] = [Self::BoidsSmall, Self::BoidsLarge, Self::Vicsek];

    /// The names `flocking bench --workload` and Python's `workload=` take.
    pub const NAMES: [&'static str; 3] = ["boids-small", "boids-large", "vicsek"];

    /// Its scenario: `fixtures/boids_small_n200.ron`, `fixtures/boids_large_n400.ron`, or
    /// `fixtures/vicsek1995_fig2a_n400.ron` cut to 100 steps.
    ///
    /// # Panics
    /// Never: the fixtures are compiled in and checked by the tests.
    #[must_use]
    pub fn scenario(self) -> Scenario {
        let (text, name) = match self {
            Self::BoidsSmall => (
                include_str!("../../../fixtures/boids_small_n200.ron"),
                "boids_small_n200.ron",
            ),
            Self::BoidsLarge => (
                include_str!("../../../fixtures/boids_large_n400.ron"),
                "boids_large_n400.ron",
            ),
            Self::Vicsek => (
                include_str!("../../../fixtures/vicsek1995_fig2a_n400.ron"),
                "vicsek1995_fig2a_n400.ron",
            ),
        };
        let scenario = Scenario::parse(text, name).unwrap_or_else(|e| unreachable!("{name}: {e}"));
        let steps = 100.0 * scenario.step;
        scenario
            .with_values([("duration", json!(steps))])
            .unwrap_or_else(|e| unreachable!("{name} over 100 steps: {e}"))
    }

    /// The workload with `agents` agents at its own density (the box grown to keep the agents per
    /// unit area of its scenario), positions uniform in the box.
    ///
    /// # Errors
    /// A number of agents the scenario refuses (0, or too many).
    pub fn scaled(self, agents: usize) -> Result<Scenario, ScenarioError> {
        let scenario = self.scenario();
        let density = match &scenario.domain {
            DomainSpec::Periodic { size } => scenario.agents as f64 / size.iter().product::<f64>(),
            DomainSpec::PeriodicAtDensity { density } => *density,
            DomainSpec::Open => unreachable!("the workloads are periodic"),
        };
        scenario.with_values([
            ("agents", json!(agents)),
            ("domain", json!({"PeriodicAtDensity": {"density": density}})),
            ("initial.positions", json!("Domain")),
        ])
    }
}

impl FromStr for Workload {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        crate::bench::one_of(s, "workload", &Self::NAMES, &Self::ALL)
    }
}

/// The timings of a workload.
#[derive(Clone, Debug, PartialEq)]
pub struct WorkloadReport {
    /// The scenario timed.
    pub scenario: Scenario,
    /// The time of the scenario's steps for each seed 0, 1, …, in order.
    pub times: Vec<Duration>,
    /// The time of building each seed's model (its random start and its net), in the same order:
    /// the frameworks' own benchmarks time it with the steps.
    pub built: Vec<Duration>,
    /// Worker threads of the rayon pool that ran them.
    pub threads: usize,
}

impl WorkloadReport {
    /// The median time of the steps over the seeds (the mean of the two middle ones for an even
    /// count).
    #[must_use]
    pub fn median(&self) -> Duration {
        median_of(self.times.clone())
    }

    /// The median over the seeds of the time of building the model and taking its steps, as the
    /// frameworks time them.
    #[must_use]
    pub fn median_with_building(&self) -> Duration {
        median_of(
            self.times
                .iter()
                .zip(&self.built)
                .map(|(t, b)| *t + *b)
                .collect(),
        )
    }

    /// Agent-steps per second at the median.
    #[must_use]
    pub fn agent_steps_per_second(&self) -> f64 {
        let work = self.scenario.agents as f64 * self.scenario.steps() as f64;
        work / self.median().as_secs_f64()
    }
}

/// The median of `times` (the mean of the two middle ones for an even count; zero for none).
fn median_of(mut times: Vec<Duration>) -> Duration {
    times.sort_unstable();
    let n = times.len();
    if n == 0 {
        return Duration::ZERO;
    }
    if n % 2 == 1 {
        times[n / 2]
    } else {
        (times[n / 2 - 1] + times[n / 2]) / 2
    }
}

/// One line: the scenario, the median of the steps, the least and most times, agent-steps/s and
/// threads, then the median with the model's building.
impl fmt::Display for WorkloadReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = &self.scenario;
        let agents = match s.algorithm {
            Algorithm::Boids(_) => "birds",
            _ => "agents",
        };
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        let least = self.times.iter().min().copied().unwrap_or_default();
        let most = self.times.iter().max().copied().unwrap_or_default();
        write!(
            f,
            "{}: {} {agents}, box {:?}, {} steps, {} seed(s): median {:.3} ms (least {:.3}, most {:.3}), {:.3e} agent-steps/s on {} thread(s); with building the model, median {:.3} ms",
            s.name,
            s.agents,
            s.box_size().unwrap_or_default(),
            s.steps(),
            self.times.len(),
            ms(self.median()),
            ms(least),
            ms(most),
            self.agent_steps_per_second(),
            self.threads,
            ms(self.median_with_building()),
        )
    }
}

/// What `flocking bench --workload` times: a workload, the seeds it is timed on and the number of
/// agents it is scaled to (its own when `None`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WorkloadConfig {
    /// The workload.
    pub workload: Workload,
    /// The number of seeds timed, 1 to [`MAX_RUNS`](crate::sweep::MAX_RUNS).
    pub seeds: u64,
    /// This many agents at the workload's density, or its own number.
    pub scale_to: Option<usize>,
}

impl WorkloadConfig {
    /// The workload's scenario, its seeds and size checked as `flocking run` and `flocking sweep`
    /// check theirs.
    ///
    /// # Errors
    /// No seed or more than a sweep's runs (`seeds`), or a size the scenario refuses (`scale_to`:
    /// none, or more than [`crate::MAX_AGENTS`]).
    pub fn scenario(&self) -> Result<Scenario, BenchError> {
        let most = crate::sweep::MAX_RUNS as u64;
        if !(1..=most).contains(&self.seeds) {
            return Err(BenchError::Invalid {
                flag: "seeds".to_owned(),
                value: self.seeds.to_string(),
                why: format!("is the number of seeds timed; it must be 1 to {most}"),
                fix: "give a whole number of seeds from 1 (the frameworks time 10)".to_owned(),
            });
        }
        match self.scale_to {
            None => Ok(self.workload.scenario()),
            Some(agents) if !(1..=crate::MAX_AGENTS).contains(&agents) => {
                Err(BenchError::Invalid {
                    flag: "scale_to".to_owned(),
                    value: agents.to_string(),
                    why: format!(
                        "is the number of agents the workload is scaled to; it must be 1 to {}",
                        crate::MAX_AGENTS
                    ),
                    fix: format!(
                        "give a whole number of agents (the workload's own is {})",
                        self.workload.scenario().agents
                    ),
                })
            }
            Some(agents) => self
                .workload
                .scaled(agents)
                .map_err(|e| BenchError::of_scenario(&e, &[("agents", "scale_to")])),
        }
    }

    /// What timing every seed will cost, as `flocking run` estimates a run, the start's net counted.
    ///
    /// # Errors
    /// As [`WorkloadConfig::scenario`].
    pub fn estimate(&self) -> Result<Estimate, BenchError> {
        Ok(self
            .scenario()?
            .estimate_at_start(&Outputs::NONE)
            .times(self.seeds))
    }
}

/// Times `scenario`'s steps (no metrics, no output: the model alone, as the frameworks time it)
/// from seeds 0 to `seeds` − 1, and apart from them the building of each seed's model.
///
/// # Errors
/// A scenario refused with a seed (or memory it cannot have), or the process's interrupt
/// ([`crate::interrupt`]) between two steps.
pub fn time_seeds(scenario: &Scenario, seeds: u64) -> Result<WorkloadReport, BenchError> {
    let (mut times, mut built) = (Vec::new(), Vec::new());
    for seed in 0..seeds {
        let refused = |e: ScenarioError| BenchError::of_scenario(&e, &[]);
        let seeded = scenario
            .with_values([("seed", json!(seed))])
            .map_err(refused)?;
        let building = Instant::now();
        let mut sim = DynSimulation::new(&seeded).map_err(refused)?;
        built.push(building.elapsed());
        let start = Instant::now();
        for _ in 0..seeded.steps() {
            let before = sim.steps();
            sim.step();
            if sim.steps() == before || crate::interrupt::requested() {
                return Err(BenchError::Interrupted);
            }
        }
        times.push(start.elapsed());
    }
    Ok(WorkloadReport {
        scenario: scenario.clone(),
        times,
        built,
        threads: rayon::current_num_threads(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_workloads_are_the_declaration() {
        let small = Workload::BoidsSmall.scenario();
        assert_eq!((small.agents, small.steps()), (200, 100));
        assert_eq!(small.box_size(), Some(vec![100.0, 100.0]));
        let large = Workload::BoidsLarge.scenario();
        assert_eq!((large.agents, large.steps()), (400, 100));
        assert_eq!(large.box_size(), Some(vec![150.0, 150.0]));
        // scaled at the declaration's density: 200 birds per 10⁴ square units
        let million = Workload::BoidsSmall.scaled(1_000_000).expect("valid");
        let side = million.box_size().expect("periodic")[0];
        assert!((side - (1e6_f64 / 0.02).sqrt()).abs() < 1e-9, "{side}");
        let report = time_seeds(
            &small
                .with_values([("duration", json!(3.0))])
                .expect("valid"),
            3,
        )
        .expect("runs");
        assert_eq!(report.times.len(), 3);
        assert!(
            report.to_string().starts_with(
                "boids_small_n200: 200 birds, box [100.0, 100.0], 3 steps, 3 seed(s): median"
            ),
            "{report}"
        );
        assert_eq!("Boids_Large".parse(), Ok(Workload::BoidsLarge));
        // Vicsek's Fig. 2(a) over 100 steps of Δt = 1, scaled at ρ = 4
        let vicsek = Workload::Vicsek.scenario();
        assert_eq!((vicsek.agents, vicsek.steps()), (400, 100));
        assert_eq!(vicsek.box_size(), Some(vec![10.0, 10.0]));
        let side = Workload::Vicsek
            .scaled(1_000_000)
            .expect("valid")
            .box_size();
        assert_eq!(side, Some(vec![500.0, 500.0]));
        assert!("boids".parse::<Workload>().is_err());
        assert!(report.median() <= *report.times.iter().max().expect("three"));
        assert_eq!(report.built.len(), 3);
        assert!(report.median_with_building() > report.median(), "{report}");
        // the median of an even count is the mean of the two middle ones
        let ms = Duration::from_millis;
        assert_eq!(median_of(vec![ms(4), ms(1), ms(2), ms(9)]), ms(3));
        assert_eq!(median_of(Vec::new()), Duration::ZERO);
    }
}
