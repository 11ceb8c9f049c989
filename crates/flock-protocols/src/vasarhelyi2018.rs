//! The flocking model of Vásárhelyi, Virágh, Somorjai, Nepusz, Eiben and Vicsek ("Optimized
//! flocking of autonomous drones in confined environments", Science Robotics 3(20), eaat3536,
//! 2018), the algorithm that flew 30 drones outdoors: repulsion, velocity alignment under a
//! braking curve, self-propulsion and shill agents on the walls of an arena, summed into a
//! desired velocity cut at v^max; here tracked by a first-order velocity relaxation, as the
//! authors' simulator robotsim (github.com/csviragh/robotsim) moves its point masses.

use flock_graph::ProximityNet;
use flock_math::Vector;
use flock_math::parallel::fill_interruptible;

use crate::error::{ParamError, check};
use crate::swarm::heading_mismatch;
use crate::{LocalForm, Perceived, Protocol, Swarm};

/// The parameters of the model, named as the paper names them (SI units: m, s).
///
/// Defaults (docs/models.md has each value's source): v^flock = 6 m/s; the friction and shill
/// values r_0^frict = 85.3 m, C^frict = 0.05, v^frict = 0.63 m/s, p^frict = 3.2 s⁻¹, a^frict =
/// 4.16 m s⁻², r_0^shill = 0.3 m, v^shill = 13.6 m/s, p^shill = 3.55 s⁻¹, a^shill = 3.02 m s⁻²
/// are SwarmLab's `param_vasarhelyi.m` (EPFL LIS); p^rep = 0.13 s⁻¹ is DANCERS's (SwarmLab has
/// 0.03; DANCERS differs from SwarmLab on C^frict, v^shill and a^shill too). r_0^rep = 25 m is
/// assumed (robotsim's shipped `R_0` is 25.67 m for its 4 m/s set). τ = 1 s (`tau_PID_XY`),
/// a^max = 6 m s⁻² (`a_max`), r_c = 100 m (`R_C`), r^coll = 3 m (`Radius`) and v^max = 8 m/s
/// (`V_Max`) are robotsim's shipped `unitparams.dat`, `initparams.dat` and `flockingparams.dat`.
/// None was checked against the paper's supplementary table, which was not available to this
/// work. The arena is a square (a cube in 3D) of side 250 m about the origin (docs/models.md).
/// A scenario may leave out any of them.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
pub struct VasarhelyiParams {
    /// The preferred (flocking) speed v^flock > 0 of the self-propulsion term.
    pub v_flock: f64,
    /// The range r_0^rep > 0 of the linear repulsion.
    pub r0_rep: f64,
    /// The repulsion gain p^rep ≥ 0 (s⁻¹).
    pub p_rep: f64,
    /// The offset r_0^frict of the alignment's stopping point beyond r_0^rep: the braking curve
    /// is evaluated at r_ij − (r_0^rep + r_0^frict) (robotsim's `R_0 + R_0_Offset_Frict`).
    pub r0_frict: f64,
    /// The alignment coefficient C^frict ≥ 0.
    pub c_frict: f64,
    /// The velocity slack v^frict ≥ 0 of the alignment.
    pub v_frict: f64,
    /// The gain p^frict > 0 (s⁻¹) of the alignment's braking curve.
    pub p_frict: f64,
    /// The acceleration a^frict > 0 of the alignment's braking curve.
    pub a_frict: f64,
    /// The stopping-point offset r_0^shill of the walls' braking curve.
    pub r0_shill: f64,
    /// The speed v^shill ≥ 0 of the shill agents (towards the arena's inside).
    pub v_shill: f64,
    /// The gain p^shill > 0 (s⁻¹) of the walls' braking curve.
    pub p_shill: f64,
    /// The acceleration a^shill > 0 of the walls' braking curve.
    pub a_shill: f64,
    /// The cut v^max > 0 of the desired velocity's length.
    pub v_max: f64,
    /// The communication range r_c > 0: the neighbours an agent hears.
    pub r_c: f64,
    /// The relaxation time τ > 0 of the velocity towards the desired one.
    pub tau: f64,
    /// The largest acceleration a^max > 0 of the tracking (`f64::INFINITY`: none).
    pub a_max: f64,
    /// The collision distance r^coll ∈ (0, r_c) of the collision ratio φ^coll.
    pub r_coll: f64,
    /// The arena's shape.
    pub arena_shape: ArenaShape,
    /// The square's (cube's) side, or the circle's (ball's) diameter, > 0.
    pub arena_side: f64,
    /// The arena's centre c, one coordinate per dimension, as a scenario writes it; `None`: the
    /// origin.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub arena_centre: Option<Vec<f64>>,
}

