//! The quadrotor: a rigid body on SE(3) lifted by four rotors, flown by the geometric tracking
//! controller of Lee, Leok and McClamroch ("Geometric tracking control of a quadrotor UAV on
//! SE(3)", IEEE CDC 2010, pp. 5420–5425; its long version arXiv:1003.2005, "Control of complex
//! maneuvers for a quadrotor UAV using geometric methods on SE(3)", carries the same controller
//! and its simulation parameters). The paper could not be read here, and its versions number
//! their equations differently, so the quantities below are cited by the names the paper gives
//! them (the model of its Section II, the tracking errors and controller of Section III), not by
//! equation number.
//!
//! # Model
//! The flock's coordinates are z-up (gravity g = 9.81 m s⁻² along −e3); Lee et al. write z down.
//! Everything here is z-up, so their signs of g e3 flip:
//! - ẋ = v, m v̇ = f R e3 − m g e3 + m d (d the external acceleration of
//!   [`Vehicle::advance`]'s `disturbance`);
//! - Ṙ = R Ω̂, with R stored as a unit quaternion q (q̇ = ½ q ⊗ (0, Ω));
//! - J Ω̇ + Ω × JΩ = M, J = diag(`inertia`) in the body frame.
//!
//! Four rotors in **X configuration** (body x forward, y left, z up), at arm length l on the
//! diagonals: rotor 1 front-left (a, a), 2 rear-left (−a, a), 3 rear-right (−a, −a),
//! 4 front-right (a, −a), a = l/√2. Rotor i gives thrust T_i = k_f ω_i² along b3 and the drag
//! torque s_i k_m ω_i² about b3, s = (+1, −1, +1, −1) (rotors 1 and 3 turn clockwise seen from
//! above). Hence f = Σ T_i, M = (a(T1 + T2 − T3 − T4), a(−T1 + T2 + T3 − T4),
//! (k_m/k_f)(T1 − T2 + T3 − T4)) ([`QuadrotorParams`]). Each motor follows its command with a
//! first-order lag ω̇_i = (ω_cmd,i − ω_i)/τ_m; commands lie in [ω_min, ω_max], so thrust is never
//! negative.
//!
//! # Controller (Lee et al. 2010, z-up)
//! - desired force F = −k_x e_x − k_v e_v + m g e3 + m ẍ_d, e_x = x − x_d, e_v = v − v_d
//!   (the bracket of the paper's thrust and b3_d with the sign of g e3 flipped);
//! - tilt limit: b3_d = F/‖F‖ is kept within `max_tilt` of e3; beyond it the force is replaced by
//!   one on the cone's edge that keeps F's vertical part (altitude first), or, when F points at
//!   or below the horizon, by F's projection on the cone's edge, never negative (the vehicle can
//!   only fall): the `at_tilt_limit` column;
//! - collective thrust f = F·R e3;
//! - b1_d: **the current heading** — the body x axis R e1 projected on the plane normal to b3_d
//!   (as the paper projects a desired heading b1_d onto that plane), so yaw is never commanded: a
//!   flock does not care where a quadrotor's nose points; R_d = [b2_d × b3_d, b2_d, b3_d] with
//!   b2_d = b3_d × b1_d / ‖·‖. Yaw is not held either: while the thrust axis turns, the heading
//!   turns about it by the solid angle that b3 sweeps (the geometric phase of a frame carried
//!   without spin about its axis): for a thrust axis tilted by α and circling at ω the heading
//!   turns at ω(1 − cos α), in the sense of the circling (the test
//!   `yaw_turns_with_the_solid_angle_the_thrust_axis_sweeps`);
//! - e_R = ½ (R_dᵀR − RᵀR_d)^∨, e_Ω = Ω − RᵀR_d Ω_d with **Ω_d = 0** (and
//!   Ω̇_d = 0): computing Ω_d needs the derivative of F, i.e. the jerk of the reference, and the
//!   held command has none; what remains is the drift term of e_x, e_v, which is small;
//! - M = −k_R e_R − k_Ω e_Ω + Ω × JΩ (the paper's moment with Ω_d = 0); with R_d fixed the
//!   attitude error is exponentially stable for Ψ(R(0), R_d(0)) = ½ tr(I − R_dᵀR(0)) < 2
//!   (rotation angle below 180°) with ‖e_Ω(0)‖ bounded (the paper's attitude-tracking result);
//!   near zero, with the motor lag τ_m, each axis is the loop J τ_m e⃛ + J ë + k_Ω ė + k_R e = 0
//!   and the error decays at its slow root (the test
//!   `attitude_error_decays_at_the_rate_of_the_linearised_loop`);
//! - the mixer inverts the rotor map for (f, M); when a rotor falls outside its range it first
//!   shifts the four thrusts alike (the moment kept, the thrust changed), then clips each
//!   ω_cmd,i² to [ω_min², ω_max²] (the `at_thrust_limit` column counts either).
//!
//! # The flock's command
//! The protocol's u enters as the feed-forward ẍ_d. At the start of every [`Vehicle::advance`]
//! the reference is reset to the vehicle's own state (x_d = x, v_d = v) and then integrated over
//! the step as a double integrator driven by the held u (x_d = x + v t + ½ u t², v_d = v + u t), so
//! e_x and e_v correct only the drift within one flock step; between steps the flock's protocol is
//! the position loop.
//!
//! # Integration
//! The controller runs at the inner step δ (default 1 ms) and holds its rotor commands over it
//! (zero-order hold). Over an inner step the motor lag is solved exactly,
//! ω_i(t) = ω_cmd,i + (ω_i(0) − ω_cmd,i) e^{−t/τ_m}, and (x, v, q, Ω) are advanced by the classical
//! fourth-order Runge–Kutta method with those rotor speeds at each stage time; q is renormalised
//! after every inner step. The rigid body's integration is of order 4 (the test
//! `free_rigid_body_conserves_energy_and_momentum_at_fourth_order` measures it).

