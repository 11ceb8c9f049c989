//! The classic models as scenarios: Couzin et al. 2002's four collective states at a point inside
//! each, every model resumed from a checkpoint with the bits of the uninterrupted run (random
//! noise, random activation order and conditions included), their parameters by dotted path, and
//! the errors of what they cannot take.

use flocking::metrics::FlockingCriteria;
use flocking::protocols::CollectiveState;
use flocking::serde_json::json;
use flocking::{DynSimulation, Scenario};

use crate::common::{assert_resumes_bit_for_bit, fixture};

/// The polarisation and milling averaged over the records of the last three quarters of `scenario`.
fn settled_order(scenario: &Scenario) -> (f64, f64) {
    let mut sim = DynSimulation::new(scenario).expect("a valid scenario");
    let steps = scenario.steps();
    let (mut p, mut m, mut count) = (0.0, 0.0, 0.0);
    for k in 1..=steps {
        sim.step();
        if k >= steps / 4 && k % scenario.record_every == 0 {
            let metrics = sim.metrics();
            p += metrics.polarisation;
            m += metrics.milling;
            count += 1.0;
        }
    }
    (p / count, m / count)
}

/// One point inside each of the paper's four states (Fig. 2, as the committed sweep
/// sweeps/couzin2002_zones.ron maps them with 3 seeds): the measured polarisation and angular
/// momentum put each in its state.
#[test]
fn couzin_shows_its_four_collective_states() {
    let base = fixture("couzin2002_torus_n100");
    for ((delta_r_o, delta_r_a), state) in [
        ((0.0, 14.0), CollectiveState::Swarm),
        ((1.0, 14.0), CollectiveState::Torus),
        ((4.0, 8.0), CollectiveState::DynamicParallel),
        ((8.0, 8.0), CollectiveState::HighlyParallel),
    ] {
        let scenario = base
            .with_values([
                ("algorithm.delta_r_o", json!(delta_r_o)),
                ("algorithm.delta_r_a", json!(delta_r_a)),
            ])
            .expect("valid zones");
        let (p, m) = settled_order(&scenario);
        assert_eq!(
            CollectiveState::of(p, m),
            state,
            "Δr_o = {delta_r_o}, Δr_a = {delta_r_a}: (p, m) = ({p}, {m})"
        );
    }
}

/// Vicsek's v_a for `agents` particles at noise `eta` and density 4 (the fixture's), as the
/// committed sweep measures it: the mean polarisation over the records after the first quarter
/// of 4,000 steps, averaged over seeds 1 to 4.
fn vicsek_va(agents: u64, eta: f64) -> f64 {
    let base = fixture("vicsek1995_fig2a_n400");
    let runs: Vec<f64> = (1..=4u64)
        .map(|seed| {
            let scenario = base
                .with_values([
                    ("agents", json!(agents)),
                    ("algorithm.eta", json!(eta)),
                    ("duration", json!(4000.0)),
                    ("seed", json!(seed)),
                ])
                .expect("a valid point of the sweep");
            settled_order(&scenario).0
        })
        .collect();
    runs.iter().sum::<f64>() / runs.len() as f64
}

/// Vicsek et al. 1995, Fig. 2(a): where v_a crosses ½, bracketed from both sides. The committed
/// sweep (sweeps/vicsek1995_fig2a.ron, 5 seeds) puts our crossings at η = 3.66 (N = 40) and
/// 3.48 (N = 100): v_a is above ½ at 0.25 below them and under ½ at 0.25 above. The paper's
/// points, read from the scan (sweeps/vicsek1995_fig2a.paper.csv), cross at 3.04 and 2.91, where
/// ours is still above ½ by more than 0.1: the gap docs/models.md documents, which any change
/// of the model that closed it would show here.
#[test]
fn vicsek_crosses_one_half_where_the_sweep_does_above_the_papers_crossing() {
    for (agents, ours, paper) in [(40, 3.66, 3.04), (100, 3.48, 2.91)] {
        let (below, above) = (
            vicsek_va(agents, ours - 0.25),
            vicsek_va(agents, ours + 0.25),
        );
        assert!(
            below > 0.5 && above < 0.5,
            "N = {agents}: v_a = {below} at η = {} and {above} at η = {}",
            ours - 0.25,
            ours + 0.25
        );
        let at_paper = vicsek_va(agents, paper);
        assert!(
            at_paper > 0.6,
            "N = {agents}: v_a = {at_paper} at the paper's crossing η = {paper}"
        );
    }
}

