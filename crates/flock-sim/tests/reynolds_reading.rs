//! ACC 2004 § 4 (seed 000): the (α, α) protocol read as Reynolds's three rules. The sign of the
//! local stress decides towards / away from the centre of neighbours with the magnitude of eq. 33,
//! neutral at d_α; the velocity-matching term is c_d |N_i| times Reynolds's alignment (eq. 17);
//! the two terms are the protocol's u_i; the regimes partition the agents.

use flock_graph::ProximityNet;
use flock_math::{Potential, Vector};
use flock_protocols::{
    AlphaAlpha, AlphaAlphaForm, AlphaAlphaParams, Flocking2003, Protocol, StressForm, StressRegime,
    Swarm,
};
use glam::{DVec2, DVec3};

use crate::common::{planar, random_swarm};

const FORMS: [AlphaAlphaForm; 3] = [
    AlphaAlphaForm::Nonsmooth,
    AlphaAlphaForm::Smooth,
    AlphaAlphaForm::Approximate,
];

/// ‖a − b‖ ≤ epsilon · (1 + ‖b‖).
#[track_caller]
fn assert_close<V: Vector>(a: V, b: V, epsilon: f64) {
    assert!(
        (a - b).length() <= epsilon * (1.0 + b.length()),
        "{a:?} vs {b:?} (relative tolerance {epsilon})"
    );
}

/// Agent 0 at `centre` and neighbours at distance `radius` in the plane at the angles (degrees),
/// at rest.
fn star<V: Vector>(centre: V, radius: f64, angles: &[f64]) -> Swarm<V> {
    let mut q = vec![centre];
    q.extend(angles.iter().map(|a| {
        let a = a.to_radians();
        centre + planar::<V>(radius * a.cos(), radius * a.sin())
    }));
    let p = vec![V::ZERO; q.len()];
    Swarm::new(q, p)
}

fn net<V: Vector>(swarm: &Swarm<V>) -> ProximityNet {
    ProximityNet::brute_force(&swarm.positions, AlphaAlphaParams::default().r)
}

/// An agent whose neighbours are all at `radius` from it: S_0 = |N| φ(radius − d_α)/radius with
/// its sign `expected`, and u_0^mp = S_0 (q_0^av − q_0) (eq. 33), towards q_0^av when S_0 > 0.
fn check_signed_stress<V: Vector>(radius: f64, expected: StressRegime, forms: &[AlphaAlphaForm]) {
    // uneven angles: the centre of neighbours is off the agent
    let swarm = star(planar::<V>(3.0, -2.0), radius, &[0.0, 50.0, 130.0]);
    let net = net(&swarm);
    for &form in forms {
        let alpha = AlphaAlpha::new(AlphaAlphaParams::default(), form, 1.0);
        let reading = alpha.reynolds_reading(0, &swarm.positions, &swarm.velocities, &net);
        assert_eq!(reading.regime, expected, "{form:?}");
        assert_eq!(reading.neighbours, 3);
        // eq. 26, 31: the weights from the action function itself
        let s = alpha.pair_action(radius) / radius;
        approx::assert_relative_eq!(reading.local_stress, 3.0 * s, max_relative = 1e-12);
        if form == AlphaAlphaForm::Nonsmooth {
            let phi = alpha.sigmoid().action(radius - alpha.params().d_alpha);
            approx::assert_relative_eq!(
                reading.local_stress,
                3.0 * phi / radius,
                max_relative = 1e-12
            );
        }
        // eq. 32: equal weights, the centre of neighbours is their plain centre
        let centre = reading.centre_of_neighbours.expect("S_0 ≠ 0");
        let plain = swarm.positions[1..].iter().fold(V::ZERO, |sum, &q| sum + q) / 3.0;
        assert_close(centre, plain, 1e-12);
        // eq. 33, magnitude and direction
        let to_centre = centre - swarm.positions[0];
        assert_close(
            reading.motion_planning,
            to_centre * reading.local_stress,
            1e-12,
        );
        let along = reading.motion_planning.dot(to_centre);
        match expected {
            StressRegime::Towards => assert!(along > 0.0, "{form:?}: {along}"),
            StressRegime::Away => assert!(along < 0.0, "{form:?}: {along}"),
            StressRegime::Neutral => unreachable!(),
        }
        // equal weights: u^mp = s |N| × Reynolds's cohesion
        assert_close(
            reading.motion_planning,
            reading.rules.cohesion * (3.0 * s),
            1e-12,
        );
        // all closer than d_α: separation is −cohesion; none closer: no separation
        if radius < alpha.params().d_alpha {
            assert_close(reading.rules.separation, -reading.rules.cohesion, 1e-15);
        } else {
            assert_eq!(reading.rules.separation, V::ZERO);
        }
    }
}

