//! What figures call a sweep's parameters: the name and symbol of each dotted path, from one
//! table ([`PARAMETERS`]); an unknown path is called by itself. The metrics' names are beside the
//! columns of `runs.csv` ([`super::metric_label`]).

use crate::Scenario;

/// The parameters by typed path — the dotted path with the enum variants it passes through named
/// and list indices as `#`, so that the `c1` of Algorithm 2 and of the 2003 protocols differ —
/// with their names, symbols (the paper's, empty when it gives none) and units (SI as
/// docs/conditions.md states them — seconds, metres, hertz — empty for a pure number). A path
/// not here is called by itself.
const PARAMETERS: [(&str, &str, &str, &str); 45] = [
    ("agents", "agents", "n", ""),
    ("duration", "duration", "", "s"),
    ("step", "time step", "Δt", "s"),
    ("collision_distance", "collision distance", "", "m"),
    ("integrator", "integrator", "", ""),
    ("vehicle", "vehicle", "", ""),
    ("algorithm", "algorithm", "", ""),
    ("obstacles", "obstacles", "", ""),
    ("obstacles.#", "obstacle", "", ""),
    ("obstacles.#.Ball.radius", "ball radius", "", "m"),
    ("alpha.d", "desired distance", "d", "m"),
    ("alpha.r", "interaction range", "r", "m"),
    ("alpha.epsilon", "σ-norm parameter", "ε", ""),
    ("alpha.h", "bump parameter", "h", ""),
    ("alpha.a", "action parameter", "a", ""),
    ("alpha.b", "action parameter", "b", ""),
    ("alpha.c1", "α gain", "c₁^α", ""),
    ("alpha.c2", "α damping gain", "c₂^α", ""),
    ("algorithm.Algorithm2.c1", "navigational gain", "c₁^γ", ""),
    (
        "algorithm.Algorithm2.c2",
        "navigational damping gain",
        "c₂^γ",
        "",
    ),
    ("algorithm.Algorithm3.c1", "navigational gain", "c₁^γ", ""),
    (
        "algorithm.Algorithm3.c2",
        "navigational damping gain",
        "c₂^γ",
        "",
    ),
    ("algorithm.Algorithm3.beta.c1", "β gain", "c₁^β", ""),
    ("algorithm.Algorithm3.beta.c2", "β damping gain", "c₂^β", ""),
    ("algorithm.Algorithm3.beta.d", "β distance", "d′", "m"),
    ("algorithm.Algorithm3.beta.r", "β range", "r′", "m"),
    ("algorithm.Algorithm3.beta.h", "β bump parameter", "h_β", ""),
    ("algorithm.Flocking2003.c1", "consensus gain", "c₁", ""),
    (
        "algorithm.Flocking2003.avoidance.c3",
        "avoidance gain",
        "c₃",
        "",
    ),
    (
        "algorithm.Flocking2003.translation.c1",
        "translational gain",
        "c₁",
        "",
    ),
    ("algorithm.Vicsek.eta", "noise amplitude", "η", "rad"),
    (
        "algorithm.Couzin.delta_r_o",
        "orientation zone width",
        "Δr_o",
        "m",
    ),
    (
        "algorithm.Couzin.delta_r_a",
        "attraction zone width",
        "Δr_a",
        "m",
    ),
    ("algorithm.Couzin.blend", "blend of the zones", "", ""),
    ("algorithm.Couzin.blind_cone", "blind cone", "", ""),
    (
        "algorithm.Tanner.graph.Random.extra",
        "extra edge probability",
        "",
        "",
    ),
    ("initial.positions.Gaussian.std", "initial spread", "σ", "m"),
    ("initial.positions.Ball.radius", "initial radius", "", "m"),
    (
        "initial.velocities.Gaussian.std",
        "initial speed spread",
        "σ_p",
        "m/s",
    ),
    (
        "conditions.communication.delay",
        "communication delay",
        "τ",
        "s",
    ),
    ("conditions.communication.loss", "packet loss", "", ""),
    (
        "conditions.communication.loss.Bernoulli.p",
        "packet loss probability",
        "p",
        "",
    ),
    ("conditions.control.rate", "control rate", "", "Hz"),
    (
        "conditions.sensing.noise.White.sigma_q",
        "position noise",
        "σ_q",
        "m",
    ),
    (
        "conditions.actuation.max_acceleration",
        "acceleration limit",
        "a_max",
        "m/s²",
    ),
];