use core::f64::consts::SQRT_2;

use glam::{DMat3, DQuat, DVec3};

use super::GRAVITY;
use super::{Vehicle, VehicleKind, inner_loop, inner_steps};
use flock_protocols::error::ParamError;

mod params;
#[cfg(test)]
mod tests;

pub use params::QuadrotorParams;

/// The names of a quadrotor's state columns (after its position and velocity).
const STATE_COLUMNS: [&str; 11] = [
    "attitude_w",
    "attitude_x",
    "attitude_y",
    "attitude_z",
    "angular_velocity_x",
    "angular_velocity_y",
    "angular_velocity_z",
    "rotor_speed_1",
    "rotor_speed_2",
    "rotor_speed_3",
    "rotor_speed_4",
];

/// The names of a quadrotor's limits.
const LIMIT_COLUMNS: [&str; 2] = ["at_thrust_limit", "at_tilt_limit"];

/// A quadrotor under Lee et al.'s geometric controller; see [the module](self).
///
/// # Example
/// ```
/// use flock_sim::Vehicle;
/// use flock_sim::vehicle::{Quadrotor, QuadrotorParams};
/// use glam::DVec3;
///
/// let quad = Quadrotor::new(QuadrotorParams::crazyflie()).unwrap();
/// let mut state = vec![0.0; quad.state_columns().len()];
/// let (mut q, mut p) = quad.start(DVec3::new(0.0, 0.0, 1.0), DVec3::ZERO, &mut state);
/// let mut limits = [false; 2];
/// quad.advance(0.01, DVec3::ZERO, DVec3::ZERO, &mut q, &mut p, &mut state, &mut limits);
/// assert!((q - DVec3::new(0.0, 0.0, 1.0)).length() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Quadrotor {
    params: QuadrotorParams,
}

impl Quadrotor {
    /// The quadrotor of `params`.
    ///
    /// # Errors
    /// As [`QuadrotorParams::validate`].
    pub fn new(params: QuadrotorParams) -> Result<Self, ParamError> {
        params.validate()?;
        Ok(Self { params })
    }

    /// Its parameters.
    #[must_use]
    pub fn params(&self) -> &QuadrotorParams {
        &self.params
    }
}

/// The rigid body's state: position, velocity, attitude (body to world) and body angular
/// velocity Ω. Also serves as its time derivative (q then a non-unit quaternion).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Body {
    x: DVec3,
    v: DVec3,
    q: DQuat,
    w: DVec3,
}

impl Body {
    /// `self + h k`, componentwise.
    fn plus(&self, k: &Body, h: f64) -> Body {
        Body {
            x: self.x + k.x * h,
            v: self.v + k.v * h,
            q: self.q + k.q * h,
            w: self.w + k.w * h,
        }
    }
}

/// The reference at an inner step's start: x_d, v_d and the feed-forward ẍ_d.
#[derive(Clone, Copy, Debug)]
struct Reference {
    x: DVec3,
    v: DVec3,
    a: DVec3,
}

