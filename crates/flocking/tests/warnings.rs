//! The warnings before a run (issue 53), one scenario that triggers each and one that does not:
//! a γ-agent faster than the vehicle, initial velocities the vehicle clips, a model of one step
//! at another step than its paper's, a start denser than the α-lattice (and the merge it makes
//! at t = 0 named as the start's); and the estimate of an all-pairs model counting every pair.

use flocking::estimate::{ALL_PAIRS_SECONDS, Outputs};
use flocking::{Merge, MergeCause, Recorder, Scenario, Warning};

/// A 2D scenario of 100 agents, TAC 2006 Fig. 11's numbers (d = 7, Gaussian start of σ = 50,
/// step 0.01) with the parts given.
fn scenario(
    algorithm: &str,
    vehicle: &str,
    positions: &str,
    velocities: &str,
    step: f64,
) -> Scenario {
    let text = format!(
        "Scenario(
            name: \"warnings\",
            dim: 2,
            agents: 100,
            seed: 11,
            algorithm: {algorithm},
            vehicle: {vehicle},
            initial: (positions: {positions}, velocities: {velocities}),
            step: {step:?},
            duration: 1.0,
        )"
    );
    Scenario::parse(&text, "warnings.ron").unwrap_or_else(|e| panic!("{e}"))
}

const SPREAD: &str = "Gaussian(mean: [0.0, 0.0], std: 50.0)";
const SLOW: &str = "Box(min: [-0.05, -0.05], max: [0.05, 0.05])";

/// Algorithm 2 behind a γ-agent of `velocity`.
fn algorithm2(velocity: &str) -> String {
    format!(
        "Algorithm2(gamma: ConstantVelocity(position: [0.0, 0.0], velocity: {velocity}), c1: 0.02, c2: 0.4)"
    )
}

/// The warnings of `scenario` on `field`.
fn on(scenario: &Scenario, field: &str) -> Vec<Warning> {
    scenario
        .warnings()
        .into_iter()
        .filter(|w| w.field == field)
        .collect()
}

#[test]
fn a_gamma_agent_faster_than_the_vehicle_is_warned_about() {
    // Fig. 11's γ-agent, 1.12 m/s, on TurtleBot3s of 0.22 m/s
    let fast = scenario(
        &algorithm2("[1.0, 0.5]"),
        "Unicycle(())",
        SPREAD,
        SLOW,
        0.01,
    );
    let warnings = on(&fast, "algorithm.gamma.velocity");
    assert_eq!(warnings.len(), 1, "{:?}", fast.warnings());
    let text = warnings[0].to_string();
    for part in [
        "speed 1.118",
        "vehicle.max_speed = 0.22",
        "groups",
        "slower than 0.22",
    ] {
        assert!(text.contains(part), "{part}: {text}");
    }
    // a wheel limit below max_speed is the top speed
    let wheels = scenario(
        &algorithm2("[0.2, 0.0]"),
        "Unicycle((max_speed: 0.3, max_wheel_speed: 0.15))",
        SPREAD,
        SLOW,
        0.01,
    );
    let warnings = on(&wheels, "algorithm.gamma.velocity");
    assert_eq!(warnings.len(), 1, "{:?}", wheels.warnings());
    assert!(
        warnings[0]
            .to_string()
            .contains("vehicle.max_wheel_speed = 0.15")
    );
    // a path's speed on a fixed wing, and the 2003 protocols' translation
    let path = scenario(
        "Algorithm2(gamma: Path(waypoints: [[0.0, 0.0], [1000.0, 0.0]], speed: 40.0), c1: 0.02, c2: 0.4)",
        "FixedWing(())",
        SPREAD,
        "Headings(speed: 25.0)",
        0.01,
    );
    assert_eq!(on(&path, "algorithm.gamma.speed").len(), 1);

    // at the unicycle fixture's 0.11 m/s, below the top speed; and no vehicle, no limit
    let slow = scenario(
        &algorithm2("[0.1, 0.05]"),
        "Unicycle(())",
        SPREAD,
        SLOW,
        0.01,
    );
    assert_eq!(slow.warnings(), []);
    let point_masses = scenario(&algorithm2("[1.0, 0.5]"), "PointMass", SPREAD, SLOW, 0.01);
    assert_eq!(point_masses.warnings(), []);
}

