//! CDS 03-006 (seed 004) Fig. 7–8 with the report's own translational controller: n = 100 agents,
//! (α, α, 2), β/γ-agents on the six balls of eq. 59 (eq. 54–58) and the *centralised* bounded
//! velocity tracking u^tr = −c₂ φ(p̄ − p_d) of eq. 66 — no pull towards a moving point, which the
//! report does not have.
//!
//! `cargo run --release -p flock-sim --example six_balls_2003 -- [key=value …]`
//!
//! Keys (defaults): `c2=2` (gain of eq. 66), `c3=30`, `c4=1`, `lambda=1` (eq. 54, our values as in
//! `fixtures/tr2003_fig7_obstacles_n100.ron`), `consensus=1` (c₁ of eq. 35), `speed=10` (‖p_d‖,
//! p_d along +x — see the fixture for why not (0, 10)), `duration=60`, `seed=7`, `every=10` (steps
//! between records), `print=1` (seconds between printed records), `xmin=-150`, `xmax=-60`,
//! `ymin=0`, `ymax=40` (the initial box), `lattice=0` (1: start from a 10 × 10 triangular
//! α-lattice patch in the middle of the box instead of the random box).
//!
//! The initial state is the fixture's: positions uniform in the box [xmin, xmax] × [ymin, ymax]
//! drawn from the PCG64 stream of `seed` as `flocking run` draws them, at rest. Every record measures the TAC 2006
//! metrics, the pairs closer than d/4 (collisions), the agents inside a ball, and H_s, H_tr.

use flock_metrics::{FlockMetrics, MetricParams};
use flock_protocols::{
    AlphaAlpha, AlphaAlphaForm, AlphaAlphaParams, BallObstacle, CentralisedTracking2003,
    ObstacleParams, Swarm, TranslationalController,
};
use flock_sim::{Integrator, Simulation};
use glam::DVec2;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

/// M_obs of eq. 59: centres (b_x, b_y) and radii l.
const BALLS: [(f64, f64, f64); 6] = [
    (100.0, 20.0, 10.0),
    (120.0, 40.0, 2.0),
    (150.0, 40.0, 5.0),
    (160.0, 0.0, 3.0),
    (200.0, -5.0, 20.0),
    (200.0, 50.0, 20.0),
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut options = [
        ("c2", 2.0),
        ("c3", 30.0),
        ("c4", 1.0),
        ("lambda", 1.0),
        ("consensus", 1.0),
        ("speed", 10.0),
        ("duration", 60.0),
        ("seed", 7.0),
        ("every", 10.0),
        ("print", 1.0),
        ("xmin", -150.0),
        ("xmax", -60.0),
        ("ymin", 0.0),
        ("ymax", 40.0),
        ("lattice", 0.0),
    ];
    for arg in std::env::args().skip(1) {
        let (key, value) = arg.split_once('=').ok_or(format!("not key=value: {arg}"))?;
        let slot = options
            .iter_mut()
            .find(|(k, _)| *k == key)
            .ok_or(format!("unknown key {key}"))?;
        slot.1 = value.parse()?;
    }
    let get = |key: &str| options.iter().find(|(k, _)| *k == key).map_or(0.0, |o| o.1);

    let params = AlphaAlphaParams::default(); // d_α = 7, r = 1.2 d_α, a = 1, b = 5
    let alpha = AlphaAlpha::new(params, AlphaAlphaForm::Smooth, get("consensus"));
    let obstacles = BALLS
        .iter()
        .map(|&(x, y, l)| BallObstacle::new(DVec2::new(x, y), l))
        .collect::<Result<Vec<_>, _>>()?;
    let obstacle_params = ObstacleParams {
        c3: get("c3"),
        c4: get("c4"),
        lambda_d: get("lambda"),
        ..ObstacleParams::for_alpha(&params)
    };
    let p_d = DVec2::new(get("speed"), 0.0);
    let protocol = CentralisedTracking2003::with_obstacles(
        alpha,
        obstacles.clone(),
        obstacle_params,
        TranslationalController::group_velocity(p_d, get("c2")),
    );

    // the fixture's start: Box(min: [xmin, ymin], max: [xmax, ymax]), zero velocities
    let mut rng = Pcg64::seed_from_u64(get("seed") as u64);
    let (min, max) = ([get("xmin"), get("ymin")], [get("xmax"), get("ymax")]);
    let positions: Vec<DVec2> = if get("lattice") > 0.0 {
        // a 10 × 10 triangular α-lattice patch (spacing d_α) centred in the box
        let centre = DVec2::new(min[0] + max[0], min[1] + max[1]) * 0.5;
        let d = params.d_alpha;
        (0..100)
            .map(|k| {
                let (row, col) = (f64::from(k / 10), f64::from(k % 10));
                let x = DVec2::new(d * (col + 0.5 * (row % 2.0)), d * row * 3f64.sqrt() / 2.0);
                centre + x - DVec2::new(4.75 * d, 4.5 * d * 3f64.sqrt() / 2.0)
            })
            .collect()
    } else {
        (0..100)
            .map(|_| {
                let mut x = [0.0; 2];
                for k in 0..2 {
                    x[k] = min[k] + (max[k] - min[k]) * rng.random::<f64>();
                }
                DVec2::from(x)
            })
            .collect()
    };
    let swarm = Swarm::new(positions, vec![DVec2::ZERO; 100]);
    let step = 0.01;
    let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, swarm, step)
        .expect("a valid simulation");

    let metric_params = MetricParams {
        d: params.d_alpha,
        collision_distance: 0.25 * params.d_alpha,
    };
    let steps = (get("duration") / step).round() as u64;
    let every = get("every") as u64;
    let print_every = (get("print") / step).round() as u64;
    let mut summary = Summary::default();
    println!(
        "t,C,C*,components,R,E~,K~,min_distance,collisions,clearance,inside,H_s,H_tr,p_bar_x,p_bar_y"
    );
    loop {
        let state = sim.swarm();
        let q = &state.positions;
        let m = sim.metrics(&metric_params);
        let clearance = q
            .iter()
            .map(|&x| {
                obstacles
                    .iter()
                    .map(|o| (x - o.centre()).length() - o.radius())
                    .fold(f64::INFINITY, f64::min)
            })
            .collect::<Vec<_>>();
        let inside = clearance.iter().filter(|&&c| c <= 0.0).count();
        let least_clearance = clearance.iter().copied().fold(f64::INFINITY, f64::min);
        let diagnostic = |name: &str| {
            let columns = sim.diagnostics();
            columns
                .iter()
                .find(|(n, _)| *n == name)
                .map_or(f64::NAN, |c| c.1)
        };
        let (h_s, h_tr) = (
            diagnostic("structural_energy"),
            diagnostic("translational_energy"),
        );
        let t = sim.time();
        summary.add(t, &m, inside, least_clearance);
        if sim.steps() % print_every == 0 || sim.steps() >= steps {
            let p_bar = state.mean_velocity();
            println!(
                "{t:.2},{:.4},{:.3},{},{:.2},{:.3e},{:.3e},{:.3},{},{:.3},{},{:.2},{:.3e},{:.3},{:.3}",
                m.connectivity,
                m.giant_component,
                m.components,
                m.cohesion_radius,
                m.deviation_energy,
                m.velocity_mismatch,
                m.min_distance,
                m.collisions,
                least_clearance,
                inside,
                h_s,
                h_tr,
                p_bar.x,
                p_bar.y
            );
        }
        if sim.steps() >= steps {
            break;
        }
        for _ in 0..every.min(steps - sim.steps()) {
            sim.step();
        }
    }
    summary.print();
    Ok(())
}

