//! Stress weights, local stress, friends and centres (ACC 2004 (seed 000) eq. 26–37).

use approx::assert_relative_eq;
use flock_graph::StressWeights;
use flock_math::Vector;
use glam::{DVec2, DVec3};

use crate::common::{cloud, searched};

/// Seed 000 eq. 26 with a linear action φ_α(z) = z and d_α = 0.3: s_ij = (‖q‖ − d_α) / ‖q‖.
fn seed000(d: f64) -> f64 {
    (d - 0.3) / d
}

fn check_eq33_and_friends<V: Vector>() {
    let q: Vec<V> = cloud(1, 300, 1.0, 0.0);
    let net = searched(&q, 0.45);
    let g = net.graph();
    let s = StressWeights::from_distances(&net, seed000);
    assert_eq!(s.weights().len(), g.directed_edge_count());
    let mut checked = 0;
    for i in 0..q.len() {
        // Friends partition N_i by the sign of s_ij (eq. 28–30).
        let friends = s.friends(g, i);
        let mut all: Vec<u32> = [&friends.positive, &friends.negative, &friends.neutral]
            .into_iter()
            .flatten()
            .copied()
            .collect();
        all.sort_unstable();
        assert_eq!(all, g.neighbours(i));
        for (e, &j) in g.edge_range(i).zip(g.neighbours(i)) {
            let w = s.weights()[e];
            assert_eq!(w, seed000(net.distances()[e]));
            let expected_list = if w > 0.0 {
                &friends.positive
            } else {
                &friends.negative
            };
            assert!(expected_list.contains(&j));
        }
        let stress = s.local_stress(g, i);
        let (pos, neg) = s.signed_local_stress(g, i);
        assert_relative_eq!(stress, pos + neg, epsilon = 1e-12);
        let u = s.motion_planning_term(g, i, &q);
        // eq. 27 written out: Σ s_ij (q_j − q_i).
        let direct = g
            .neighbours(i)
            .iter()
            .zip(&s.weights()[g.edge_range(i)])
            .fold(V::ZERO, |acc, (&j, &w)| acc + (q[j as usize] - q[i]) * w);
        assert_eq!(u, direct);
        match s.centre_of_neighbours(g, i, &q) {
            // eq. 33: u_i^mp = S_i (q_i^av − q_i).
            Some(centre) => {
                checked += 1;
                let scale = 1.0 + pos - neg;
                assert!((u - (centre - q[i]) * stress).length() <= 1e-12 * scale);
                // eq. 36: q_i^av = λ₁ q_i^av+ + λ₂ q_i^av−, λ = S_i^± / S_i.
                let (plus, minus) = s.centres_of_friends(g, i, &q);
                let mix = plus.map_or(V::ZERO, |c| c * pos) + minus.map_or(V::ZERO, |c| c * neg);
                assert!((mix / stress - centre).length() <= 1e-9 * (1.0 + centre.length()));
            }
            None => assert_eq!(stress, 0.0),
        }
    }
    assert!(checked > 250, "only {checked} agents with neighbours");
}

#[test]
fn motion_planning_term_is_stress_times_offset_to_centre_2d() {
    check_eq33_and_friends::<DVec2>();
}

#[test]
fn motion_planning_term_is_stress_times_offset_to_centre_3d() {
    check_eq33_and_friends::<DVec3>();
}

fn check_eq37<V: Vector>() {
    // Agent 0 at the origin, a negative friend at distance 0.5 and a positive one at 1.5, with
    // s = d − 1: stresses −0.5 and +0.5 cancel exactly (S_0 = 0, Figure 3(c)).
    let axis = |k: usize, x: f64| V::from_fn(|a| if a == k { x } else { 0.0 });
    let q = [V::ZERO, axis(0, 0.5), axis(1, -1.5), axis(0, 9.0)];
    let net = searched(&q, 2.0);
    let g = net.graph();
    let s = StressWeights::from_distances(&net, |d| d - 1.0);
    assert_eq!(g.neighbours(0), &[1, 2]);
    assert_eq!(s.local_stress(g, 0), 0.0);
    assert_eq!(s.signed_local_stress(g, 0), (0.5, -0.5));
    assert_eq!(s.centre_of_neighbours(g, 0, &q), None);
    let friends = s.friends(g, 0);
    assert_eq!(
        (friends.positive, friends.negative, friends.neutral),
        (vec![2], vec![1], vec![])
    );
    // With one friend each, the centres are the friends themselves.
    let (plus, minus) = s.centres_of_friends(g, 0, &q);
    assert_eq!((plus, minus), (Some(q[2]), Some(q[1])));
    // eq. 37: u_i^mp = S_i⁺ (q_i^av+ − q_i^av−), along the line from the negative to the positive friend.
    let u = s.motion_planning_term(g, 0, &q);
    assert_eq!(u, (q[2] - q[1]) * 0.5);
    assert_ne!(u, V::ZERO);
    // The isolated agent 3 has no stress, no friends, no motion.
    assert_eq!(s.motion_planning_term(g, 3, &q), V::ZERO);
    assert_eq!(s.centres_of_friends(g, 3, &q), (None, None));
    assert_eq!(s.friends(g, 3), Default::default());
}

#[test]
fn zero_local_stress_moves_from_negative_to_positive_friends_2d() {
    check_eq37::<DVec2>();
}

#[test]
fn zero_local_stress_moves_from_negative_to_positive_friends_3d() {
    check_eq37::<DVec3>();
}

#[test]
fn neutral_friends_have_zero_stress() {
    // Hexagon of side d_α around agent 0 (Figure 3(b)): every neighbour is neutral, u^mp = 0.
    let q: Vec<DVec2> = std::iter::once(DVec2::ZERO)
        .chain((0..6).map(|k| DVec2::from_angle(k as f64 * core::f64::consts::FRAC_PI_3) * 0.3))
        .collect();
    let net = searched(&q, 0.31);
    let s = StressWeights::from_distances(&net, |d| {
        if (d - 0.3).abs() < 1e-12 {
            0.0
        } else {
            seed000(d)
        }
    });
    let friends = s.friends(net.graph(), 0);
    assert_eq!(friends.neutral, vec![1, 2, 3, 4, 5, 6]);
    assert!(friends.positive.is_empty() && friends.negative.is_empty());
    assert_eq!(s.motion_planning_term(net.graph(), 0, &q), DVec2::ZERO);
}