#[test]
fn initial_velocities_the_vehicle_clips_are_warned_about() {
    let gamma = algorithm2("[0.1, 0.05]");
    // Fig. 11's start, uniform in [−2, 2]², on robots of 0.22 m/s
    let fast = scenario(
        &gamma,
        "Unicycle(())",
        SPREAD,
        "Box(min: [-2.0, -2.0], max: [2.0, 2.0])",
        0.01,
    );
    let warnings = on(&fast, "initial.velocities");
    assert_eq!(warnings.len(), 1, "{:?}", fast.warnings());
    let text = warnings[0].to_string();
    assert!(
        text.contains("clips") && text.contains("Headings(speed: 0.22)"),
        "{text}"
    );
    // the fixed wing above its max_airspeed (32 m/s)
    let plane = scenario(
        "Algorithm2(gamma: ConstantVelocity(position: [0.0, 0.0], velocity: [25.0, 0.0]), c1: 0.02, c2: 0.4)",
        "FixedWing(())",
        SPREAD,
        "Headings(speed: 40.0)",
        0.01,
    );
    assert_eq!(on(&plane, "initial.velocities").len(), 1);

    // at the top speed (to round-off) nothing is clipped
    let at_limit = scenario(
        &gamma,
        "Unicycle(())",
        SPREAD,
        "Headings(speed: 0.22)",
        0.01,
    );
    assert_eq!(at_limit.warnings(), []);
    let plane_ok = scenario(
        "Algorithm2(gamma: ConstantVelocity(position: [0.0, 0.0], velocity: [25.0, 0.0]), c1: 0.02, c2: 0.4)",
        "FixedWing(())",
        SPREAD,
        "Headings(speed: 25.0)",
        0.01,
    );
    assert_eq!(plane_ok.warnings(), []);
}

#[test]
fn a_model_at_another_step_than_its_papers_is_warned_about() {
    let headings = "Headings(speed: 0.5)";
    let box_start = "Box(min: [0.0, 0.0], max: [20.0, 20.0])";
    for (algorithm, paper) in [
        ("Vicsek(eta: 2.0)", 1.0),
        ("Boids()", 1.0),
        ("Couzin(delta_r_o: 1.0, delta_r_a: 14.0)", 0.1),
    ] {
        // swapped into an Olfati-Saber scenario at step 0.01
        let swapped = scenario(algorithm, "PointMass", box_start, headings, 0.01);
        let warnings = on(&swapped, "step");
        assert_eq!(warnings.len(), 1, "{algorithm}: {:?}", swapped.warnings());
        let text = warnings[0].to_string();
        assert!(text.contains(&format!("set `step: {paper:?}`")), "{text}");
        // at the paper's step
        let at_paper = scenario(algorithm, "PointMass", box_start, headings, paper);
        assert_eq!(at_paper.warnings(), [], "{algorithm}");
    }
    // the differential equations have no step of their paper
    let cucker_smale = scenario("CuckerSmale(beta: 0.25)", "PointMass", SPREAD, SLOW, 0.5);
    assert_eq!(on(&cucker_smale, "step"), []);
}

/// Keeps the first merge a run tells.
#[derive(Default)]
struct FirstMerge(Option<Merge>);

impl Recorder for FirstMerge {
    type Error = std::convert::Infallible;
    fn record(&mut self, _record: &flocking::Record<'_>) -> Result<(), Self::Error> {
        Ok(())
    }
    fn merged(&mut self, merge: &Merge) {
        self.0.get_or_insert_with(|| merge.clone());
    }
}

