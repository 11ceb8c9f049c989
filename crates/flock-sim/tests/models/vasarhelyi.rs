//! Vásárhelyi et al. 2018 against its terms written out again, and its walls and limits.

use super::*;

/// D(r, a, p) written out again: 0, r p below a/p, √(2 a r − a²/p²) beyond.
fn vas_braking(r: f64, a: f64, p: f64) -> f64 {
    if r <= 0.0 {
        0.0
    } else if r * p < a / p {
        r * p
    } else {
        (2.0 * a * r - (a / p) * (a / p)).sqrt()
    }
}

/// The model's acceleration of every agent, brute force over all pairs: robotsim's terms
/// summed, cut at v^max, relaxed over τ and cut at a^max; the arena a square (cube) about `centre`.
fn vasarhelyi_inputs<V: Vector>(
    q: &[V],
    p: &[V],
    c: &VasarhelyiParams,
    centre: V,
    side: f64,
) -> Vec<V> {
    let n = q.len();
    let shorten = |x: V, limit: f64| {
        if x.length() > limit {
            x * (limit / x.length())
        } else {
            x
        }
    };
    (0..n)
        .map(|i| {
            let mut desired = p[i].normalize_or_zero() * c.v_flock;
            for j in 0..n {
                let r = (q[i] - q[j]).length();
                if j == i || r >= c.r_c {
                    continue;
                }
                if r < c.r0_rep {
                    desired += (q[i] - q[j]) * (1.0 / r) * (c.p_rep * (c.r0_rep - r));
                }
                let v_ij = (p[i] - p[j]).length();
                // the stopping point of robotsim's FrictionLinSqrt: R_0 + R_0_Offset_Frict
                let stop = c.r0_rep + c.r0_frict;
                let allowed = vas_braking(r - stop, c.a_frict, c.p_frict).max(c.v_frict);
                if v_ij > allowed {
                    desired += (p[j] - p[i]) * (1.0 / v_ij) * (c.c_frict * (v_ij - allowed));
                }
            }
            for k in 0..V::DIM {
                let x = q[i].coord(k) - centre.coord(k);
                let inwards = V::from_fn(|m| if m == k { -x.signum() } else { 0.0 });
                let to_wall = side / 2.0 - x.abs();
                let dv = inwards * c.v_shill - p[i];
                let allowed = vas_braking(to_wall - c.r0_shill, c.a_shill, c.p_shill);
                if dv.length() > allowed {
                    desired += dv * ((dv.length() - allowed) / dv.length());
                }
            }
            shorten((shorten(desired, c.v_max) - p[i]) * (1.0 / c.tau), c.a_max)
        })
        .collect()
}

/// A swarm of 40 at up to 8 m/s spread over 260 m about `centre`, in an arena of side 200: pairs
/// within r_0^rep, within and beyond r_c, agents outside the arena on every side.
fn vasarhelyi_agrees<V: Vector>() {
    let centre = V::from_fn(|k| 10.0 * (k as f64 + 1.0));
    let mut swarm = random_swarm::<V>(40, 130.0, 8.0, 23);
    for q in &mut swarm.positions {
        *q += centre;
    }
    let params = VasarhelyiParams::default();
    let arena = Arena {
        shape: ArenaShape::Square,
        centre,
        side: 200.0,
    };
    let model = vasarhelyi_in(params.clone(), arena);
    let h = 0.01;
    let reference = |_, q: &[V], p: &[V]| {
        let u = vasarhelyi_inputs(q, p, &params, centre, 200.0);
        let p2: Vec<V> = p.iter().zip(&u).map(|(&v, &a)| v + a * h).collect();
        let q2 = q.iter().zip(&p2).map(|(&x, &v)| x + v * h).collect();
        (q2, p2)
    };
    agrees_with_reference(model, swarm, (h, None, 50), reference, (1e-9, 1e-10));
}

#[test]
fn vasarhelyi_equals_brute_force_2d_3d() {
    vasarhelyi_agrees::<DVec2>();
    vasarhelyi_agrees::<DVec3>();
}

/// The braking curve at three points by hand (a = 4.16 m s⁻², p = 3.2 s⁻¹, the alignment's):
/// 0 before the stopping point, the linear branch r p = 0.8 at r = 0.25 (below a/p = 1.3) and
/// the square-root branch √(2 · 4.16 · 10 − 1.3²) = √81.51 at r = 10.
#[test]
fn vasarhelyi_braking_curve_at_hand_values() {
    use flock_protocols::vasarhelyi2018::braking_curve;
    assert_eq!(braking_curve(-1.0, 4.16, 3.2), 0.0);
    assert_abs_diff_eq!(braking_curve(0.25, 4.16, 3.2), 0.8, epsilon = 1e-15);
    assert_abs_diff_eq!(
        braking_curve(10.0, 4.16, 3.2),
        9.028_288_874_421_332,
        epsilon = 1e-12
    );
}

