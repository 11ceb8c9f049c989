//! What figures call a sweep's parameters: the name and symbol of each dotted path, from one
//! table ([`PARAMETERS`]); an unknown path is called by itself. The metrics' names are beside the
//! columns of `runs.csv` ([`super::metric_label`]).

use crate::Scenario;

/// The parameters by typed path — the dotted path with the enum variants it passes through named
/// and list indices as `#`, so that the `c1` of Algorithm 2 and of the 2003 protocols differ —
/// with their names and symbols (TAC 2006's, empty when the paper gives none).
const PARAMETERS: [(&str, &str, &str); 25] = [
    ("agents", "agents", "n"),
    ("duration", "duration", ""),
    ("step", "time step", "Δt"),
    ("collision_distance", "collision distance", ""),
    ("alpha.d", "desired distance", "d"),
    ("alpha.r", "interaction range", "r"),
    ("alpha.epsilon", "σ-norm parameter", "ε"),
    ("alpha.h", "bump parameter", "h"),
    ("alpha.c1", "α gain", "c₁^α"),
    ("alpha.c2", "α damping gain", "c₂^α"),
    ("algorithm.Algorithm2.c1", "navigational gain", "c₁^γ"),
    (
        "algorithm.Algorithm2.c2",
        "navigational damping gain",
        "c₂^γ",
    ),
    ("algorithm.Algorithm3.c1", "navigational gain", "c₁^γ"),
    (
        "algorithm.Algorithm3.c2",
        "navigational damping gain",
        "c₂^γ",
    ),
    ("algorithm.Algorithm3.beta.c1", "β gain", "c₁^β"),
    ("algorithm.Algorithm3.beta.c2", "β damping gain", "c₂^β"),
    ("algorithm.Algorithm3.beta.d", "β distance", "d′"),
    ("algorithm.Algorithm3.beta.r", "β range", "r′"),
    ("algorithm.Algorithm3.beta.h", "β bump parameter", "h_β"),
    ("algorithm.Flocking2003.c1", "consensus gain", "c₁"),
    ("obstacles.#.Ball.radius", "ball radius", ""),
    ("initial.positions.Gaussian.std", "initial spread", "σ"),
    ("initial.positions.Ball.radius", "initial radius", ""),
    (
        "initial.velocities.Gaussian.std",
        "initial speed spread",
        "σ_p",
    ),
    (
        "algorithm.Tanner.graph.Random.extra",
        "extra edge probability",
        "",
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
/// assert_eq!(c1.axis(), "navigational gain c₁^γ (algorithm.c1)");
/// assert_eq!(c1.short(), "c₁^γ");
/// assert_eq!(ParameterLabel::of(&scenario, "agents").axis(), "agents n");
/// assert_eq!(ParameterLabel::of(&scenario, "seed").axis(), "seed");
/// # Ok::<(), flocking::ScenarioError>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParameterLabel {
    /// The dotted path (`algorithm.c1`).
    pub path: String,
    /// Its name and symbol (the symbol empty when it has none); `None` for a path the table does
    /// not know.
    pub known: Option<(&'static str, &'static str)>,
}

impl ParameterLabel {
    /// The label of `path` in `scenario` (whose algorithm and obstacles say what the path is).
    #[must_use]
    pub fn of(scenario: &Scenario, path: &str) -> Self {
        let typed = scenario.typed_path(path);
        let known = PARAMETERS
            .iter()
            .find(|(key, _, _)| typed.as_deref() == Some(key))
            .map(|&(_, name, symbol)| (name, symbol));
        Self {
            path: path.to_owned(),
            known,
        }
    }

    /// The label of an axis: name, symbol and path ("navigational gain c₁^γ (algorithm.c1)";
    /// "agents n", whose name is its path); the path alone when unknown.
    #[must_use]
    pub fn axis(&self) -> String {
        let Some((name, symbol)) = self.known else {
            return self.path.clone();
        };
        let mut label = name.to_owned();
        if !symbol.is_empty() {
            label = format!("{label} {symbol}");
        }
        if name != self.path {
            label = format!("{label} ({})", self.path);
        }
        label
    }

    /// What stands before a value (`n` in "n = 50"): the symbol, else the name, else the path.
    #[must_use]
    pub fn short(&self) -> &str {
        match self.known {
            Some((_, symbol)) if !symbol.is_empty() => symbol,
            Some((name, _)) => name,
            None => &self.path,
        }
    }
}