/// A run interrupted at a checkpoint and resumed records the bits of the uninterrupted run: the
/// models' noise, the boids' activation order and the conditions' draws are keyed by step.
#[test]
fn every_model_resumes_with_the_bits_of_the_whole_run() {
    let short = |name: &str, changes: &[(&str, flocking::serde_json::Value)]| {
        let scenario = fixture(name);
        let mut changes = changes.to_vec();
        changes.push(("duration", json!(40.0 * scenario.step)));
        changes.push(("record_every", json!(5)));
        scenario.with_values(changes).expect("valid")
    };
    let noisy = json!({"noise": {"White": {"sigma_q": 0.01, "sigma_p": 0.001}}});
    let lossy = json!({"delay": 2.0, "loss": {"Bernoulli": {"p": 0.2}}});
    let scenarios = [
        short("vicsek1995_fig2a_n400", &[]),
        short(
            "vicsek1995_fig2a_n400",
            &[
                ("conditions.sensing", noisy),
                ("conditions.communication", lossy),
            ],
        ),
        short("boids_small_n200", &[]),
        short(
            "couzin2002_torus_n100",
            &[("conditions.faults", json!({"rate": 0.05}))],
        ),
        short("cucker_smale2007_n50", &[]),
        short(
            "vasarhelyi2018_n30",
            &[("conditions.communication", json!({"delay": 0.05}))],
        ),
    ];
    for scenario in &scenarios {
        assert_resumes_bit_for_bit(scenario, 15);
    }
}

/// What a model cannot take is refused with its field: an acceleration condition for a model
/// that sets velocities, a 3D Vicsek run, a box smaller than twice the range, obstacles or a
/// γ-agent on a torus, perception conditions for the all-pairs Cucker–Smale model.
#[test]
fn models_refuse_what_they_cannot_take_naming_the_field() {
    let refused = |name: &str, changes: Vec<(&str, flocking::serde_json::Value)>| {
        let error = fixture(name).with_values(changes).expect_err("refused");
        error.field().unwrap_or_default()
    };
    assert_eq!(
        refused(
            "boids_small_n200",
            vec![("conditions.actuation.max_acceleration", json!(1.0))]
        ),
        "conditions.actuation"
    );
    assert_eq!(
        refused(
            "vicsek1995_fig2a_n400",
            vec![("conditions.disturbance.process_noise", json!(0.1))]
        ),
        "conditions.disturbance"
    );
    assert_eq!(
        refused("vicsek1995_fig2a_n400", vec![("algorithm.eta", json!(7.0))]),
        "algorithm.eta"
    );
    assert_eq!(
        refused(
            "vicsek1995_fig2a_n400",
            vec![("domain", json!({"PeriodicAtDensity": {"density": 500.0}}))]
        ),
        "domain.density"
    );
    assert_eq!(
        refused(
            "boids_small_n200",
            vec![("domain", json!({"Periodic": {"size": [100.0, 10.0]}}))]
        ),
        "domain.size[1]"
    );
    assert_eq!(
        refused(
            "cucker_smale2007_n50",
            vec![("conditions.communication.delay", json!(0.1))]
        ),
        "conditions.communication"
    );
    assert_eq!(
        refused(
            "tac2006_fig11_alg2_n100",
            vec![("domain", json!({"Periodic": {"size": [500.0, 500.0]}}))]
        ),
        "domain"
    );
    let three_d = Scenario::parse(
        "Scenario(dim: 3, agents: 10, algorithm: Vicsek(eta: 1.0), \
         initial: (positions: Box(min: [0.0, 0.0, 0.0], max: [5.0, 5.0, 5.0])), duration: 10.0, step: 1.0)",
        "vicsek3d.ron",
    )
    .expect_err("planar");
    assert_eq!(three_d.field().as_deref(), Some("algorithm.dim"));
}