/// Extremes over every record.
#[derive(Debug)]
struct Summary {
    records: usize,
    colliding_records: usize,
    max_collisions: (usize, f64),
    min_distance: (f64, f64),
    min_distance_after_start: (f64, f64),
    max_inside: usize,
    min_clearance: f64,
    min_giant: (f64, f64),
    last: Option<FlockMetrics>,
}

impl Default for Summary {
    fn default() -> Self {
        Self {
            records: 0,
            colliding_records: 0,
            max_collisions: (0, 0.0),
            min_distance: (f64::INFINITY, 0.0),
            min_distance_after_start: (f64::INFINITY, 0.0),
            max_inside: 0,
            min_clearance: f64::INFINITY,
            min_giant: (f64::INFINITY, 0.0),
            last: None,
        }
    }
}

impl Summary {
    fn add(&mut self, t: f64, m: &FlockMetrics, inside: usize, clearance: f64) {
        self.records += 1;
        self.colliding_records += usize::from(m.collisions > 0);
        if m.collisions > self.max_collisions.0 {
            self.max_collisions = (m.collisions, t);
        }
        if m.min_distance < self.min_distance.0 {
            self.min_distance = (m.min_distance, t);
        }
        // after the random start has spread out (first second)
        if t >= 1.0 && m.min_distance < self.min_distance_after_start.0 {
            self.min_distance_after_start = (m.min_distance, t);
        }
        self.max_inside = self.max_inside.max(inside);
        self.min_clearance = self.min_clearance.min(clearance);
        // C* during the pass: once the flock has formed (t ≥ 10 s)
        if t >= 10.0 && m.giant_component < self.min_giant.0 {
            self.min_giant = (m.giant_component, t);
        }
        self.last = Some(*m);
    }

    fn print(&self) {
        eprintln!(
            "records {}: collisions (pairs < d/4) in {} records, at most {} (t = {:.2}); min distance {:.3} (t = {:.2}), {:.3} after t = 1 (t = {:.2}); agents inside balls at most {}, min clearance {:.3}; min C* after t = 10: {:.3} (t = {:.2})",
            self.records,
            self.colliding_records,
            self.max_collisions.0,
            self.max_collisions.1,
            self.min_distance.0,
            self.min_distance.1,
            self.min_distance_after_start.0,
            self.min_distance_after_start.1,
            self.max_inside,
            self.min_clearance,
            self.min_giant.0,
            self.min_giant.1
        );
        if let Some(m) = self.last {
            eprintln!(
                "final: C = {:.4}, C* = {:.3}, {} components, R = {:.2}, Ẽ = {:.3e}, K̃ = {:.3e}, min distance {:.3}, collisions {}",
                m.connectivity,
                m.giant_component,
                m.components,
                m.cohesion_radius,
                m.deviation_energy,
                m.velocity_mismatch,
                m.min_distance,
                m.collisions
            );
        }
    }
}