/// What the controller decided at one inner step.
#[derive(Clone, Copy, Debug)]
struct Control {
    /// The rotor speed commands ω_cmd (rad/s), clipped.
    rotor_speeds: [f64; 4],
    /// The desired thrust direction b3_d after the tilt limit (read by the tests).
    #[cfg_attr(not(test), allow(dead_code))]
    axis: DVec3,
    /// A rotor command was clipped.
    thrust_limited: bool,
    /// The desired thrust direction was tilt-limited.
    tilt_limited: bool,
}

impl Quadrotor {
    /// Lee et al.'s desired force F = −k_x e_x − k_v e_v + m g e3 + m ẍ_d (z-up).
    fn desired_force(&self, body: &Body, reference: &Reference) -> DVec3 {
        let p = &self.params;
        -p.k_x * (body.x - reference.x) - p.k_v * (body.v - reference.v)
            + p.mass * (GRAVITY * DVec3::Z + reference.a)
    }

    /// The force pursued and its direction b3_d within `max_tilt` of e3, and whether the limit
    /// acted: beyond it the force keeps its vertical part on the cone's edge; a force pointing at
    /// or below the horizon becomes the cone's edge towards it with zero (or its projected,
    /// never negative) magnitude; a downward or zero force keeps b3_d = e3.
    fn limit_tilt(&self, force: DVec3) -> (DVec3, DVec3, bool) {
        let (sin, cos) = self.params.max_tilt.sin_cos();
        let length = force.length();
        if length == 0.0 {
            return (DVec3::ZERO, DVec3::Z, false);
        }
        if force.z >= length * cos {
            return (force, force / length, false);
        }
        let horizontal = DVec3::new(force.x, force.y, 0.0);
        let h = horizontal.length();
        if h == 0.0 {
            return (DVec3::ZERO, DVec3::Z, true);
        }
        let axis = horizontal / h * sin + DVec3::Z * cos;
        let pursued = if force.z > 0.0 {
            axis * (force.z / cos)
        } else {
            axis * force.dot(axis).max(0.0)
        };
        (pursued, axis, true)
    }

    /// Lee et al.'s moment M = −k_R e_R − k_Ω Ω + Ω × JΩ (with Ω_d = 0), e_R = ½ (R_dᵀR − RᵀR_d)^∨.
    fn attitude_moment(&self, r: DMat3, w: DVec3, r_d: DMat3) -> DVec3 {
        let p = &self.params;
        let e_r = 0.5 * vee(r_d.transpose() * r - r.transpose() * r_d);
        -p.k_r * e_r - p.k_omega * w + w.cross(p.inertia * w)
    }

    /// The rotor speed commands for thrust `f` and moment `m` (the inverse of the X rotor map),
    /// and whether the rotors' limits changed them. The moment comes first: when a rotor's
    /// thrust falls outside [k_f ω_min², k_f ω_max²] the four thrusts are shifted by one amount
    /// (which leaves M unchanged and changes f) into that interval, or centred on it when their
    /// spread exceeds it; then each ω_cmd² is clipped. Without the shift an upside-down vehicle
    /// (f = F·R e3 < 0) would have every rotor clipped to ω_min and no moment to right itself.
    fn mix(&self, f: f64, m: DVec3) -> ([f64; 4], bool) {
        let p = &self.params;
        let a = p.arm_length / SQRT_2;
        let c = p.drag_coefficient / p.thrust_coefficient;
        let (x, y, z) = (m.x / a, m.y / a, m.z / c);
        let thrusts = [f + x - y + z, f + x + y - z, f - x + y + z, f - x - y - z].map(|t| t / 4.0);
        let (lo, hi) = (
            p.thrust_coefficient * p.rotor_speed_min * p.rotor_speed_min,
            p.thrust_coefficient * p.rotor_speed_max * p.rotor_speed_max,
        );
        let least = thrusts.iter().copied().fold(f64::INFINITY, f64::min);
        let most = thrusts.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let shift = if most - least > hi - lo {
            0.5 * (lo + hi - least - most)
        } else if least < lo {
            lo - least
        } else if most > hi {
            hi - most
        } else {
            0.0
        };
        let mut clipped = shift != 0.0;
        let speeds = thrusts.map(|t| {
            let squared = (t + shift) / p.thrust_coefficient;
            let bounded = squared.clamp(p.rotor_speed_min.powi(2), p.rotor_speed_max.powi(2));
            clipped |= bounded != squared;
            bounded.sqrt()
        });
        (speeds, clipped)
    }