#[test]
fn a_start_denser_than_the_lattice_is_warned_about_and_named_as_the_cause_of_its_merges() {
    let gamma = algorithm2("[1.0, 0.5]");
    // 100 agents in a 20 m square with d = 7: 37 neighbours each within r, the lattice's 6
    let dense = scenario(
        &gamma,
        "PointMass",
        "Box(min: [-10.0, -10.0], max: [10.0, 10.0])",
        SLOW,
        0.01,
    );
    let warnings = on(&dense, "initial.positions");
    assert_eq!(warnings.len(), 1, "{:?}", dense.warnings());
    let text = warnings[0].to_string();
    // n · √3/2 d² = 100 · 42.44 = 4243.5, a square of side 65.1
    for part in [
        "denser than the α-lattice",
        "37.2 neighbours",
        "4243.5",
        "side 65.1",
    ] {
        assert!(text.contains(part), "{part}: {text}");
    }
    // Fig. 11's spread start, and a start at about the lattice's density (n · √3/2 d² in a
    // square of side 65), are not dense
    assert_eq!(
        on(
            &scenario(&gamma, "PointMass", SPREAD, SLOW, 0.01),
            "initial.positions"
        ),
        []
    );
    let lattice = scenario(
        &gamma,
        "PointMass",
        "Box(min: [-32.5, -32.5], max: [32.5, 32.5])",
        SLOW,
        0.01,
    );
    assert_eq!(on(&lattice, "initial.positions"), []);

    // 300 agents in a 4 m square place a pair within 10⁻³ d at t = 0 (seed 1): the merge is the
    // start's, named so, with the spread as the fix; the run parts them and flocks
    let text = "Scenario(
        name: \"dense\", dim: 2, agents: 300, seed: 1,
        algorithm: Algorithm2(gamma: ConstantVelocity(position: [0.0, 0.0], velocity: [1.0, 0.5]), c1: 0.02, c2: 0.4),
        initial: (positions: Box(min: [-2.0, -2.0], max: [2.0, 2.0])),
        step: 0.01, duration: 0.2, record_every: 10,
    )";
    let packed = Scenario::parse(text, "dense.ron").unwrap_or_else(|e| panic!("{e}"));
    let mut first = FirstMerge::default();
    flocking::run(&packed, &mut first).unwrap_or_else(|e| panic!("{e}"));
    let merge = first.0.expect("a pair within 10⁻³ d at the start");
    assert_eq!(merge.t, 0.0);
    let MergeCause::Start(Some(start)) = merge.cause else {
        panic!("the start named as the cause: {merge:?}");
    };
    assert!(start.degree > 2.0 * start.lattice, "{start:?}");
    let message = merge.to_string();
    assert!(
        message.contains("start merged") && message.contains("spread `initial.positions`"),
        "{message}"
    );
    assert!(!message.contains("lower the gain"), "{message}");
}

#[test]
fn the_estimate_of_an_all_pairs_model_counts_every_pair() {
    // Fig. 11 swapped to Cucker–Smale without a cutoff (issue 53: "about 0.0 s", ran 1.9 s)
    let every_pair = scenario("CuckerSmale(beta: 0.25)", "PointMass", SPREAD, SLOW, 0.01);
    let cutoff = scenario(
        "CuckerSmale(beta: 0.25, cutoff: 8.4)",
        "PointMass",
        SPREAD,
        SLOW,
        0.01,
    );
    let (all, local) = (
        every_pair.estimate_at_start(&Outputs::NONE),
        cutoff.estimate_at_start(&Outputs::NONE),
    );
    // each agent-step sums over the 99 others
    let pairs = all.agent_steps * 99.0 * ALL_PAIRS_SECONDS;
    assert!(all.seconds >= pairs, "{all}");
    assert!(
        all.seconds - local.seconds >= 0.99 * pairs,
        "{all} against {local}"
    );
}