/// A parameter of a scenario as a figure names it.
///
/// # Example
/// ```
/// use flocking::Scenario;
/// use flocking::sweep::ParameterLabel;
///
/// let scenario = Scenario::load("../../fixtures/tac2006_fig11_alg2_n100.ron")?;
/// let c1 = ParameterLabel::of(&scenario, "algorithm.c1");
/// assert_eq!(c1.axis(), "navigational gain c₁^γ");
/// let delay = ParameterLabel::of(&scenario, "conditions.communication.delay");
/// assert_eq!(delay.axis(), "communication delay τ (s)");
/// assert_eq!(c1.short(), "c₁^γ");
/// assert_eq!(ParameterLabel::of(&scenario, "agents").axis(), "agents n");
/// assert_eq!(ParameterLabel::of(&scenario, "seed").axis(), "seed");
/// # Ok::<(), flocking::ScenarioError>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParameterLabel {
    /// The dotted path (`algorithm.c1`).
    pub path: String,
    /// Its name, symbol and unit (each but the name empty when it has none); `None` for a path
    /// the table does not know.
    pub known: Option<(&'static str, &'static str, &'static str)>,
}

impl ParameterLabel {
    /// The label of `path` in `scenario` (whose algorithm and obstacles say what the path is).
    #[must_use]
    pub fn of(scenario: &Scenario, path: &str) -> Self {
        let typed = scenario.typed_path(path);
        let known = PARAMETERS
            .iter()
            // a section the scenario leaves unset has no typed path: by its path
            .find(|(key, ..)| typed.as_deref().unwrap_or(path) == *key)
            .map(|&(_, name, symbol, unit)| (name, symbol, unit));
        Self {
            path: path.to_owned(),
            known,
        }
    }

    /// The label of an axis: name, symbol and unit ("communication delay τ (s)", "navigational
    /// gain c₁^γ", "agents n"); the path alone when unknown.
    #[must_use]
    pub fn axis(&self) -> String {
        match self.unit() {
            "" => self.name(),
            unit => format!("{} ({unit})", self.name()),
        }
    }

    /// Its name and symbol, without the unit ("communication delay τ"; a dataset's
    /// `long_name`); the path alone when unknown.
    #[must_use]
    pub fn name(&self) -> String {
        match self.known {
            None => self.path.clone(),
            Some((name, "", _)) => name.to_owned(),
            Some((name, symbol, _)) => format!("{name} {symbol}"),
        }
    }

    /// The unit of the parameter (SI: "s", "m", "m/s²"), empty for a pure number or an unknown
    /// path.
    #[must_use]
    pub fn unit(&self) -> &'static str {
        self.known.map_or("", |(_, _, unit)| unit)
    }

    /// What stands before a value (`n` in "n = 50"): the symbol, else the name, else the path.
    #[must_use]
    pub fn short(&self) -> &str {
        match self.known {
            Some((_, symbol, _)) if !symbol.is_empty() => symbol,
            Some((name, ..)) => name,
            None => &self.path,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{PARAMETERS, ParameterLabel};
    use crate::sweep::Sweep;

    /// Every axis of every sweep file of the repository is named by the table (a new sweep over
    /// an unnamed parameter fails here until it is named), each typed path is named once, and an
    /// unknown path is called by itself.
    #[test]
    fn every_swept_path_has_a_name_and_a_unit_rule() {
        let sweeps = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../sweeps");
        let mut unnamed = Vec::new();
        let mut checked = 0;
        for entry in std::fs::read_dir(&sweeps).expect("sweeps/") {
            let path = entry.expect("an entry").path();
            if path.extension().is_none_or(|e| e != "ron") {
                continue;
            }
            let sweep = Sweep::load(&path).expect("a sweep");
            let base = sweep.base_scenario().expect("its base");
            for axis in &sweep.axes {
                let label = ParameterLabel::of(&base, &axis.path);
                checked += 1;
                if label.known.is_none() {
                    unnamed.push(format!(
                        "{}: {} ({:?})",
                        path.display(),
                        axis.path,
                        base.typed_path(&axis.path)
                    ));
                }
            }
        }
        assert!(checked >= 20, "{checked} axes");
        assert!(unnamed.is_empty(), "unnamed: {unnamed:#?}");
        let mut keys: Vec<&str> = PARAMETERS.iter().map(|(key, ..)| *key).collect();
        keys.sort_unstable();
        let count = keys.len();
        keys.dedup();
        assert_eq!(keys.len(), count, "a typed path named twice");
        let scenario = Sweep::load(sweeps.join("alg2_c1_n.ron"))
            .expect("a sweep")
            .base_scenario()
            .expect("its base");
        let unknown = ParameterLabel::of(&scenario, "alpha.nonexistent");
        assert_eq!(unknown.axis(), "alpha.nonexistent");
        assert_eq!(unknown.short(), "alpha.nonexistent");
        assert_eq!(unknown.unit(), "");
        let delay = ParameterLabel::of(&scenario, "conditions.communication.delay");
        assert_eq!(delay.axis(), "communication delay τ (s)");
        assert_eq!(delay.unit(), "s");
    }
}
