//! The boids of the ABM frameworks' benchmark against their declared sequential rule.

use super::*;

/// One boids step as the ABM frameworks' declaration writes it, in the activation order given.
fn boids_step<V: Vector>(
    q: &mut [V],
    heading: &mut [V],
    order: &[u32],
    b: BoidsParams,
    h: f64,
    side: Option<f64>,
) {
    for &i in order {
        let i = i as usize;
        let (mut n, mut cohere, mut separate, mut matching) = (0, V::ZERO, V::ZERO, V::ZERO);
        for j in 0..q.len() {
            if j == i {
                continue;
            }
            let d = offset(q[i], q[j], side);
            if d.length() <= b.visual_distance {
                n += 1;
                cohere += d;
                if d.length() < b.separation {
                    separate -= d;
                }
                matching += heading[j];
            }
        }
        let n = f64::from(n.max(1));
        let v = (heading[i]
            + cohere * (b.cohere_factor / n)
            + separate * (b.separate_factor / n)
            + matching * (b.match_factor / n))
            * 0.5;
        heading[i] = v / v.length();
        q[i] = wrapped(q[i] + heading[i] * (b.speed * h), side);
    }
}

fn boids_agree<V: Vector>(side: Option<f64>) {
    let b = BoidsParams {
        visual_distance: 3.0,
        separation: 1.5,
        ..BoidsParams::default()
    };
    let n = 150;
    let mut swarm = near_the_wrap::<V>(n, 20.0, 1.0, 5);
    for p in &mut swarm.velocities {
        *p = p.normalize_or_zero() * b.speed;
    }
    let h = 0.5;
    let model = Boids::new(b, h, 4, domain(side)).unwrap();
    let orders: Vec<Vec<u32>> = (0..10)
        .map(|k| model.activation_order(f64::from(k) * h, n))
        .collect();
    // the declared rule keeps unit headings: the reference steps them and moves at the speed
    let reference = |k: u64, q: &[V], p: &[V]| {
        let (mut q, mut heading) = (
            q.to_vec(),
            p.iter().map(|&p| p / b.speed).collect::<Vec<V>>(),
        );
        boids_step(&mut q, &mut heading, &orders[k as usize], b, h, side);
        (q, heading.into_iter().map(|v| v * b.speed).collect())
    };
    agrees_with_reference(model, swarm, (h, side, 10), reference, (1e-9, 1e-12));
}

#[test]
fn boids_equal_the_declared_sequential_rule_2d_3d_open_and_periodic() {
    boids_agree::<DVec2>(Some(20.0));
    boids_agree::<DVec3>(Some(20.0));
    boids_agree::<DVec2>(None);
    boids_agree::<DVec3>(None);
}

/// On a torus the boids step without the net (their sweep searches its own cells): what the
/// simulation measures between steps is still of the net of the current state, and a step
/// after a measurement has the bits of one without.
#[test]
fn boids_measure_the_net_of_the_current_state() {
    let b = BoidsParams::default();
    let (n, side, h) = (200, 60.0, 1.0);
    let swarm = near_the_wrap::<DVec2>(n, side, b.speed, 3);
    let model = Boids::new(b, h, 2, domain(Some(side))).unwrap();
    let range = model.interaction_range();
    let new = |model| {
        Simulation::new(model, Integrator::SymplecticEuler, swarm.clone(), h)
            .unwrap()
            .with_domain(domain(Some(side)))
            .unwrap()
    };
    let (mut measured, mut unmeasured) = (new(model.clone()), new(model));
    let params = flock_metrics::MetricParams {
        d: 5.0,
        collision_distance: 1.0,
    };
    for _ in 0..5 {
        measured.step();
        unmeasured.step();
        let mut net = flock_graph::ProximityNet::without_distances();
        let now = measured.swarm();
        let torus = domain(Some(side));
        flock_graph::NeighbourSearch::new().build_in(&torus, &now.positions, range, &mut net);
        assert!(net.graph().directed_edge_count() > 0);
        assert_eq!(*measured.graph(), *net.graph());
        let (q, p) = (&now.positions, &now.velocities);
        let metrics = flock_metrics::FlockMetrics::measure_in(&torus, q, p, &net, &params);
        assert_eq!(measured.observe(&params).metrics, metrics);
        assert_eq!(measured.metrics(&params), metrics);
    }
    assert_eq!(measured.swarm(), unmeasured.swarm());
}

#[test]
fn boids_order_is_a_permutation_drawn_anew_each_step() {
    let model = Boids::<DVec2>::new(BoidsParams::default(), 1.0, 1, Domain::Open).unwrap();
    let a = model.activation_order(0.0, 1000);
    let b = model.activation_order(1.0, 1000);
    let mut sorted = a.clone();
    sorted.sort_unstable();
    assert_eq!(sorted, (0..1000).collect::<Vec<u32>>());
    assert_ne!(a, b);
    assert_eq!(a, model.activation_order(0.0, 1000));
}