/// The model with `params` in `arena`.
fn vasarhelyi_in<V: Vector>(params: VasarhelyiParams, arena: Arena<V>) -> Vasarhelyi<V> {
    Vasarhelyi::new(VasarhelyiParams {
        arena_shape: arena.shape,
        arena_side: arena.side,
        arena_centre: Some((0..V::DIM).map(|k| arena.centre.coord(k)).collect()),
        ..params
    })
    .unwrap()
}

/// The default model in a 10 km arena (walls out of reach).
fn far_walls<V: Vector>() -> Vasarhelyi<V> {
    let arena = Arena {
        shape: ArenaShape::Square,
        centre: V::ZERO,
        side: 10_000.0,
    };
    vasarhelyi_in(VasarhelyiParams::default(), arena)
}

/// Two drones 10 m apart flying side by side at v^flock (no velocity difference, so no
/// alignment): each is pushed straight away from the other at p^rep (r_0^rep − r) =
/// 0.13 · 15 = 1.95 m/s, desired (∓1.95, 6) below v^max, so u = ∓(1.95, 0)/τ.
#[test]
fn vasarhelyi_repulsion_pushes_a_close_pair_apart() {
    let model = far_walls::<DVec2>();
    let v = DVec2::new(0.0, 6.0);
    let (a, b) = (DVec2::ZERO, DVec2::new(10.0, 0.0));
    let desired = model.desired_velocity(a, v, [(b, v)].into_iter());
    assert_abs_diff_eq!(desired, DVec2::new(-1.95, 6.0), epsilon = 1e-12);
    let swarm = Swarm::new(vec![a, b], vec![v, v]);
    let mut sim = Simulation::new(model, Integrator::SymplecticEuler, swarm, 0.01).unwrap();
    sim.step();
    let p = &sim.swarm().velocities;
    assert_abs_diff_eq!(p[0], v + DVec2::new(-1.95, 0.0) * 0.01, epsilon = 1e-12);
    assert_abs_diff_eq!(p[1], v + DVec2::new(1.95, 0.0) * 0.01, epsilon = 1e-12);
    // beyond r_0^rep and with equal velocities: self-propulsion alone
    let alone = model_far_desired(DVec2::new(30.0, 0.0), v);
    assert_abs_diff_eq!(alone, v, epsilon = 1e-12);
}

fn model_far_desired(b: DVec2, v: DVec2) -> DVec2 {
    far_walls::<DVec2>().desired_velocity(DVec2::ZERO, v, [(b, v)].into_iter())
}

/// The shill agents of a 250 m square: a drone at rest 5 m outside the right wall gets the
/// whole shill velocity (−13.6, 0) (D = 0 outside); one 5 m inside flying at the wall at 6 m/s
/// gets (19.6 − D(4.7, a^shill, p^shill)) along −x, D = √(2 · 3.02 · 4.7 − (3.02/3.55)²); one
/// at the centre gets nothing. A circle pushes back along the radius.
#[test]
fn vasarhelyi_walls_push_back_outside_and_brake_inside() {
    let square = Arena {
        shape: ArenaShape::Square,
        centre: DVec2::ZERO,
        side: 250.0,
    };
    let model = vasarhelyi_in(VasarhelyiParams::default(), square);
    let outside = model.wall_term(DVec2::new(130.0, 0.0), DVec2::ZERO);
    assert_abs_diff_eq!(outside, DVec2::new(-13.6, 0.0), epsilon = 1e-12);
    assert_eq!(square.outside(DVec2::new(130.0, 0.0)), 5.0);
    let inside = model.wall_term(DVec2::new(120.0, 0.0), DVec2::new(6.0, 0.0));
    let braking = 5.259_686_523_070_369;
    assert_abs_diff_eq!(inside, DVec2::new(-(19.6 - braking), 0.0), epsilon = 1e-9);
    assert_eq!(square.outside(DVec2::new(120.0, 0.0)), 0.0);
    assert_eq!(
        model.wall_term(DVec2::ZERO, DVec2::new(6.0, 0.0)),
        DVec2::ZERO
    );
    let circle = Arena {
        shape: ArenaShape::Circle,
        ..square
    };
    let model = vasarhelyi_in(VasarhelyiParams::default(), circle);
    let q = DVec2::new(100.0, 100.0); // 141.4 m out, 16.4 m beyond the wall
    let w = model.wall_term(q, DVec2::ZERO);
    assert_abs_diff_eq!(w, -q.normalize() * 13.6, epsilon = 1e-12);
    assert_abs_diff_eq!(circle.outside(q), q.length() - 125.0, epsilon = 1e-12);
}

