//! β-agents on walls against the closed forms of Olfati-Saber (IEEE TAC 51(3) 2006):
//! `μ = 1`, `q̂ = P q + (I − P) y`, `p̂ = P p`, `P = I − a aᵀ`.

use approx::assert_abs_diff_eq;
use flock_math::Vector;
use flock_obstacles::{Obstacle, Obstacle2d, Obstacle3d};
use glam::{DVec2, DVec3};

use crate::common::{assert_close, grid, velocity};

/// A wall through `y` with a non-unit, non-axis outward normal `n`.
fn wall<V: Vector, O: Obstacle<V>>() -> (O, V, V) {
    let y = V::from_fn(|axis| 0.5 * axis as f64 - 1.0);
    let n = V::from_fn(|axis| [1.0, 2.0, -2.0][axis]);
    (O::wall(y, n).unwrap(), y, n / n.length())
}

/// `P z = z − a (a · z)`.
fn tangent<V: Vector>(a: V, z: V) -> V {
    z - a * a.dot(z)
}

fn check_closed_form<V: Vector, O: Obstacle<V>>() {
    let (wall, y, a) = wall::<V, O>();
    let (mut inside, mut outside) = (0, 0);
    for (index, q) in grid(y, 5.0, 12).enumerate() {
        let p = velocity::<V>(index);
        let beta = wall.beta_agent(q, p);
        let height = a.dot(q - y);

        assert_eq!(beta.mu, 1.0);
        assert_close(beta.normal, a, 1e-15);
        assert_close(beta.position, tangent(a, q) + (y - tangent(a, y)), 1e-13);
        assert_close(beta.velocity, tangent(a, p), 1e-14);
        assert_abs_diff_eq!(beta.distance, height.abs(), epsilon = 1e-13);
        assert_eq!(beta.inside, height <= 0.0, "q = {q:?}");
        if beta.inside {
            inside += 1;
        } else {
            outside += 1;
        }
    }
    assert!(
        inside > 0 && outside > 0,
        "{inside} inside, {outside} outside"
    );
}

#[test]
fn closed_form_2d() {
    check_closed_form::<DVec2, Obstacle2d>();
}

#[test]
fn closed_form_3d() {
    check_closed_form::<DVec3, Obstacle3d>();
}

/// `q̂` on the boundary plane (`a · (q̂ − y) = 0`), `p̂` tangent (`p̂ · a = 0`).
fn check_geometry<V: Vector, O: Obstacle<V>>() {
    let (wall, y, a) = wall::<V, O>();
    for (index, q) in grid(y, 4.0, 10).enumerate() {
        let beta = wall.beta_agent(q, velocity(index));
        assert_abs_diff_eq!(a.dot(beta.position - y), 0.0, epsilon = 1e-13);
        assert_abs_diff_eq!(beta.velocity.dot(beta.normal), 0.0, epsilon = 1e-14);
    }
}

#[test]
fn geometry_2d() {
    check_geometry::<DVec2, Obstacle2d>();
}

#[test]
fn geometry_3d() {
    check_geometry::<DVec3, Obstacle3d>();
}

/// The wall is closed: an α-agent on the boundary plane is inside, and is its own β-agent.
fn check_agent_on_boundary<V: Vector, O: Obstacle<V>>() {
    let (wall, y, a) = wall::<V, O>();
    let beta = wall.beta_agent(y, velocity(5));
    assert!(beta.inside);
    assert_close(beta.position, y, 1e-15);
    assert_close(beta.normal, a, 1e-15);
    assert_eq!(beta.distance, 0.0);
}

#[test]
fn agent_on_boundary_2d() {
    check_agent_on_boundary::<DVec2, Obstacle2d>();
}

#[test]
fn agent_on_boundary_3d() {
    check_agent_on_boundary::<DVec3, Obstacle3d>();
}

/// The floor `z ≤ 0` (`y ≤ 0` in 2D): an agent below it is inside, its β-agent straight above.
fn check_agent_below_floor<V: Vector, O: Obstacle<V>>() {
    let up = V::from_fn(|axis| if axis + 1 == V::DIM { 1.0 } else { 0.0 });
    let floor = O::wall(V::ZERO, up * 7.0).unwrap();
    let q = V::from_fn(|axis| if axis + 1 == V::DIM { -3.0 } else { 2.0 });
    let beta = floor.beta_agent(q, up * -1.0 + velocity::<V>(0));
    assert!(beta.inside);
    assert_eq!(beta.normal, up);
    assert_eq!(beta.position, q + up * 3.0);
    assert_eq!(beta.distance, 3.0);
}

#[test]
fn agent_below_floor_2d() {
    check_agent_below_floor::<DVec2, Obstacle2d>();
}

#[test]
fn agent_below_floor_3d() {
    check_agent_below_floor::<DVec3, Obstacle3d>();
}