/// A model's parameters are reachable by dotted path, with their defaults.
#[test]
fn model_parameters_by_path() {
    let boids = fixture("boids_small_n200");
    assert_eq!(
        boids.value("algorithm.cohere_factor").ok(),
        Some(json!(0.03))
    );
    let wider = boids
        .with_values([("algorithm.visual_distance", json!(7.5))])
        .expect("valid");
    assert_eq!(wider.range(), 7.5 + 2.0);
    let couzin = fixture("couzin2002_torus_n100");
    assert_eq!(
        couzin.value("algorithm.field_of_perception").ok(),
        Some(json!(270.0))
    );
    assert_eq!(couzin.range(), 16.0);
}

/// The steady-state order parameters of Vásárhelyi et al. (2018) over a run of `scenario`: the
/// means of φ^corr and φ^vel / v^flock, the largest φ^coll and φ^wall, and the least distance,
/// over the records from `from` seconds on.
fn vasarhelyi_order(scenario: &Scenario, from: f64) -> [f64; 5] {
    let mut sim = DynSimulation::new(scenario).expect("a valid scenario");
    let (mut corr, mut speed, mut coll, mut wall) = (0.0, 0.0, 0.0_f64, 0.0_f64);
    let (mut least, mut count) = (f64::INFINITY, 0.0);
    for k in 1..=scenario.steps() {
        sim.step();
        if sim.time() >= from && k % scenario.record_every == 0 {
            let observed = sim.observe();
            let value = |name: &str| {
                observed
                    .diagnostics
                    .iter()
                    .find(|(column, _)| *column == name)
                    .map(|(_, v)| *v)
                    .unwrap_or_else(|| panic!("no {name} column"))
            };
            corr += value("velocity_correlation");
            speed += value("speed_ratio");
            coll = coll.max(value("collision_ratio"));
            wall = wall.max(value("wall_violation"));
            least = least.min(observed.metrics.min_distance);
            count += 1.0;
        }
    }
    [corr / count, speed / count, coll, wall, least]
}

/// The reproduction of Vásárhelyi et al. (2018): the fixture's 30 drones (v^flock = 6 m/s, the
/// optimised parameters, a 250 m square) over 600 s, measured from t = 150 s as the paper's
/// steady state. Its fitness asks for φ^corr near 1, φ^vel near v^flock, no collision and no
/// wall violation; measured (docs/models.md) φ^corr = 0.982, φ^vel / v^flock = 0.924, φ^coll = 0,
/// φ^wall = 0, least distance 9.7 m > r^coll = 3 m. (≈ 2 s in debug: not ignored.)
#[test]
fn vasarhelyi_thirty_drones_flock_in_their_arena() {
    let scenario = fixture("vasarhelyi2018_n30");
    let [corr, speed, coll, wall, least] = vasarhelyi_order(&scenario, 150.0);
    eprintln!(
        "φ^corr {corr:.4}, φ^vel/v^flock {speed:.4}, max φ^coll {coll}, max φ^wall {wall}, least distance {least:.3}"
    );
    assert!(corr > 0.95, "φ^corr = {corr}");
    assert!((0.85..1.0).contains(&speed), "φ^vel / v^flock = {speed}");
    assert_eq!(coll, 0.0);
    assert_eq!(wall, 0.0);
    assert!(least > 3.0, "least distance {least}");
}

