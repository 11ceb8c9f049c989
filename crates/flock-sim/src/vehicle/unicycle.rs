//! The kinematic unicycle (a differential-drive ground robot) flocking through the handle ahead
//! of its axle.
//!
//! The robot's axle midpoint x moves along its heading θ, ẋ = v e(θ), θ̇ = ω, with
//! e(θ) = (cos θ, sin θ), e⊥(θ) = (−sin θ, cos θ), |v| ≤ v_max, |ω| ≤ ω_max and, with a track
//! width b, each wheel's ground speed v ± ω b/2 at most w_max. The flock sees the *handle*
//! q = x + ℓ e(θ), a point at distance ℓ ahead of the axle, whose velocity
//! p = v e + ℓ ω e⊥ is an invertible function of (v, ω): v = e·p, ω = e⊥·p / ℓ. The handle is
//! therefore fully actuated — the feedback linearisation at a point ahead used for formations of
//! unicycles by Lawton, Beard & Young ("A decentralized approach to formation maneuvers", IEEE
//! T-RA 19(6), 2003, the robot's "hand position"; not re-read here), by the Robotarium's
//! single-integrator-to-unicycle map (`robotarium/robotarium-matlab-simulator`,
//! `utilities/transformations/create_si_to_uni_mapping.m`, its `ProjectionDistance`) and by
//! TUHH's multi-agent simulation library for flocking unicycles
//! (`TUHH-ICS/MAS-Simulation`, `lib/agents/models/DynamicUnicycle.m`: "unicycle with handle",
//! q̇ = v e + d ω e⊥ with d the handle's length, Euler-discretised).

use glam::DVec2;

use super::{Vehicle, VehicleKind, inner_loop, inner_steps};
use flock_protocols::error::{ParamError, check};

/// The unicycle's parameters. Defaults are ROBOTIS's TurtleBot3 Burger: maximum translational
/// velocity 0.22 m/s and rotational velocity 2.84 rad/s (ROBOTIS e-manual, TurtleBot3
/// *Specifications*, `ROBOTIS-GIT/emanual`, `docs/en/platform/turtlebot3/specifications.md`), wheel
/// separation 0.160 m (the wheels at y = ±0.08 m in ROBOTIS's Gazebo model
/// `turtlebot3_simulations/turtlebot3_gazebo/models/turtlebot3_burger/model.sdf`, and
/// `WHEEL_SEPARATION … BURGER : 0.160` in the OpenCR firmware headers). The wheel-speed limit
/// 0.22 m/s is our reading: each wheel at the robot's straight-line top speed (the firmware
/// writes it as 61 rpm × 2π × 0.033 m ≈ 0.21 m/s; the e-manual's 2.84 rad/s is ≈ 0.227 m/s /
/// 0.08 m, the same wheel speed spun in place). The handle ℓ = 0.08 m (half the track, the
/// firmware's `TURNING_RADIUS`) is our choice: it makes the handle's sideways speed limit
/// ℓ ω_max ≈ 0.227 m/s match the forward one. The inner step 10 ms is our choice.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields, default)
)]
pub struct UnicycleParams {
    /// The handle's distance ℓ > 0 (m) ahead of the axle: the flock's reference point.
    pub handle: f64,
    /// The largest forward or backward speed v_max > 0 (m/s) of the axle.
    pub max_speed: f64,
    /// The largest turn rate ω_max > 0 (rad/s).
    pub max_turn_rate: f64,
    /// The track width b > 0 (m), the distance between the wheels; `None`: no wheel limit.
    pub track_width: Option<f64>,
    /// The largest ground speed w_max > 0 (m/s) of each wheel, v ± ω b/2; needs `track_width`.
    pub max_wheel_speed: Option<f64>,
    /// The inner step δ > 0 (s).
    pub inner_step: f64,
}