    /// The collective thrust f and the body moment M of rotor speeds ω (the X rotor map).
    fn rotor_wrench(&self, speeds: &[f64; 4]) -> (f64, DVec3) {
        let p = &self.params;
        let a = p.arm_length / SQRT_2;
        let sq = speeds.map(|w| w * w);
        let t = sq.map(|s| p.thrust_coefficient * s);
        let moment = DVec3::new(
            a * (t[0] + t[1] - t[2] - t[3]),
            a * (-t[0] + t[1] + t[2] - t[3]),
            p.drag_coefficient * (sq[0] - sq[1] + sq[2] - sq[3]),
        );
        (t.iter().sum(), moment)
    }

    /// The controller at one inner step: desired force, tilt limit, thrust f = F·R e3, R_d from
    /// b3_d and the current heading, the moment, the mixer.
    fn control(&self, body: &Body, reference: &Reference) -> Control {
        let r = DMat3::from_quat(body.q);
        let (force, axis, tilt_limited) = self.limit_tilt(self.desired_force(body, reference));
        let thrust = force.dot(r.z_axis);
        let moment = self.attitude_moment(r, body.w, desired_attitude(axis, r));
        let (rotor_speeds, thrust_limited) = self.mix(thrust, moment);
        Control {
            rotor_speeds,
            axis,
            thrust_limited,
            tilt_limited,
        }
    }

    /// One inner step `dt`: the controller, then the motors (exactly) and the rigid body (RK4)
    /// under the external acceleration `disturbance`.
    fn inner_step(
        &self,
        body: &mut Body,
        speeds: &mut [f64; 4],
        reference: &Reference,
        disturbance: DVec3,
        dt: f64,
    ) -> Control {
        let p = &self.params;
        let control = self.control(body, reference);
        let (start, command) = (*speeds, control.rotor_speeds);
        let at = |t: f64| -> [f64; 4] {
            core::array::from_fn(|i| motor_response(start[i], command[i], t, p.motor_time_constant))
        };
        let external = disturbance - GRAVITY * DVec3::Z;
        *body = rk4_step(body, dt, p.inertia, external, |t| {
            let (f, m) = self.rotor_wrench(&at(t));
            (f / p.mass, m)
        });
        *speeds = at(dt);
        control
    }

    /// A flock step `h` under the held `command`: the reference reset to the body's state and
    /// integrated as a double integrator, then the inner steps; `observe` sees the body after and
    /// the control of each inner step.
    fn fly(
        &self,
        h: f64,
        command: DVec3,
        disturbance: DVec3,
        body: &mut Body,
        speeds: &mut [f64; 4],
        mut observe: impl FnMut(&Body, &Control),
    ) {
        let n = inner_steps(h, self.params.inner_step);
        if n == 0 {
            return;
        }
        let dt = h / n as f64;
        let (x0, v0) = (body.x, body.v);
        for k in inner_loop(n) {
            let t = k as f64 * dt;
            let reference = Reference {
                x: x0 + v0 * t + command * (0.5 * t * t),
                v: v0 + command * t,
                a: command,
            };
            let control = self.inner_step(body, speeds, &reference, disturbance, dt);
            observe(body, &control);
        }
    }
}

/// The rotation matrix's skew part as a vector: S^∨ = (S₃₂, S₁₃, S₂₁).
#[inline]
#[must_use]
fn vee(s: DMat3) -> DVec3 {
    DVec3::new(s.y_axis.z, s.z_axis.x, s.x_axis.y)
}

/// R_d = [b2 × b3, b2, b3] with b2 = b3 × b1_d / ‖·‖ and b1_d = R e1, the current heading
/// (its first column the projection of R e1 on the plane normal to b3, as Lee et al. project a
/// desired heading).
/// When R e1 is along b3 the heading is R e2's projection instead.
fn desired_attitude(b3: DVec3, r: DMat3) -> DMat3 {
    let b2 = b3.cross(r.x_axis);
    let b2 = if b2.length_squared() > 1e-18 {
        b2.normalize()
    } else {
        (r.y_axis - b3 * b3.dot(r.y_axis)).normalize()
    };
    DMat3::from_cols(b2.cross(b3), b2, b3)
}

/// The motor's speed after `t` from `start` under the held `command`, time constant `tau`:
/// the exact solution of ω̇ = (ω_cmd − ω)/τ.
#[inline]
#[must_use]
fn motor_response(start: f64, command: f64, t: f64, tau: f64) -> f64 {
    command + (start - command) * (-t / tau).exp()
}