/// The default arena side (m): 250 (docs/models.md has its source).
pub const ARENA_SIDE: f64 = 250.0;

impl Default for VasarhelyiParams {
    fn default() -> Self {
        Self {
            v_flock: 6.0,
            r0_rep: 25.0,
            p_rep: 0.13,
            r0_frict: 85.3,
            c_frict: 0.05,
            v_frict: 0.63,
            p_frict: 3.2,
            a_frict: 4.16,
            r0_shill: 0.3,
            v_shill: 13.6,
            p_shill: 3.55,
            a_shill: 3.02,
            v_max: 8.0,
            r_c: 100.0,
            tau: 1.0,
            a_max: 6.0,
            r_coll: 3.0,
            arena_shape: ArenaShape::Square,
            arena_side: ARENA_SIDE,
            arena_centre: None,
        }
    }
}

impl VasarhelyiParams {
    /// The arena of the parameters in vectors `V`.
    ///
    /// # Errors
    /// `arena_side` not positive, `arena_centre` not of `V::DIM` finite coordinates within ±10⁹.
    pub fn arena<V: Vector>(&self) -> Result<Arena<V>, ParamError> {
        check::positive("arena_side", self.arena_side)?;
        let centre = match &self.arena_centre {
            None => V::ZERO,
            Some(c) => {
                check::require(
                    c.len() == V::DIM,
                    "arena_centre",
                    c,
                    &format!(
                        "has {} components but the space has {} dimensions",
                        c.len(),
                        V::DIM
                    ),
                    &format!(
                        "give exactly {} numbers, e.g. [{}], or leave it out for the origin",
                        V::DIM,
                        vec!["0.0"; V::DIM].join(", ")
                    ),
                )?;
                check::coordinates("arena_centre", c)?;
                V::from_fn(|k| c[k])
            }
        };
        Ok(Arena {
            shape: self.arena_shape,
            centre,
            side: self.arena_side,
        })
    }
}

/// The shape of an arena: a square (a cube in 3D) or a circle (a ball in 3D).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ArenaShape {
    /// Walls on the planes |x_k − c_k| = side/2 of every axis k (robotsim's `ArenaShape` 1).
    #[default]
    Square,
    /// The wall ‖x − c‖ = side/2 (robotsim's `ArenaShape` 0).
    Circle,
}

/// The arena whose walls the shill agents stand on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arena<V> {
    /// Its shape.
    pub shape: ArenaShape,
    /// Its centre c.
    pub centre: V,
    /// The square's (cube's) side, or the circle's (ball's) diameter, > 0.
    pub side: f64,
}

impl<V: Vector> Arena<V> {
    /// How far `q` is outside the arena (0 inside): the length of the per-axis excess beyond
    /// the walls for a square, ‖q − c‖ − side/2 for a circle (robotsim's
    /// `SaveModelSpecificStats`).
    #[must_use]
    pub fn outside(&self, q: V) -> f64 {
        let half = self.side / 2.0;
        let d = q - self.centre;
        match self.shape {
            ArenaShape::Square => V::from_fn(|k| (d.coord(k).abs() - half).max(0.0)).length(),
            ArenaShape::Circle => (d.length() - half).max(0.0),
        }
    }
}