/// The model's arena lives in open space, its centre has `dim` coordinates, and its parameters
/// are checked by name.
#[test]
fn vasarhelyi_refuses_a_torus_a_bad_centre_and_bad_parameters() {
    let base = fixture("vasarhelyi2018_n30");
    let field = |changes: Vec<(&str, flocking::serde_json::Value)>| {
        base.with_values(changes)
            .expect_err("refused")
            .field()
            .unwrap_or_default()
    };
    assert_eq!(
        field(vec![(
            "domain",
            json!({"Periodic": {"size": [400.0, 400.0]}})
        )]),
        "domain"
    );
    assert_eq!(
        field(vec![("algorithm.arena_centre", json!([0.0, 0.0, 0.0]))]),
        "algorithm.arena_centre"
    );
    assert_eq!(field(vec![("algorithm.tau", json!(0.0))]), "algorithm.tau");
    assert_eq!(
        field(vec![("algorithm.r_coll", json!(200.0))]),
        "algorithm.r_coll"
    );
    // the defaults: the optimised set, the collision distance r^coll, the range r_c
    let resolved = base.resolved();
    assert_eq!(resolved.collision_distance, Some(3.0));
    assert_eq!(resolved.range(), 100.0);
}

/// Issue 49: one agent on a torus was judged "α-flocking … no, strict: yes" and showed a milling
/// up to 0.996 (one Vicsek particle 0.68): the circular mean of a single agent sat a round-off
/// away from it, and the agent seemed to circle it. One agent never mills, its cohesion radius is
/// 0, and a group of one gets no verdict, whatever the model.
#[test]
fn issue_49_one_agent_on_a_torus_neither_mills_nor_is_judged() {
    let torus = json!({"Periodic": {"size": [60.0, 60.0]}});
    for (name, changes) in [
        (
            "tac2006_fig12_alg1_n40",
            vec![
                ("agents", json!(1)),
                ("domain", torus.clone()),
                (
                    "initial",
                    json!({"positions": {"Box": {"min": [0.0, 0.0], "max": [60.0, 60.0]}},
                           "velocities": {"Box": {"min": [-2.0, -2.0], "max": [2.0, 2.0]}}}),
                ),
                ("duration", json!(20.0)),
            ],
        ),
        (
            "vicsek1995_fig2a_n400",
            vec![
                ("agents", json!(1)),
                ("domain", json!({"Periodic": {"size": [7.0, 7.0]}})),
                ("duration", json!(200.0)),
            ],
        ),
    ] {
        let scenario = fixture(name).with_values(changes).expect("valid");
        let summary = flocking::run(&scenario, &mut ()).expect("runs");
        assert!(summary.history.len() > 10);
        for (t, m) in &summary.history {
            assert_eq!(
                (m.milling, m.cohesion_radius),
                (0.0, 0.0),
                "{name} at t = {t}"
            );
            assert!((m.polarisation - 1.0).abs() < 1e-12, "{name} at t = {t}");
        }
        let verdict = summary
            .verdict(&FlockingCriteria::default())
            .expect("records");
        assert_eq!(verdict.state(), "undefined", "{name}: {verdict}");
        assert!(verdict.to_string().contains("undefined"), "{verdict}");
    }
}

/// Issue 50: the classic models were judged by TAC 2006 Definition 5 — a lattice at d and
/// collisions at d/4 they do not have. Each fixture is judged by its own states: Vicsek's ordered
/// phase at η = 2 (its Fig. 2(a)), Couzin's torus, the boids' disorder at the benchmark's small
/// visual distance, Cucker–Smale's convergence of velocities (β = 0.25 < ½, unconditional),
/// Vásárhelyi's flock; none gets an α-flocking answer.
#[test]
fn issue_50_each_classic_model_is_judged_by_its_own_states() {
    for (name, state) in [
        ("vicsek1995_fig2a_n400", "polarised (ordered)"),
        ("couzin2002_torus_n100", "torus"),
        ("boids_small_n200", "swarm (disordered)"),
        ("cucker_smale2007_n50", "flocking"),
        ("vasarhelyi2018_n30", "flocking"),
    ] {
        let summary = flocking::run(&fixture(name), &mut ()).expect("runs");
        let verdict = summary
            .verdict(&FlockingCriteria::default())
            .expect("records");
        assert_eq!(verdict.state(), state, "{name}: {verdict}");
        assert_eq!(verdict.alpha_flock(), None, "{name}");
        assert!(!verdict.to_string().contains("α-flocking"), "{verdict}");
    }
}

