//! Couzin et al. 2002 against a brute-force step, and its noise's spread.

use super::*;

/// The desired direction of Couzin et al. 2002 without noise, then the bounded turn, brute force.
fn couzin_step<V: Vector>(
    q: &[V],
    p: &[V],
    c: CouzinParams,
    tau: f64,
    side: Option<f64>,
) -> (Vec<V>, Vec<V>) {
    let n = q.len();
    let r_o = c.r_r + c.delta_r_o;
    let r_a = r_o + c.delta_r_a;
    let half = c.field_of_perception.to_radians() / 2.0;
    let mut p2 = p.to_vec();
    for i in 0..n {
        let v = p[i] / p[i].length();
        let (mut dr, mut dorient, mut da) = (V::ZERO, V::ZERO, V::ZERO);
        let (mut nr, mut no, mut na) = (0, 0, 0);
        for j in 0..n {
            if j == i {
                continue;
            }
            let r = offset(q[i], q[j], side);
            let d = r.length();
            if d >= r_a || v.dot(r / d).clamp(-1.0, 1.0).acos() > half + 1e-12 {
                continue;
            }
            if d < c.r_r {
                dr -= r / d;
                nr += 1;
            } else if d < r_o {
                dorient += p[j] / p[j].length();
                no += 1;
            } else {
                da += r / d;
                na += 1;
            }
        }
        let desired = if nr > 0 {
            dr
        } else if no > 0 && na > 0 {
            (dorient / dorient.length() + da / da.length()) * 0.5
        } else if no > 0 {
            dorient
        } else if na > 0 {
            da
        } else {
            v
        };
        let desired = desired / desired.length();
        let angle = v.dot(desired).clamp(-1.0, 1.0).acos();
        let max = c.turning_rate.to_radians() * tau;
        let heading = if angle <= max {
            desired
        } else {
            // rotate v towards desired by max in their plane
            let w = desired - v * v.dot(desired);
            let w = w / w.length();
            v * max.cos() + w * max.sin()
        };
        p2[i] = heading * c.speed;
    }
    let q2 = (0..n).map(|i| wrapped(q[i] + p2[i] * tau, side)).collect();
    (q2, p2)
}

fn couzin_agrees<V: Vector>(side: Option<f64>) {
    let c = CouzinParams {
        noise: 0.0,
        delta_r_o: 1.5,
        delta_r_a: 3.0,
        ..CouzinParams::default()
    };
    let n = 120;
    let swarm = near_the_wrap::<V>(n, 14.0, 3.0, 8);
    let tau = 0.1;
    let model = Couzin::new(c, tau, 2, domain(side)).unwrap();
    let reference = |_, q: &[V], p: &[V]| couzin_step(q, p, c, tau, side);
    agrees_with_reference(model, swarm, (tau, side, 20), reference, (1e-9, 1e-9));
}

#[test]
fn couzin_equals_brute_force_2d_3d_open_and_periodic() {
    couzin_agrees::<DVec2>(None);
    couzin_agrees::<DVec3>(None);
    couzin_agrees::<DVec2>(Some(14.0));
    couzin_agrees::<DVec3>(Some(14.0));
}

/// The angular noise turns the desired direction by N(0, σ²): over many agents and steps of a
/// lone individual (no neighbours, desired = its heading), the turn's standard deviation is σ
/// (when the turning bound θ τ lets the turns through, as here).
#[test]
fn couzin_noise_has_the_papers_spread() {
    let c = CouzinParams {
        noise: 0.05,
        ..CouzinParams::default()
    };
    // τ = 1 s: the turning bound θ τ = 40° lets every drawn turn through
    let tau = 1.0;
    let n = 2000;
    let q: Vec<DVec2> = (0..n)
        .map(|i| DVec2::new(100.0 * f64::from(i), 0.0))
        .collect();
    let p = vec![DVec2::new(c.speed, 0.0); n as usize];
    let model = Couzin::new(c, tau, 7, Domain::Open).unwrap();
    let mut inputs = vec![DVec2::ZERO; n as usize];
    let swarm = Swarm::new(q, p);
    let net = flock_graph::ProximityNet::brute_force(&swarm.positions, model.interaction_range());
    model.controls(0.0, &swarm, &net, &mut inputs);
    let angles: Vec<f64> = inputs.iter().map(|u| u.y.atan2(u.x)).collect();
    let var = angles.iter().map(|a| a * a).sum::<f64>() / f64::from(n);
    assert!((var.sqrt() - 0.05).abs() < 0.005, "{}", var.sqrt());
}