/// The braking curve D(r, a, p) (robotsim's `VelDecayLinSqrt` in
/// `utilities/math_utils.c`): the largest velocity difference that can still be cancelled over
/// the distance r with acceleration a, with the linear gain p near the stop:
/// 0 for r ≤ 0, r p for 0 < r p < a/p, √(2 a r − a²/p²) beyond. Continuous at r p = a/p.
///
/// # Example
/// ```
/// use flock_protocols::vasarhelyi2018::braking_curve;
///
/// assert_eq!(braking_curve(-1.0, 4.0, 2.0), 0.0);
/// assert_eq!(braking_curve(0.5, 4.0, 2.0), 1.0); // linear: r p = 1 < a/p = 2
/// assert_eq!(braking_curve(2.5, 4.0, 2.0), 4.0); // √(2·4·2.5 − 4) = 4
/// ```
#[inline]
#[must_use]
pub fn braking_curve(r: f64, a: f64, p: f64) -> f64 {
    if r <= 0.0 || a <= 0.0 || p <= 0.0 {
        return 0.0;
    }
    let linear = r * p;
    if linear < a / p {
        linear
    } else {
        (2.0 * a * r - a * a / (p * p)).sqrt()
    }
}

/// The model of Vásárhelyi et al. (2018) as an acceleration protocol.
///
/// Agent i at q_i with velocity v_i hears the agents j within r_c (r_ij = ‖q_i − q_j‖) and sums
/// the terms as the paper's simulator robotsim computes them (`algo_spp_evol.c`
/// `CalculatePreferredVelocity`, `utilities/interactions.c`, `arenas.c`; the paper's text was not
/// available to this work, so no equation number is cited):
/// - repulsion, linear within r_0^rep: Σ_j p^rep (r_0^rep − r_ij) (q_i − q_j)/r_ij over
///   r_ij < r_0^rep (robotsim `RepulsionLin` caps each pair at `V_Rep`, a value the optimised
///   set of the reimplementations does not have; ours has no cap);
/// - alignment ("friction"): with v_ij = ‖v_i − v_j‖ and the allowed difference
///   v_ij^frictmax = max(v^frict, D(r_ij − (r_0^rep + r_0^frict), a^frict, p^frict))
///   ([`braking_curve`]; the stopping point r_0^rep + r_0^frict is robotsim's
///   `R_0 + R_0_Offset_Frict`, `FrictionLinSqrt` called from `CalculatePreferredVelocity`),
///   Σ_j C^frict (v_ij − v_ij^frictmax) (v_j − v_i)/v_ij over v_ij > v_ij^frictmax;
/// - self-propulsion v^flock v_i/‖v_i‖ (0 at rest);
/// - the walls: for each wall nearest along an axis (square, cube) or the one wall (circle,
///   ball), a shill agent at the agent's foot on it moves inwards, perpendicular to the wall, at
///   v^shill: v_s. With r_s the distance to the wall (negative outside) and v_is = ‖v_s − v_i‖,
///   it adds (v_is − D(r_s − r_0^shill, a^shill, p^shill)) (v_s − v_i)/v_is when positive.
///
/// The sum ṽ_i is cut at v^max keeping its direction: v_d,i = ṽ_i min(1, v^max/‖ṽ_i‖)
/// (robotsim's `CutOffMode` branch; robotsim ships that switch off and rescales ṽ_i to v^flock
/// instead). The
/// protocol's output is the acceleration u_i = (v_d,i − v_i)/τ, cut at a^max keeping its
/// direction: the point mass of robotsim's `robotmodel.c`, whose velocity relaxes to the
/// preferred one with the time `tau_PID` and whose acceleration saturates at `a_max`.
///
/// In 3D every term is the same in three dimensions and the arena is a cube (or ball) about its
/// centre: robotsim's `Dim = 3` (its square arena loops over every axis). The paper flies in the
/// plane at a held altitude; the 3D form is robotsim's, not a result of the paper.
///
/// Diagnostics, the paper's order parameters (robotsim's `algo_spp_evol_stat.c`, `stat.c`):
/// `velocity_correlation` φ^corr = Σ_{i≠j} v̂_i · v̂_j / (N(N − 1)) (all pairs: robotsim's
/// within connected clusters, the same for one cluster), `speed_ratio` φ^vel / v^flock with φ^vel
/// the mean speed, `collision_ratio` φ^coll = 2 (pairs closer than r^coll) / (N(N − 1)) and
/// `wall_violation` φ^wall, the mean over the agents of the distance outside the arena.
///
/// # Example
/// ```
/// use flock_graph::{NeighbourSearch, ProximityNet};
/// use flock_math::Domain;
/// use flock_protocols::{Arena, ArenaShape, Protocol, Swarm, Vasarhelyi, VasarhelyiParams};
/// use glam::DVec2;
///
/// let model = Vasarhelyi::<DVec2>::new(VasarhelyiParams::default())?; // a square of side 250 m
/// assert_eq!(model.arena().shape, ArenaShape::Square);
/// let q = vec![DVec2::ZERO, DVec2::new(10.0, 0.0)];
/// let p = vec![DVec2::new(0.0, 6.0), DVec2::new(0.0, 6.0)];
/// let mut net = ProximityNet::new();
/// NeighbourSearch::new().build_in(&Domain::Open, &q, model.interaction_range(), &mut net);
/// let mut u = vec![DVec2::ZERO; 2];
/// model.controls(0.0, &Swarm::new(q, p), &net, &mut u);
/// // pushed apart towards r_0^rep = 25 m (run apart by flock-sim's test
/// // `vasarhelyi_pushes_a_close_pair_apart`)
/// assert!(u[0].x < 0.0 && u[1].x > 0.0);
/// # Ok::<(), flock_protocols::ParamError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Vasarhelyi<V> {
    params: VasarhelyiParams,
    arena: Arena<V>,
}