/// Issue 51: each model's scenario variant holds the model's own parameter struct, and reads and
/// writes as the struct variant users have always written (`Vicsek(eta: 2.0)`, `Vasarhelyi()`),
/// its defaults those of the struct; RON errors keep the variant, the field, the line and the
/// column; the JSON form of sweeps and Python keeps its shape.
#[test]
fn models_read_and_write_as_struct_variants_holding_their_params() {
    use flocking::Algorithm;
    use flocking::protocols::{
        BoidsParams, CouzinParams, CuckerSmaleParams, VasarhelyiParams, VicsekParams,
    };
    let scenario = |algorithm: &str| {
        format!(
            "Scenario(dim: 2, agents: 10, algorithm: {algorithm}, initial: (positions: Box(min: [-5.0, -5.0], max: [5.0, 5.0])), duration: 1.0)"
        )
    };
    let cases = [
        (
            "Vicsek(eta: 2.0)",
            Algorithm::Vicsek(VicsekParams::with_eta(2.0)),
            "    algorithm: Vicsek(\n        v0: 0.03,\n        r: 1.0,\n        eta: 2.0,\n    ),\n",
        ),
        (
            "CuckerSmale(beta: 0.25)",
            Algorithm::CuckerSmale(CuckerSmaleParams::with_beta(0.25)),
            "    algorithm: CuckerSmale(\n        lambda: 1.0,\n        k: 1.0,\n        sigma: 1.0,\n        beta: 0.25,\n    ),\n",
        ),
        (
            "Boids()",
            Algorithm::Boids(BoidsParams::default()),
            "        visual_distance: 5.0,\n    ),\n",
        ),
        (
            "Couzin(delta_r_o: 2.0, delta_r_a: 12.0)",
            Algorithm::Couzin(CouzinParams::default()),
            "        blend: Unit,\n        blind_cone: Everywhere,\n    ),\n",
        ),
        (
            "Vasarhelyi()",
            Algorithm::Vasarhelyi(VasarhelyiParams::default()),
            "        arena_shape: Square,\n        arena_side: 250.0,\n    ),\n",
        ),
    ];
    for (written, algorithm, ron) in cases {
        let read: Scenario = scenario(written).parse().expect(written);
        assert_eq!(read.algorithm, algorithm, "{written}");
        let text = read.to_ron().expect("written");
        assert!(text.contains(ron), "{written} is written\n{text}");
        assert_eq!(text.parse::<Scenario>().expect("read back"), read);
        let json = read.value("algorithm").expect("the algorithm");
        let name = written.split('(').next().unwrap_or_default();
        assert!(json.get(name).is_some_and(|v| v.is_object()), "{json}");
        let changed = read
            .with_values([("algorithm", json)])
            .expect("the JSON form");
        assert_eq!(changed.algorithm, read.algorithm);
    }
    let error = |algorithm: &str| {
        scenario(algorithm)
            .parse::<Scenario>()
            .expect_err("refused")
            .to_string()
    };
    assert_eq!(
        error("Vicsek()"),
        "<string>:1:48: Unexpected missing field named `eta` in `Vicsek`"
    );
    assert_eq!(
        error("Vicsek(eta: 2.0, foo: 1.0)"),
        "<string>:1:58: Unexpected field named `foo` in `Vicsek`, expected one of `v0`, `r`, or `eta` instead"
    );
    assert_eq!(
        error("Vicsek(eta: \"x\")"),
        "<string>:1:53: `algorithm.eta` = \"x\": expected a number, e.g. `eta: 1.0`"
    );
    assert!(
        error("Vasarhelyi(arena_side: -1.0)")
            .starts_with("<string>:1:52: `algorithm.arena_side` = -1.0")
    );
    // the form of a vehicle's parameters (`Quadrotor((…))`) is not a model's
    assert_eq!(
        error("Vicsek((eta: 2.0))"),
        "<string>:1:48: Expected identifier (in the value of `algorithm`)"
    );
}