/// The cut: a desired velocity beyond v^max keeps its direction at length v^max, and the
/// acceleration is cut at a^max. A drone at rest 5 m outside the left wall with two others 1 m
/// further out (repulsion 2 · 0.13 · 24 = 6.24 m/s inwards) plus the wall (13.6 m/s inwards):
/// ‖ṽ‖ = 19.84 > 8.
#[test]
fn vasarhelyi_cuts_the_desired_velocity_and_the_acceleration() {
    let arena = Arena {
        shape: ArenaShape::Square,
        centre: DVec2::ZERO,
        side: 100.0,
    };
    let model = vasarhelyi_in(VasarhelyiParams::default(), arena);
    let q = DVec2::new(-55.0, 0.0);
    let others = [
        (DVec2::new(-56.0, 0.0), DVec2::ZERO),
        (DVec2::new(-56.0, 0.0), DVec2::ZERO),
    ];
    let desired = model.desired_velocity(q, DVec2::ZERO, others.into_iter());
    assert_abs_diff_eq!(desired.length(), 8.0, epsilon = 1e-12);
    assert_abs_diff_eq!(desired.normalize(), DVec2::new(1.0, 0.0), epsilon = 1e-12);
    let swarm = Swarm::new(vec![q], vec![DVec2::ZERO]);
    let mut sim = Simulation::new(model, Integrator::SymplecticEuler, swarm, 0.01).unwrap();
    sim.step();
    // alone: u = (v_d − 0)/τ = 8 m s⁻² (13.6 cut at v^max), cut at a^max = 6
    assert_abs_diff_eq!(
        sim.swarm().velocities[0],
        DVec2::new(0.06, 0.0),
        epsilon = 1e-12
    );
}

/// The order parameters of a constructed state: φ^corr over all pairs (two heading +x, one +y:
/// (1 + 0 + 0) · 2 / 6 = 1/3), φ^vel / v^flock, φ^coll (one pair within r^coll of three: 2/6)
/// and φ^wall (one drone 10 m out of three: 10/3).
#[test]
fn vasarhelyi_order_parameters_of_a_constructed_state() {
    use flock_graph::{NeighbourSearch, ProximityNet};
    let arena = Arena {
        shape: ArenaShape::Square,
        centre: DVec2::ZERO,
        side: 100.0,
    };
    let model = vasarhelyi_in(VasarhelyiParams::default(), arena);
    let q = vec![DVec2::ZERO, DVec2::new(2.0, 0.0), DVec2::new(60.0, 0.0)];
    let p = vec![
        DVec2::new(6.0, 0.0),
        DVec2::new(3.0, 0.0),
        DVec2::new(0.0, 3.0),
    ];
    let swarm = Swarm::new(q.clone(), p);
    let mut net = ProximityNet::new();
    NeighbourSearch::new().build(&q, model.interaction_range(), &mut net);
    let [corr, speed, coll, wall] = model.order_parameters(&swarm, &net);
    assert_abs_diff_eq!(corr, 1.0 / 3.0, epsilon = 1e-15);
    assert_abs_diff_eq!(speed, 12.0 / 3.0 / 6.0, epsilon = 1e-15);
    assert_abs_diff_eq!(coll, 1.0 / 3.0, epsilon = 1e-15);
    assert_abs_diff_eq!(wall, 10.0 / 3.0, epsilon = 1e-12);
}

/// The paper's flock in the small (the reproduction at full length runs the fixture in the
/// `flocking` crate's tests): 30 drones from random headings in a 250 m square align within a
/// minute of simulated time: φ^corr > 0.9, speed within 20 % of v^flock, none outside.
#[test]
fn vasarhelyi_thirty_drones_align_within_a_minute() {
    let arena = Arena {
        shape: ArenaShape::Square,
        centre: DVec2::ZERO,
        side: 250.0,
    };
    let model = vasarhelyi_in(VasarhelyiParams::default(), arena);
    let mut swarm = random_swarm::<DVec2>(30, 50.0, 6.0, 5);
    for v in &mut swarm.velocities {
        *v = v.normalize() * 6.0;
    }
    let mut sim = Simulation::new(model, Integrator::SymplecticEuler, swarm, 0.01).unwrap();
    for _ in 0..6000 {
        sim.step();
    }
    let diagnostics: std::collections::BTreeMap<_, _> = sim.diagnostics().into_iter().collect();
    assert!(diagnostics["velocity_correlation"] > 0.9, "{diagnostics:?}");
    assert!(
        (diagnostics["speed_ratio"] - 1.0).abs() < 0.2,
        "{diagnostics:?}"
    );
    assert_eq!(diagnostics["wall_violation"], 0.0, "{diagnostics:?}");
    assert_eq!(diagnostics["collision_ratio"], 0.0, "{diagnostics:?}");
}
