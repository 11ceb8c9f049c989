//! The periodic domain: a run away from the wrap equals open space; a lattice across it keeps its metrics.

use super::*;

/// A run of Algorithm 1 (the γ-agent-free α-interaction, TAC 2006 eq. 23 with c₁ = c₂ = 1) from
/// a perturbed triangular lattice drifting at `drift`, in `domain`.
fn drifting_lattice(
    domain: Domain<DVec2>,
    drift: DVec2,
    offset: DVec2,
) -> Simulation<DVec2, flock_protocols::Algorithm1> {
    let mut q = crate::common::triangular_lattice::<DVec2>(5, 6, 7.0);
    for (k, x) in q.iter_mut().enumerate() {
        *x += offset
            + DVec2::new(
                0.3 * ((k * 7) % 5) as f64 / 5.0,
                0.2 * ((k * 3) % 4) as f64 / 4.0,
            );
    }
    let p = vec![drift; q.len()];
    let protocol = flock_protocols::Algorithm1 {
        alpha: crate::common::papers_alpha(),
    };
    Simulation::new(
        protocol,
        Integrator::SymplecticEuler,
        Swarm::new(q, p),
        0.01,
    )
    .unwrap()
    .with_domain(domain)
    .unwrap()
}

/// Away from the wrap the torus changes nothing: the run of Algorithm 1 in a box of side 400
/// whose flock stays near its centre has the bits of the run in open space.
#[test]
fn periodic_run_equals_open_space_away_from_the_wrap() {
    let torus = Domain::Periodic {
        size: DVec2::splat(400.0),
    };
    let centre = DVec2::splat(180.0);
    let mut open = drifting_lattice(Domain::Open, DVec2::new(0.5, 0.2), centre);
    let mut periodic = drifting_lattice(torus, DVec2::new(0.5, 0.2), centre);
    for _ in 0..2000 {
        open.step();
        periodic.step();
    }
    let (a, b) = (open.swarm(), periodic.swarm());
    for (x, y) in a
        .positions
        .iter()
        .zip(&b.positions)
        .chain(a.velocities.iter().zip(&b.velocities))
    {
        assert_eq!(
            (x.x.to_bits(), x.y.to_bits()),
            (y.x.to_bits(), y.y.to_bits())
        );
    }
}

/// A lattice drifting across the wrap keeps its shape: its state is the open-space run's,
/// wrapped into the box (to round-off), and its metrics on the torus stay those of open space
/// at every step (connectivity 1, the same deviation energy, cohesion radius and least
/// distance), before, while and after it straddles the faces.
#[test]
fn a_lattice_crossing_the_wrap_keeps_its_metrics() {
    let side = 120.0;
    let torus = Domain::Periodic {
        size: DVec2::splat(side),
    };
    let start = DVec2::new(5.0, 20.0);
    let drift = DVec2::new(4.0, 1.5);
    let mut open = drifting_lattice(Domain::Open, drift, start);
    let mut periodic = drifting_lattice(torus, drift, start);
    let params = flock_metrics::MetricParams {
        d: 7.0,
        collision_distance: 1.75,
    };
    let mut straddled = 0;
    let mut worst_radius = 0.0_f64;
    for step in 0..3000 {
        open.step();
        periodic.step();
        if step % 50 != 0 {
            continue;
        }
        let (a, b) = (open.swarm(), periodic.swarm());
        for (x, y) in a.positions.iter().zip(&b.positions) {
            assert!(torus.displacement(*x, *y).length() < 1e-9);
        }
        let xs: Vec<f64> = b.positions.iter().map(|q| q.x).collect();
        if xs.iter().any(|&x| x < 7.0) && xs.iter().any(|&x| x > side - 7.0) {
            straddled += 1;
        }
        let (m_open, m_torus) = (open.metrics(&params), periodic.metrics(&params));
        assert_eq!(m_torus.connectivity, 1.0);
        assert_abs_diff_eq!(
            m_torus.deviation_energy,
            m_open.deviation_energy,
            epsilon = 1e-9
        );
        // R about the circular mean, not the arithmetic one: equal only for a flock small
        // against the box
        let gap = (m_torus.cohesion_radius - m_open.cohesion_radius).abs();
        worst_radius = worst_radius.max(gap / m_open.cohesion_radius);
        assert_abs_diff_eq!(m_torus.min_distance, m_open.min_distance, epsilon = 1e-9);
        assert_abs_diff_eq!(m_torus.polarisation, m_open.polarisation, epsilon = 1e-12);
    }
    assert!(
        straddled >= 5,
        "the flock straddled the faces at only {straddled} checks"
    );
    assert!(
        worst_radius < 0.01,
        "R on the torus {worst_radius} from R in open space"
    );
}