/// The rigid body's time derivative: ẋ = v, v̇ = (f/m) R e3 + a_ext, q̇ = ½ q ⊗ (0, Ω),
/// Ω̇ = J⁻¹(M − Ω × JΩ), with `specific_thrust` f/m and `moment` M.
fn rate(body: &Body, inertia: DVec3, external: DVec3, specific_thrust: f64, moment: DVec3) -> Body {
    let w = body.w;
    Body {
        x: body.v,
        v: body.q.normalize() * DVec3::Z * specific_thrust + external,
        q: body.q * DQuat::from_xyzw(w.x, w.y, w.z, 0.0) * 0.5,
        w: (moment - w.cross(inertia * w)) / inertia,
    }
}

/// One classical Runge–Kutta step (order 4) of `dt` for the rigid body with principal inertia
/// `inertia`, the world-frame acceleration `external` (gravity, disturbance) and the rotors'
/// `input(t)` = (f/m, M) at time t within the step; q renormalised at the end.
fn rk4_step(
    body: &Body,
    dt: f64,
    inertia: DVec3,
    external: DVec3,
    input: impl Fn(f64) -> (f64, DVec3),
) -> Body {
    let f = |b: &Body, t: f64| {
        let (thrust, moment) = input(t);
        rate(b, inertia, external, thrust, moment)
    };
    let k1 = f(body, 0.0);
    let k2 = f(&body.plus(&k1, 0.5 * dt), 0.5 * dt);
    let k3 = f(&body.plus(&k2, 0.5 * dt), 0.5 * dt);
    let k4 = f(&body.plus(&k3, dt), dt);
    let sum = Body {
        x: k1.x + 2.0 * (k2.x + k3.x) + k4.x,
        v: k1.v + 2.0 * (k2.v + k3.v) + k4.v,
        q: k1.q + (k2.q + k3.q) * 2.0 + k4.q,
        w: k1.w + 2.0 * (k2.w + k3.w) + k4.w,
    };
    let mut next = body.plus(&sum, dt / 6.0);
    next.q = next.q.normalize();
    next
}

/// The attitude of a state slice (identity when it is not a usable quaternion).
fn read_attitude(state: &[f64]) -> DQuat {
    let q = DQuat::from_xyzw(state[1], state[2], state[3], state[0]);
    let n = q.length();
    if n.is_finite() && n > 0.0 {
        q / n
    } else {
        DQuat::IDENTITY
    }
}

/// Writes attitude, angular velocity and rotor speeds into a state slice.
fn write_state(state: &mut [f64], q: DQuat, w: DVec3, speeds: &[f64; 4]) {
    state[..4].copy_from_slice(&[q.w, q.x, q.y, q.z]);
    state[4..7].copy_from_slice(&w.to_array());
    state[7..11].copy_from_slice(speeds);
}

impl VehicleKind for Quadrotor {
    fn name(&self) -> &'static str {
        "Quadrotor"
    }

    fn validate(&self) -> Result<(), ParamError> {
        self.params.validate()
    }

    fn inner_step(&self) -> f64 {
        self.params.inner_step
    }

    fn takes_disturbance(&self) -> bool {
        true
    }
}

impl Vehicle<DVec3> for Quadrotor {
    fn state_columns(&self) -> &'static [&'static str] {
        &STATE_COLUMNS
    }

    fn limit_columns(&self) -> &'static [&'static str] {
        &LIMIT_COLUMNS
    }

    /// Hover at `q` moving with `p`: level attitude (body axes along the world's), Ω = 0, every
    /// rotor at the hover speed √(m g / (4 k_f)).
    fn start(&self, q: DVec3, p: DVec3, state: &mut [f64]) -> (DVec3, DVec3) {
        let hover = self.params.hover_speed();
        write_state(state, DQuat::IDENTITY, DVec3::ZERO, &[hover; 4]);
        (q, p)
    }

    fn advance(
        &self,
        h: f64,
        command: DVec3,
        disturbance: DVec3,
        q: &mut DVec3,
        p: &mut DVec3,
        state: &mut [f64],
        limits: &mut [bool],
    ) {
        let mut body = Body {
            x: *q,
            v: *p,
            q: read_attitude(state),
            w: DVec3::new(state[4], state[5], state[6]),
        };
        let mut speeds = [state[7], state[8], state[9], state[10]];
        self.fly(
            h,
            command,
            disturbance,
            &mut body,
            &mut speeds,
            |_, control| {
                limits[0] |= control.thrust_limited;
                limits[1] |= control.tilt_limited;
            },
        );
        *q = body.x;
        *p = body.v;
        write_state(state, body.q, body.w, &speeds);
    }

    /// The body x axis R e1 (not projected on the horizontal plane: it tilts with the vehicle).
    fn heading(&self, _p: DVec3, state: &[f64]) -> DVec3 {
        read_attitude(state) * DVec3::X
    }
}