#[test]
fn positive_local_stress_pulls_towards_the_centre_of_neighbours_2d() {
    check_signed_stress::<DVec2>(7.3, StressRegime::Towards, &FORMS);
}

#[test]
fn positive_local_stress_pulls_towards_the_centre_of_neighbours_3d() {
    check_signed_stress::<DVec3>(7.5, StressRegime::Towards, &FORMS);
}

#[test]
fn negative_local_stress_pushes_away_from_the_centre_of_neighbours_2d() {
    check_signed_stress::<DVec2>(4.0, StressRegime::Away, &FORMS);
}

#[test]
fn negative_local_stress_pushes_away_from_the_centre_of_neighbours_3d() {
    check_signed_stress::<DVec3>(6.5, StressRegime::Away, &FORMS);
}

/// (α, α, 2) near the edge of the range: beyond d_α, but the derivative of the influence map in
/// φ_α = d/dz[ρ((z + d_α)/r) ψ_α(z)] (seed 000 eq. 23) outweighs the attraction (g(8) = −0.23 with
/// the defaults): S_i < 0 and the agent is pushed away, where (α, α, 1) and the approximation pull.
#[test]
fn the_smooth_protocol_pushes_away_near_the_edge_of_the_range() {
    check_signed_stress::<DVec2>(8.0, StressRegime::Away, &[AlphaAlphaForm::Smooth]);
    check_signed_stress::<DVec2>(
        8.0,
        StressRegime::Towards,
        &[AlphaAlphaForm::Nonsmooth, AlphaAlphaForm::Approximate],
    );
}

/// Seed 000 Fig. 3(a): mixed friends, three nearer than d_α and three beyond. Eq. 33 holds with
/// the weighted centre of eq. 32, and eq. 36 splits it between the centres of friends.
#[test]
fn mixed_friends_follow_eq_33_and_36() {
    let q: Vec<DVec2> = [
        (4.0, 10.0),
        (5.0, 100.0),
        (6.0, 200.0),
        (7.5, 250.0),
        (8.0, 300.0),
        (8.2, 340.0),
    ]
    .iter()
    .map(|&(d, a): &(f64, f64)| {
        let a = a.to_radians();
        DVec2::new(d * a.cos(), d * a.sin())
    })
    .collect();
    let mut positions = vec![DVec2::ZERO];
    positions.extend(q);
    let swarm = Swarm::new(positions, vec![DVec2::ZERO; 7]);
    let net = net(&swarm);
    for form in FORMS {
        let alpha = AlphaAlpha::new(AlphaAlphaParams::default(), form, 1.0);
        let reading = alpha.reynolds_reading(0, &swarm.positions, &swarm.velocities, &net);
        let (positive, negative) = reading.signed_stress;
        assert!(positive > 0.0 && negative < 0.0, "{form:?}");
        assert_eq!(reading.local_stress, positive + negative);
        let centre = reading.centre_of_neighbours.expect("S_0 ≠ 0");
        assert_close(
            reading.motion_planning,
            centre * reading.local_stress,
            1e-12,
        );
        let weights = StressForm(alpha.clone()).stress_weights(&net);
        let (plus, minus) = weights.centres_of_friends(net.graph(), 0, &swarm.positions);
        let (l1, l2) = (
            positive / reading.local_stress,
            negative / reading.local_stress,
        );
        assert_close(centre, plus.unwrap() * l1 + minus.unwrap() * l2, 1e-12);
        let expected = if reading.local_stress > 0.0 {
            StressRegime::Towards
        } else {
            StressRegime::Away
        };
        assert_eq!(reading.regime, expected);
    }
}