impl<V: Vector> Vasarhelyi<V> {
    /// The model with `params` in their arena (open space around it).
    ///
    /// # Errors
    /// A parameter outside its domain, named as in [`VasarhelyiParams`].
    pub fn new(params: VasarhelyiParams) -> Result<Self, ParamError> {
        let c = &params;
        check::positive("v_flock", c.v_flock)?;
        check::positive("r0_rep", c.r0_rep)?;
        check::non_negative("p_rep", c.p_rep)?;
        check::finite("r0_frict", c.r0_frict)?;
        check::non_negative("c_frict", c.c_frict)?;
        check::non_negative("v_frict", c.v_frict)?;
        check::positive("p_frict", c.p_frict)?;
        check::positive("a_frict", c.a_frict)?;
        check::finite("r0_shill", c.r0_shill)?;
        check::non_negative("v_shill", c.v_shill)?;
        check::positive("p_shill", c.p_shill)?;
        check::positive("a_shill", c.a_shill)?;
        check::positive("v_max", c.v_max)?;
        check::positive("r_c", c.r_c)?;
        check::positive("tau", c.tau)?;
        check::require(
            c.a_max > 0.0 && !c.a_max.is_nan(),
            "a_max",
            c.a_max,
            "is not positive",
            "give the largest acceleration, > 0 (a very large value for none)",
        )?;
        check::positive("r_coll", c.r_coll)?;
        check::require(
            c.r_coll < c.r_c,
            "r_coll",
            c.r_coll,
            "is not below the communication range r_c",
            "give a collision distance below r_c",
        )?;
        let arena = params.arena()?;
        Ok(Self { params, arena })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &VasarhelyiParams {
        &self.params
    }

    /// The arena.
    #[must_use]
    pub const fn arena(&self) -> &Arena<V> {
        &self.arena
    }

    /// The wall term of an agent at `q` with velocity `v`: the shill agents' sum.
    #[must_use]
    pub fn wall_term(&self, q: V, v: V) -> V {
        let c = &self.params;
        let half = self.arena.side / 2.0;
        let to_centre = self.arena.centre - q;
        let shill = |distance: f64, inwards: V| {
            let vs = inwards * c.v_shill;
            let diff = vs - v;
            let v_is = diff.length();
            let allowed = braking_curve(distance - c.r0_shill, c.a_shill, c.p_shill);
            if v_is > allowed {
                diff * ((v_is - allowed) / v_is)
            } else {
                V::ZERO
            }
        };
        match self.arena.shape {
            ArenaShape::Square => {
                let mut total = V::ZERO;
                for k in 0..V::DIM {
                    let along = to_centre.coord(k);
                    let inwards = V::from_fn(|m| if m == k { along.signum() } else { 0.0 });
                    total += shill(half - along.abs(), inwards);
                }
                total
            }
            ArenaShape::Circle => {
                let r = to_centre.length();
                shill(half - r, to_centre.normalize_or_zero())
            }
        }
    }

    /// The desired velocity v_d of an agent at `q` with velocity `v` from the states `others`
    /// (position, velocity) it hears, those beyond r_c left out.
    pub fn desired_velocity(&self, q: V, v: V, others: impl Iterator<Item = (V, V)>) -> V {
        let c = &self.params;
        let (mut repulsion, mut friction) = (V::ZERO, V::ZERO);
        for (qj, vj) in others {
            let offset = q - qj;
            let r = offset.length();
            if r >= c.r_c || r == 0.0 {
                continue;
            }
            if r < c.r0_rep {
                repulsion += offset * (c.p_rep * (c.r0_rep - r) / r);
            }
            let dv = vj - v;
            let v_ij = dv.length();
            let allowed = c.v_frict.max(braking_curve(
                r - (c.r0_rep + c.r0_frict),
                c.a_frict,
                c.p_frict,
            ));
            if v_ij > allowed {
                friction += dv * (c.c_frict * (v_ij - allowed) / v_ij);
            }
        }
        let propulsion = v.normalize_or_zero() * c.v_flock;
        let total = propulsion + repulsion + friction + self.wall_term(q, v);
        cut(total, c.v_max)
    }

    /// u = (v_d − v)/τ cut at a^max, from the agent's state and the states it hears.
    fn input(&self, q: V, v: V, others: impl Iterator<Item = (V, V)>) -> V {
        let desired = self.desired_velocity(q, v, others);
        cut((desired - v) * (1.0 / self.params.tau), self.params.a_max)
    }

    /// The paper's order parameters of a state (see [`Vasarhelyi`]) in the order
    /// φ^corr, φ^vel / v^flock, φ^coll, φ^wall; pairs closer than r^coll counted over `net`.
    /// Sums over the agents run in ascending original index (the net's numbering), so agents
    /// stored in any order give the same bits.
    #[must_use]
    pub fn order_parameters(&self, swarm: &Swarm<V>, net: &ProximityNet) -> [f64; 4] {
        let (q, v) = (&swarm.positions, &swarm.velocities);
        let numbering = net.numbering();
        let n = q.len();
        let pairs = (n * n.saturating_sub(1)) as f64;
        let headings = numbering
            .ordered(v)
            .fold(V::ZERO, |acc, p| acc + p.normalize_or_zero());
        let moving = v.iter().filter(|p| **p != V::ZERO).count() as f64;
        let correlation = if n < 2 {
            1.0
        } else {
            (headings.length_squared() - moving) / pairs
        };
        let speed = numbering.ordered(v).map(|p| p.length()).sum::<f64>() / n.max(1) as f64;
        let mut close = 0usize;
        for i in 0..n {
            for &j in net.graph().neighbours(i) {
                let j = j as usize;
                if j > i && (q[i] - q[j]).length() <= self.params.r_coll {
                    close += 1;
                }
            }
        }
        let collisions = if n < 2 {
            0.0
        } else {
            2.0 * close as f64 / pairs
        };
        let wall = numbering
            .ordered(q)
            .map(|x| self.arena.outside(x))
            .sum::<f64>()
            / n.max(1) as f64;
        [correlation, speed / self.params.v_flock, collisions, wall]
    }
}

/// `x` shortened to length `limit` when longer, keeping its direction.
#[inline]
fn cut<V: Vector>(x: V, limit: f64) -> V {
    let length = x.length();
    if length > limit {
        x * (limit / length)
    } else {
        x
    }
}

impl<V: Vector> Protocol<V> for Vasarhelyi<V> {
    fn interaction_range(&self) -> f64 {
        self.params.r_c
    }