impl Default for UnicycleParams {
    fn default() -> Self {
        Self {
            handle: 0.08,
            max_speed: 0.22,
            max_turn_rate: 2.84,
            track_width: Some(0.160),
            max_wheel_speed: Some(0.22),
            inner_step: 0.01,
        }
    }
}

impl UnicycleParams {
    /// Checks every parameter: ℓ a length, v_max, ω_max, δ positive, b and w_max positive when
    /// given, w_max only with b.
    ///
    /// # Errors
    /// The first parameter outside its domain, named by its field (`handle`, `max_speed`,
    /// `max_turn_rate`, `track_width`, `max_wheel_speed`, `inner_step`).
    pub fn validate(&self) -> Result<(), ParamError> {
        check::length("handle", self.handle)?;
        check::positive("max_speed", self.max_speed)?;
        check::positive("max_turn_rate", self.max_turn_rate)?;
        if let Some(b) = self.track_width {
            check::length("track_width", b)?;
        }
        if let Some(w) = self.max_wheel_speed {
            check::positive("max_wheel_speed", w)?;
            check::require(
                self.track_width.is_some(),
                "max_wheel_speed",
                w,
                "a wheel-speed limit needs the track width b (the wheels turn at v ± ω b/2)",
                "give track_width too (e.g. 0.160 for a TurtleBot3 Burger) or remove max_wheel_speed",
            )?;
        }
        check::positive("inner_step", self.inner_step)
    }
}

/// The state columns: heading θ (rad), axle speed v (m/s), turn rate ω (rad/s).
const STATE: &[&str] = &["heading", "speed", "turn_rate"];

/// The limit columns, in the order of [`Limits`]' fields.
const LIMITS: &[&str] = &["at_speed_limit", "at_turn_rate_limit", "at_wheel_limit"];

/// The kinematic unicycle driven through its handle (module docs): per inner step δ the handle's
/// desired velocity p_des = p + δ a, the inputs (v, ω) = (e·p_des, e⊥·p_des / ℓ), saturated,
/// p = v e + ℓ ω e⊥, q ← q + δ p, θ ← θ + δ ω (the axle is q − ℓ e(θ)).
///
/// **Without saturation** p is p_des itself (v e + ℓ ω e⊥ equals it up to the rotation's
/// round-off, so the identity is not recomputed), and the handle is exactly the flock's double
/// integrator under symplectic Euler, p ← p + δ u, q ← q + δ p, bit for bit.
///
/// **Saturation** scales (v, ω) by the largest s ∈ (0, 1] that meets every limit
/// ([`Unicycle::feasible_scale`]), rather than clipping v and ω each. Both limits are on a
/// linear image of the handle's velocity, so scaling keeps p along p_des: the handle goes where
/// the protocol asked, only slower, and a saturated turn does not also swing the handle's
/// direction (clipping ω alone while keeping v rotates p towards e; clipping v alone rotates it
/// towards e⊥). The feasible set is a convex polygon symmetric about 0, so the scaled input lies
/// on its boundary.
/// Reversing (v < 0) is allowed, as a differential drive can.
///
/// The heading θ is kept in (−π, π].
#[derive(Clone, Debug, PartialEq)]
pub struct Unicycle {
    params: UnicycleParams,
}

impl Unicycle {
    /// The unicycle of `params`.
    ///
    /// # Errors
    /// As [`UnicycleParams::validate`].
    pub fn new(params: UnicycleParams) -> Result<Self, ParamError> {
        params.validate()?;
        Ok(Self { params })
    }

    /// Its parameters.
    #[must_use]
    pub fn params(&self) -> &UnicycleParams {
        &self.params
    }

    /// The axle midpoint x = q − ℓ e(θ) of the handle at `q` with heading `heading`.
    #[must_use]
    pub fn axle(&self, q: DVec2, heading: f64) -> DVec2 {
        q - forward(heading) * self.params.handle
    }