/// Seed 000 Fig. 3(b): every neighbour at d_α (a hexagon of side d_α around the agent): S_i = 0 to
/// round-off, neutral, no centre of neighbours, u_i^mp = 0 to round-off. An isolated agent is
/// neutral too.
#[test]
fn neutral_at_the_desired_distance() {
    let d = AlphaAlphaParams::default().d_alpha;
    let hexagon = star(
        DVec2::new(1.0, 2.0),
        d,
        &[0.0, 60.0, 120.0, 180.0, 240.0, 300.0],
    );
    let mut positions = hexagon.positions.clone();
    positions.push(DVec2::new(100.0, 100.0)); // isolated
    let swarm = Swarm::new(positions, vec![DVec2::X; 8]);
    let net = net(&swarm);
    for form in FORMS {
        let alpha = AlphaAlpha::new(AlphaAlphaParams::default(), form, 1.0);
        let reading = alpha.reynolds_reading(0, &swarm.positions, &swarm.velocities, &net);
        assert_eq!(reading.neighbours, 6, "{form:?}");
        assert_eq!(
            reading.regime,
            StressRegime::Neutral,
            "{form:?}: S = {}",
            reading.local_stress
        );
        assert!(reading.local_stress.abs() < 1e-14);
        assert_eq!(reading.centre_of_neighbours, None);
        assert!(reading.motion_planning.length() < 1e-13);
        let alone = alpha.reynolds_reading(7, &swarm.positions, &swarm.velocities, &net);
        assert_eq!((alone.regime, alone.neighbours), (StressRegime::Neutral, 0));
        assert_eq!(alone.local_stress, 0.0);
        assert_eq!(alone.motion_planning + alone.velocity_matching, DVec2::ZERO);
        // a neighbour 1 % beyond d_α is not neutral
        let mut stretched = swarm.positions.clone();
        stretched[1] = swarm.positions[0] + DVec2::new(1.01 * d, 0.0);
        let net = ProximityNet::brute_force(&stretched, alpha.params().r);
        let reading = alpha.reynolds_reading(0, &stretched, &swarm.velocities, &net);
        assert_eq!(reading.regime, StressRegime::Towards, "{form:?}");
    }
}

/// u_i^vm = c_d Σ_j (p_j − p_i) = c_d |N_i| (p̄_{N_i} − p_i): with c_d = 1 the velocity-matching term
/// is |N_i| times Reynolds's alignment (seed 000 eq. 17).
fn check_alignment<V: Vector>() {
    let swarm = random_swarm::<V>(60, 15.0, 2.0, 17);
    let net = net(&swarm);
    for c_d in [1.0, 2.5] {
        let alpha = AlphaAlpha::new(AlphaAlphaParams::default(), AlphaAlphaForm::Smooth, c_d);
        let mut checked = 0;
        for (i, reading) in alpha.reynolds_readings(&swarm, &net).iter().enumerate() {
            let neighbours = net.graph().neighbours(i);
            assert_eq!(reading.neighbours, neighbours.len());
            let n = neighbours.len() as f64;
            if neighbours.is_empty() {
                assert_eq!(reading.rules.alignment, V::ZERO);
                assert_eq!(reading.velocity_matching, V::ZERO);
                continue;
            }
            let mean = neighbours
                .iter()
                .fold(V::ZERO, |sum, &j| sum + swarm.velocities[j as usize])
                / n;
            assert_close(reading.rules.alignment, mean - swarm.velocities[i], 1e-12);
            assert_close(
                reading.velocity_matching,
                reading.rules.alignment * (c_d * n),
                1e-12,
            );
            checked += 1;
        }
        assert!(checked > 20, "only {checked} agents with neighbours");
    }
}

#[test]
fn velocity_matching_is_alignment_times_neighbours_2d() {
    check_alignment::<DVec2>();
}

#[test]
fn velocity_matching_is_alignment_times_neighbours_3d() {
    check_alignment::<DVec3>();
}