    fn uses_net_distances(&self) -> bool {
        false
    }

    /// Each agent's terms summed over its list in ascending original index: agents at random
    /// are stored by cell.
    fn follows_numbering(&self) -> bool {
        true
    }

    fn controls(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let (q, p) = (&swarm.positions, &swarm.velocities);
        fill_interruptible(inputs, |i| {
            let others = net
                .graph()
                .neighbours(i)
                .iter()
                .map(|&j| (q[j as usize], p[j as usize]));
            self.input(q[i], p[i], others)
        });
    }

    /// The heading mismatch n − ‖Σ_i p̂_i‖: the model decreases no energy.
    fn energy(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        heading_mismatch(&swarm.velocities, net.numbering())
    }

    fn diagnostics(
        &self,
        _t: f64,
        swarm: &Swarm<V>,
        net: &ProximityNet,
    ) -> Vec<(&'static str, f64)> {
        let [correlation, speed, collisions, wall] = self.order_parameters(swarm, net);
        vec![
            ("velocity_correlation", correlation),
            ("speed_ratio", speed),
            ("collision_ratio", collisions),
            ("wall_violation", wall),
        ]
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }
}

impl<V: Vector> LocalForm<V> for Vasarhelyi<V> {
    fn local_input(&self, _t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        let others = heard.iter().map(|o| (o.position, o.velocity));
        self.input(own.position, own.velocity, others)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn the_braking_curve_is_continuous_where_its_branches_meet() {
        let (a, p) = (4.16, 3.2);
        let knee = a / (p * p);
        let below = braking_curve(knee * (1.0 - 1e-12), a, p);
        let above = braking_curve(knee * (1.0 + 1e-12), a, p);
        assert!((below - a / p).abs() < 1e-9 && (above - a / p).abs() < 1e-9);
    }

    /// robotsim's `CalculatePreferredVelocity` stops the friction's braking curve at
    /// `R_0 + R_0_Offset_Frict`: within r_0^rep + r_0^frict = 110.3 m only the slack v^frict is
    /// allowed, so a velocity difference of 1 m/s is damped at 100 m (the curve at 100 − 85.3 m
    /// would allow 11 m/s) and not at 120 m (D(9.7 m) = 8.9 m/s allowed).
    #[test]
    fn the_friction_stops_at_r0_rep_plus_r0_frict_as_robotsim() {
        use glam::DVec2;
        let params = VasarhelyiParams {
            r_c: 200.0,
            arena_side: 1e6,
            ..VasarhelyiParams::default()
        };
        let model = Vasarhelyi::<DVec2>::new(params.clone()).unwrap();
        let (v_i, v_j) = (DVec2::new(6.0, 0.0), DVec2::new(6.0, 1.0));
        let across = |r: f64| {
            let others = [(DVec2::new(r, 0.0), v_j)];
            model
                .desired_velocity(DVec2::ZERO, v_i, others.into_iter())
                .y
        };
        let c = &params;
        let damped = c.c_frict * (1.0 - c.v_frict);
        assert!((across(100.0) - damped).abs() < 1e-12, "{}", across(100.0));
        assert!((across(110.0) - damped).abs() < 1e-12, "{}", across(110.0));
        assert_eq!(across(120.0), 0.0);
        assert!(braking_curve(120.0 - 110.3, c.a_frict, c.p_frict) > 1.0);
        assert!(braking_curve(100.0 - 85.3, c.a_frict, c.p_frict) > 1.0);
    }

    #[test]
    fn a_cube_arena_pushes_back_along_the_axis_left() {
        let params = VasarhelyiParams {
            arena_side: 100.0,
            ..VasarhelyiParams::default()
        };
        let model = Vasarhelyi::<DVec3>::new(params).unwrap();
        let arena = *model.arena();
        // above the lid, at rest: only the z shill acts, downwards at full v^shill
        let w = model.wall_term(DVec3::new(0.0, 0.0, 60.0), DVec3::ZERO);
        assert_eq!(w, DVec3::new(0.0, 0.0, -13.6));
        assert_eq!(arena.outside(DVec3::new(0.0, 0.0, 60.0)), 10.0);
    }
}