    /// One inner step of length `delta` under `command`: advances the handle (`q`, `p`), the
    /// heading `theta` and returns the inputs (v, ω) applied and the limits hit.
    fn step_once(
        &self,
        delta: f64,
        command: DVec2,
        q: &mut DVec2,
        p: &mut DVec2,
        theta: &mut f64,
    ) -> (f64, f64, Limits) {
        let l = self.params.handle;
        let (e, e_perp) = (forward(*theta), forward(*theta).perp());
        let desired = *p + command * delta;
        let (v, omega) = (e.dot(desired), e_perp.dot(desired) / l);
        let hit = self.limits_hit(v, omega);
        let (v, omega) = if hit.any() {
            let s = self.feasible_scale(v, omega);
            let (v, omega) = (v * s, omega * s);
            *p = e * v + e_perp * (l * omega);
            (v, omega)
        } else {
            *p = desired;
            (v, omega)
        };
        *q += *p * delta;
        *theta = wrap_angle(*theta + omega * delta);
        (v, omega, hit)
    }

    /// Which limits the inputs (v, ω) exceed.
    fn limits_hit(&self, v: f64, omega: f64) -> Limits {
        let wheel = self.wheel_limit().is_some_and(|(half_track, w_max)| {
            (v + omega * half_track).abs() > w_max || (v - omega * half_track).abs() > w_max
        });
        Limits {
            speed: v.abs() > self.params.max_speed,
            turn_rate: omega.abs() > self.params.max_turn_rate,
            wheel,
        }
    }

    /// The largest s ∈ (0, 1] with s (v, ω) within every limit: the minimum over the limits of
    /// bound / |value| (1 where a value is within its bound).
    #[must_use]
    pub fn feasible_scale(&self, v: f64, omega: f64) -> f64 {
        let ratio = |value: f64, bound: f64| {
            if value.abs() > bound {
                bound / value.abs()
            } else {
                1.0
            }
        };
        let mut s = ratio(v, self.params.max_speed).min(ratio(omega, self.params.max_turn_rate));
        if let Some((half_track, w_max)) = self.wheel_limit() {
            s = s
                .min(ratio(v + omega * half_track, w_max))
                .min(ratio(v - omega * half_track, w_max));
        }
        s
    }

    /// Half the track width and the wheel-speed limit, when both are given.
    fn wheel_limit(&self) -> Option<(f64, f64)> {
        Some((self.params.track_width? / 2.0, self.params.max_wheel_speed?))
    }
}

/// The limits hit in one inner step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Limits {
    speed: bool,
    turn_rate: bool,
    wheel: bool,
}

impl Limits {
    fn any(self) -> bool {
        self.speed || self.turn_rate || self.wheel
    }

    /// Sets (never clears) the flags of `limits`, in the order of [`LIMITS`].
    fn record(self, limits: &mut [bool]) {
        for (flag, hit) in limits
            .iter_mut()
            .zip([self.speed, self.turn_rate, self.wheel])
        {
            *flag |= hit;
        }
    }
}

impl VehicleKind for Unicycle {
    fn name(&self) -> &'static str {
        "Unicycle"
    }

    fn validate(&self) -> Result<(), ParamError> {
        self.params.validate()
    }

    fn inner_step(&self) -> f64 {
        self.params.inner_step
    }

    /// False: the wheels roll without slipping, so nothing but (v, ω) moves the robot.
    fn takes_disturbance(&self) -> bool {
        false
    }
}