/// On a random state: u_i^mp + u_i^vm is the protocol's u_i (bit for bit: the same sums), the PD
/// form's to round-off; u_i^mp and S_i are those of the stress weights (eq. 27, 31); the regimes
/// partition the agents, and the 2003 protocol writes their counts as its last diagnostics.
fn check_terms_sum_to_the_input<V: Vector>() {
    let swarm = random_swarm::<V>(80, if V::DIM == 2 { 30.0 } else { 14.0 }, 1.5, 5);
    let net = net(&swarm);
    for form in FORMS {
        let alpha = AlphaAlpha::new(AlphaAlphaParams::default(), form, 1.3);
        let mut inputs = vec![V::ZERO; swarm.len()];
        alpha.controls(0.0, &swarm, &net, &mut inputs);
        let stress = StressForm(alpha.clone());
        let mut pd = vec![V::ZERO; swarm.len()];
        stress.controls(0.0, &swarm, &net, &mut pd);
        let weights = stress.stress_weights(&net);
        let readings = alpha.reynolds_readings(&swarm, &net);
        let mut regimes = [0usize; 3];
        for (i, reading) in readings.iter().enumerate() {
            let u = reading.motion_planning + reading.velocity_matching;
            assert_eq!(u, inputs[i], "{form:?} agent {i}");
            assert_close(u, pd[i], 1e-12);
            let mp = weights.motion_planning_term(net.graph(), i, &swarm.positions);
            assert_close(reading.motion_planning, mp, 1e-12);
            approx::assert_abs_diff_eq!(
                reading.local_stress,
                weights.local_stress(net.graph(), i),
                epsilon = 1e-12
            );
            regimes[reading.regime as usize] += 1;
        }
        assert!(regimes[0] > 0 && regimes[1] > 0, "{form:?}: {regimes:?}");
        let counts = alpha.stress_regimes(&swarm, &net);
        assert_eq!(
            [counts.towards, counts.away, counts.neutral],
            regimes,
            "{form:?}"
        );
        assert_eq!(counts.total(), swarm.len());
        let flocking = Flocking2003::<V> {
            alpha,
            translation: None,
        };
        let columns = flocking.diagnostics(0.0, &swarm, &net);
        let tail: Vec<(&str, f64)> = columns[columns.len() - 3..].to_vec();
        assert_eq!(tail, counts.columns());
        let total: f64 = tail.iter().map(|(_, v)| v).sum();
        assert_eq!(total, swarm.len() as f64);
    }
}

#[test]
fn the_two_terms_sum_to_the_input_2d() {
    check_terms_sum_to_the_input::<DVec2>();
}

#[test]
fn the_two_terms_sum_to_the_input_3d() {
    check_terms_sum_to_the_input::<DVec3>();
}

/// An α-lattice at rest with every link at d_α (a triangular one: second neighbours at √3 d_α,
/// beyond r): every agent is neutral, S_i = 0 and u_i = 0 (seed 000 Fig. 3(b), a relative
/// equilibrium), in both dimensions.
fn check_lattice_is_neutral<V: Vector>() {
    let params = AlphaAlphaParams::default();
    let q: Vec<V> = crate::common::triangular_lattice(5, 6, params.d_alpha);
    let swarm = Swarm::new(q, vec![planar::<V>(1.0, 0.5); 30]);
    let net = net(&swarm);
    for form in FORMS {
        let alpha = AlphaAlpha::new(params, form, 1.0);
        let counts = alpha.stress_regimes(&swarm, &net);
        assert_eq!(
            (counts.neutral, counts.total()),
            (30, 30),
            "{form:?}: {counts:?}"
        );
        for reading in alpha.reynolds_readings(&swarm, &net) {
            assert!(reading.motion_planning.length() < 1e-13);
            assert_eq!(reading.velocity_matching, V::ZERO);
            assert_eq!(reading.rules.alignment, V::ZERO);
        }
    }
}

#[test]
fn an_alpha_lattice_at_rest_is_neutral_2d() {
    check_lattice_is_neutral::<DVec2>();
}

#[test]
fn an_alpha_lattice_at_rest_is_neutral_3d() {
    check_lattice_is_neutral::<DVec3>();
}