impl Vehicle<DVec2> for Unicycle {
    fn state_columns(&self) -> &'static [&'static str] {
        STATE
    }

    fn limit_columns(&self) -> &'static [&'static str] {
        LIMITS
    }

    /// Heading along `p` (0 when `p` is zero), turning rate 0 and speed |p| scaled into the
    /// limits: the handle's velocity is v e(θ).
    fn start(&self, q: DVec2, p: DVec2, state: &mut [f64]) -> (DVec2, DVec2) {
        let theta = if p == DVec2::ZERO {
            0.0
        } else {
            p.y.atan2(p.x)
        };
        let speed = p.length();
        let v = speed * self.feasible_scale(speed, 0.0);
        state.copy_from_slice(&[theta, v, 0.0]);
        (q, forward(theta) * v)
    }

    fn advance(
        &self,
        h: f64,
        command: DVec2,
        _disturbance: DVec2,
        q: &mut DVec2,
        p: &mut DVec2,
        state: &mut [f64],
        limits: &mut [bool],
    ) {
        let delta = self.params.inner_step;
        let mut theta = state[0];
        for _ in inner_loop(inner_steps(h, delta)) {
            let (v, omega, hit) = self.step_once(delta, command, q, p, &mut theta);
            state[1] = v;
            state[2] = omega;
            hit.record(limits);
        }
        state[0] = theta;
    }

    fn heading(&self, _p: DVec2, state: &[f64]) -> DVec2 {
        forward(state[0])
    }
}

/// The unit vector e(θ) = (cos θ, sin θ).
#[inline]
#[must_use]
fn forward(theta: f64) -> DVec2 {
    let (sin, cos) = theta.sin_cos();
    DVec2::new(cos, sin)
}

/// `angle` brought into (−π, π].
#[inline]
#[must_use]
pub(crate) fn wrap_angle(angle: f64) -> f64 {
    use core::f64::consts::{PI, TAU};
    let wrapped = (angle + PI).rem_euclid(TAU) - PI;
    if wrapped == -PI { PI } else { wrapped }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    /// Limits no command of the tests reaches.
    fn unbounded() -> Unicycle {
        Unicycle::new(UnicycleParams {
            max_speed: 1e9,
            max_turn_rate: 1e9,
            track_width: None,
            max_wheel_speed: None,
            ..UnicycleParams::default()
        })
        .unwrap()
    }

    fn started(robot: &Unicycle, q: DVec2, p: DVec2) -> (DVec2, DVec2, [f64; 3]) {
        let mut state = [0.0; 3];
        let (q, p) = robot.start(q, p, &mut state);
        (q, p, state)
    }

    #[test]
    fn one_unsaturated_step_is_the_point_mass_bit_for_bit() {
        let robot = unbounded();
        let h = robot.params().inner_step;
        let (mut q, mut p, mut state) =
            started(&robot, DVec2::new(0.3, -1.2), DVec2::new(0.1, 0.05));
        let (q0, p0, u) = (q, p, DVec2::new(-0.7, 0.4));
        let mut limits = [false; 3];
        robot.advance(h, u, DVec2::ZERO, &mut q, &mut p, &mut state, &mut limits);
        let p1 = p0 + u * h;
        assert_eq!(p, p1);
        assert_eq!(q, q0 + p1 * h);
        assert_eq!(limits, [false; 3]);
    }

    #[test]
    fn unsaturated_handle_is_the_double_integrator_over_1000_inner_steps() {
        let robot = unbounded();
        let delta = robot.params().inner_step;
        let (mut q, mut p, mut state) = started(&robot, DVec2::ZERO, DVec2::new(0.2, 0.0));
        let (mut q_ref, mut p_ref) = (q, p);
        let mut limits = [false; 3];
        for k in 0..1000 {
            let t = k as f64 * delta;
            let u = DVec2::new((1.3 * t).sin(), (0.7 * t).cos() - 0.5);
            robot.advance(
                delta,
                u,
                DVec2::ZERO,
                &mut q,
                &mut p,
                &mut state,
                &mut limits,
            );
            p_ref += u * delta;
            q_ref += p_ref * delta;
        }
        assert_eq!(p, p_ref);
        assert_eq!(q, q_ref);
        assert_eq!(limits, [false; 3]);
        // the robot did turn: the exactness is not that of a straight line
        assert!(state[0].abs() > 0.1, "heading {}", state[0]);
    }

    #[test]
    fn the_rotation_round_trip_is_within_round_off() {
        // p = (e·p) e + (e⊥·p) e⊥, the identity the unsaturated step skips
        for k in 0..100 {
            let theta = 0.37 * k as f64;
            let (e, e_perp) = (forward(theta), forward(theta).perp());
            let p = DVec2::new(0.3 - 0.01 * k as f64, 0.17);
            let back = e * e.dot(p) + e_perp * e_perp.dot(p);
            assert_relative_eq!(back, p, max_relative = 1e-12);
        }
    }

    #[test]
    fn axle_is_behind_the_handle_and_rolls_without_slipping() {
        let robot = Unicycle::new(UnicycleParams::default()).unwrap();
        let l = robot.params().handle;
        let delta = robot.params().inner_step;
        let (mut q, mut p, mut state) = started(&robot, DVec2::ZERO, DVec2::new(0.1, 0.0));
        let mut limits = [false; 3];
        for k in 0..500 {
            let u = DVec2::new(-0.3, (0.05 * k as f64).sin()) * 2.0;
            let (theta0, x0) = (state[0], robot.axle(q, state[0]));
            robot.advance(
                delta,
                u,
                DVec2::ZERO,
                &mut q,
                &mut p,
                &mut state,
                &mut limits,
            );
            let x1 = robot.axle(q, state[0]);
            assert_relative_eq!(q.distance(x1), l, max_relative = 1e-12);
            // the axle moves along its heading at the step's start (Euler on ẋ = v e(θ)): its
            // sideways slip ℓ (δω − sin δω) is third order in δ
            let sideways = forward(theta0).perp().dot(x1 - x0);
            let bound = l * (delta * robot.params().max_turn_rate).powi(3) / 6.0 + 1e-15;
            assert!(sideways.abs() <= bound, "slip {sideways} at step {k}");
        }
    }

    /// One saturated run: every inner step's (v, ω) within the limits.
    fn check_limits(robot: &Unicycle, commands: &[(f64, f64)]) -> [bool; 3] {
        let par = *robot.params();
        let (mut q, mut p, mut state) = started(robot, DVec2::ZERO, DVec2::new(0.1, 0.1));
        let mut limits = [false; 3];
        for &(x, y) in commands {
            robot.advance(
                par.inner_step,
                DVec2::new(x, y),
                DVec2::ZERO,
                &mut q,
                &mut p,
                &mut state,
                &mut limits,
            );
            let (v, omega) = (state[1], state[2]);
            let slack = 1.0 + 1e-12;
            assert!(v.abs() <= par.max_speed * slack, "v = {v}");
            assert!(omega.abs() <= par.max_turn_rate * slack, "ω = {omega}");
            if let (Some(b), Some(w)) = (par.track_width, par.max_wheel_speed) {
                for wheel in [v + omega * b / 2.0, v - omega * b / 2.0] {
                    assert!(wheel.abs() <= w * slack, "wheel {wheel}");
                }
            }
        }
        limits
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn saturated_inputs_stay_within_the_limits(
            commands in prop::collection::vec((-50.0..50.0f64, -50.0..50.0f64), 1..200),
            wheels in any::<bool>(),
        ) {
            let params = UnicycleParams {
                track_width: wheels.then_some(0.160),
                max_wheel_speed: wheels.then_some(0.20),
                ..UnicycleParams::default()
            };
            check_limits(&Unicycle::new(params).unwrap(), &commands);
        }
    }

    #[test]
    fn each_limit_is_reported() {
        let robot = Unicycle::new(UnicycleParams {
            max_wheel_speed: Some(0.2),
            ..UnicycleParams::default()
        })
        .unwrap();
        // straight ahead (the start heads along (1, 1)), hard: the speed and the wheels
        // saturate, the turn rate does not
        let hits = check_limits(&robot, &[(100.0, 100.0); 10]);
        assert_eq!(hits, [true, false, true]);
        // hard sideways: the turn rate saturates
        let hits = check_limits(&robot, &[(-100.0, 100.0); 3]);
        assert!(hits[1]);
        let unlimited_wheels = Unicycle::new(UnicycleParams {
            track_width: None,
            max_wheel_speed: None,
            ..UnicycleParams::default()
        })
        .unwrap();
        let hits = check_limits(&unlimited_wheels, &[(100.0, 100.0), (-100.0, 100.0)]);
        assert_eq!(hits[..2], [true, true]);
        assert!(!hits[2], "no track width, no wheel limit");
    }

    #[test]
    fn saturation_keeps_the_handle_velocity_direction() {
        let robot = Unicycle::new(UnicycleParams::default()).unwrap();
        let delta = robot.params().inner_step;
        let (mut q, mut p, mut state) = started(&robot, DVec2::ZERO, DVec2::new(0.1, 0.0));
        let p0 = p;
        let u = DVec2::new(3.0, 40.0);
        let mut limits = [false; 3];
        robot.advance(
            delta,
            u,
            DVec2::ZERO,
            &mut q,
            &mut p,
            &mut state,
            &mut limits,
        );
        assert!(limits.iter().any(|&hit| hit));
        let desired = p0 + u * delta;
        assert_relative_eq!(p.normalize(), desired.normalize(), max_relative = 1e-12);
        assert!(p.length() < desired.length());
    }

    #[test]
    fn start_points_along_p_within_the_limits() {
        let robot = Unicycle::new(UnicycleParams::default()).unwrap();
        let (_, p, state) = started(&robot, DVec2::ZERO, DVec2::new(0.0, -3.0));
        assert_relative_eq!(state[0], -core::f64::consts::FRAC_PI_2);
        assert_relative_eq!(p, DVec2::new(0.0, -0.22), epsilon = 1e-15);
        assert_eq!(state[1..], [0.22, 0.0]);
        let (_, p, state) = started(&robot, DVec2::ZERO, DVec2::ZERO);
        assert_eq!((p, state), (DVec2::ZERO, [0.0; 3]));
        assert_eq!(robot.heading(p, &state), DVec2::X);
    }

    #[test]
    fn wrap_angle_lands_in_minus_pi_to_pi() {
        use core::f64::consts::PI;
        assert_relative_eq!(wrap_angle(3.0 * PI / 2.0), -PI / 2.0);
        assert_relative_eq!(wrap_angle(-3.0 * PI / 2.0), PI / 2.0);
        assert_eq!(wrap_angle(-PI), PI);
        assert_eq!(wrap_angle(0.5), 0.5);
    }

    #[test]
    fn validation_names_the_field() {
        let error = |params: UnicycleParams| params.validate().unwrap_err().field;
        let base = UnicycleParams::default();
        assert_eq!(
            error(UnicycleParams {
                handle: -0.1,
                ..base
            }),
            "handle"
        );
        assert_eq!(
            error(UnicycleParams {
                max_speed: 0.0,
                ..base
            }),
            "max_speed"
        );
        assert_eq!(
            error(UnicycleParams {
                max_turn_rate: f64::NAN,
                ..base
            }),
            "max_turn_rate"
        );
        assert_eq!(
            error(UnicycleParams {
                track_width: Some(-1.0),
                ..base
            }),
            "track_width"
        );
        assert_eq!(
            error(UnicycleParams {
                max_wheel_speed: Some(0.0),
                ..base
            }),
            "max_wheel_speed"
        );
        assert_eq!(
            error(UnicycleParams {
                track_width: None,
                ..base
            }),
            "max_wheel_speed"
        );
        assert_eq!(
            error(UnicycleParams {
                inner_step: 0.0,
                ..base
            }),
            "inner_step"
        );
        assert!(base.validate().is_ok());
        assert!(
            Unicycle::new(UnicycleParams {
                handle: -0.1,
                ..base
            })
            .is_err()
        );
    }
}
