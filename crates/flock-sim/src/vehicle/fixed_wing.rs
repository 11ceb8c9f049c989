//! The fixed-wing aircraft as a guidance model of Beard & McLain, *Small Unmanned Aircraft:
//! Theory and Practice* (Princeton University Press, 2012), chapter 9: the closed loop of the
//! aircraft and its autopilot seen as first-order responses of airspeed, bank and flight-path
//! angle to their commands, and the coordinated turn.
//!
//! In still air (zero wind: airspeed = ground speed, heading = course, γ_a = γ), with the
//! position q, altitude z (up), airspeed V, course χ (from +x, counter-clockwise), bank φ and
//! flight-path angle γ:
//!
//! - q̇ = V (cos χ cos γ, sin χ cos γ, sin γ),
//! - V̇ = b_V (V_c − V), the autopilot's airspeed hold,
//! - χ̇ = (g / V) tan φ, the coordinated turn,
//! - φ̇ = b_φ (φ_c − φ), the roll loop,
//! - γ̇ = b_γ (γ_c − γ), the flight-path loop.
//!
//! The book gives its guidance models in chapter 9, in several forms (course or roll as the
//! lateral command, altitude or flight-path angle as the longitudinal one); this is the form with
//! roll and flight-path angle. The book itself could not be read here, so no equation number is
//! cited (the book's own course files, randybeard/mavsim_public, refer to "the guidance model
//! given in equation (9.18)" without saying which form that is). The same equations, wind
//! included, are in the public `alfiduhri/ThesisProject` `DynamicsModel.m` "Model for Guidance",
//! and MathWorks' UAV Toolbox `fixedwing` guidance model cites the book for them. b = 1/τ with
//! the time constants of [`FixedWingParams`]. In the plane γ = 0 throughout.

use core::f64::consts::FRAC_PI_2;

use glam::{DVec2, DVec3};

use super::GRAVITY;
use super::unicycle::wrap_angle;
use super::{Vehicle, VehicleKind, inner_loop, inner_steps};
use flock_protocols::error::{ParamError, check};

/// The fixed wing's parameters (SI units, angles in radians). Defaults: Beard & McLain's
/// Aerosonde, whose trim airspeed V_a0 = 25 m/s lies in [`min_airspeed`, `max_airspeed`]
/// = [18, 32] m/s (V_a0 = `u0` = 25 m/s in the book's simulation parameters,
/// randybeard/mavsim_public `mavsim_python/parameters/aerosonde_parameters.py`, commit a514cf1;
/// the envelope 18–32 m/s is the Aerosonde's commonly quoted speed range, not confirmed here).
/// The bank limit 30° is the roll command the book's autopilot gives at most: its course loop
/// saturates its roll command at `np.radians(30)` (`mavsim_python/controllers/autopilot.py`,
/// `course_from_roll`; the 45° beside it is the aileron deflection's limit, `roll_from_aileron`,
/// and the book's path planner assumes 25°, `planner_parameters.py`). The time constants
/// τ_φ = 0.5 s, τ_V = 2 s, τ_γ = 1 s and the flight-path limit 15° are our choices for a small
/// UAV's autopilot, not a source's: the book leaves b_φ, b_V, b_γ to be fitted to the autopilot
/// at hand.
///
/// [`min_airspeed`]: FixedWingParams::min_airspeed
/// [`max_airspeed`]: FixedWingParams::max_airspeed
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields, default)
)]
pub struct FixedWingParams {
    /// The stall speed V_min > 0 (m/s): the least airspeed.
    pub min_airspeed: f64,
    /// The greatest airspeed V_max ≥ V_min (m/s).
    pub max_airspeed: f64,
    /// The bank limit φ_max ∈ (0, π/2) (rad).
    pub max_bank: f64,
    /// The roll loop's time constant τ_φ = 1/b_φ > 0 (s).
    pub bank_time_constant: f64,
    /// The airspeed loop's time constant τ_V = 1/b_V > 0 (s).
    pub airspeed_time_constant: f64,
    /// The flight-path limit γ_max ∈ (0, π/2) (rad); 3D only.
    pub max_flight_path: f64,
    /// The flight-path loop's time constant τ_γ = 1/b_γ > 0 (s); 3D only.
    pub flight_path_time_constant: f64,
    /// The inner step δ (s), at most the shortest time constant.
    pub inner_step: f64,
}

impl Default for FixedWingParams {
    fn default() -> Self {
        Self {
            min_airspeed: 18.0,
            max_airspeed: 32.0,
            max_bank: 30f64.to_radians(),
            bank_time_constant: 0.5,
            airspeed_time_constant: 2.0,
            max_flight_path: 15f64.to_radians(),
            flight_path_time_constant: 1.0,
            inner_step: 0.01,
        }
    }
}

impl FixedWingParams {
    /// Checks every parameter: speeds positive with V_min ≤ V_max, the angle limits in
    /// (0, π/2), the time constants positive, δ positive and at most the shortest time constant.
    ///
    /// # Errors
    /// The first parameter outside its domain, named by its field.
    pub fn validate(&self) -> Result<(), ParamError> {
        check::positive("min_airspeed", self.min_airspeed)?;
        check::positive("max_airspeed", self.max_airspeed)?;
        check::require(
            self.min_airspeed <= self.max_airspeed,
            "min_airspeed",
            self.min_airspeed,
            &format!(
                "the stall speed exceeds max_airspeed = {}: no airspeed is flyable",
                self.max_airspeed
            ),
            "lower min_airspeed below max_airspeed or raise max_airspeed (equal values fly at constant speed)",
        )?;
        check_angle("max_bank", self.max_bank)?;
        check::positive("bank_time_constant", self.bank_time_constant)?;
        check::positive("airspeed_time_constant", self.airspeed_time_constant)?;
        check_angle("max_flight_path", self.max_flight_path)?;
        check::positive("flight_path_time_constant", self.flight_path_time_constant)?;
        check::positive("inner_step", self.inner_step)?;
        let shortest = self
            .bank_time_constant
            .min(self.airspeed_time_constant)
            .min(self.flight_path_time_constant);
        check::require(
            self.inner_step <= shortest,
            "inner_step",
            self.inner_step,
            &format!("exceeds the shortest time constant {shortest} s, which RK4 does not resolve"),
            "use an inner step of at most the shortest time constant (default 0.01 s)",
        )
    }
}

/// An angle limit in (0, π/2).
fn check_angle(field: &str, value: f64) -> Result<(), ParamError> {
    check::finite(field, value)?;
    check::require(
        value > 0.0 && value < FRAC_PI_2,
        field,
        value,
        "must lie in (0, π/2) radians",
        "give the limit in radians, e.g. 0.524 for 30°",
    )
}

/// The state columns in the plane.
const STATE_2D: &[&str] = &["airspeed", "course", "bank"];
/// The state columns in space.
const STATE_3D: &[&str] = &["airspeed", "course", "bank", "flight_path"];
/// The limit columns in the plane.
const LIMITS_2D: &[&str] = &["at_airspeed_limit", "at_bank_limit"];
/// The limit columns in space.
const LIMITS_3D: &[&str] = &["at_airspeed_limit", "at_bank_limit", "at_flight_path_limit"];

/// A fixed-wing aircraft flying Beard & McLain's guidance model (module docs), its reference
/// point its position, in the plane (`DVec2`, γ = 0) or in space (`DVec3`, z up).
///
/// The commanded acceleration a of the flock is split along the velocity's frame — along track
/// e = (cos χ cos γ, sin χ cos γ, sin γ), sideways s = (−sin χ, cos χ, 0), up
/// n = (−cos χ sin γ, −sin χ sin γ, cos γ) — and mapped to the autopilot's commands, held over
/// one inner step:
///
/// - airspeed V_c = V + τ_V (e·a), clipped to [V_min, V_max]: V̇ = (V_c − V)/τ_V starts at e·a;
/// - bank φ_c = atan(s·a / (g cos γ)), clipped to ±φ_max: in the steady coordinated turn the
///   horizontal sideways acceleration is V cos γ χ̇ = g tan φ cos γ;
/// - flight path γ_c = γ + τ_γ (n·a) / V, clipped to ±γ_max: γ̇ starts at (n·a)/V, the turn
///   rate of a velocity V in the vertical plane (a linear map like the airspeed's rather than an
///   asin of a climb rate, which would mix e·a into the climb).
///
/// The limit flags are the commands clipped. The state is integrated by RK4 at the inner step,
/// V, φ and γ then kept within their limits (RK4 on a first-order response with δ ≤ τ does not
/// overshoot; this only removes round-off); χ is kept in (−π, π].
///
/// No disturbance: the guidance model is written in still air, and the wind's effect on a flock
/// of aircraft (drift of the ground velocity, crab angle) is the wind triangle of the book's
/// chapter 2, not an acceleration on the reference point, so [`VehicleKind::takes_disturbance`] is
/// false.
#[derive(Clone, Debug, PartialEq)]
pub struct FixedWing {
    params: FixedWingParams,
}

impl FixedWing {
    /// The aircraft of `params`.
    ///
    /// # Errors
    /// As [`FixedWingParams::validate`].
    pub fn new(params: FixedWingParams) -> Result<Self, ParamError> {
        params.validate()?;
        Ok(Self { params })
    }

    /// Its parameters.
    #[must_use]
    pub fn params(&self) -> &FixedWingParams {
        &self.params
    }

    /// The steady turn radius V² / (g tan φ_max) at airspeed `airspeed` and the bank limit.
    #[must_use]
    pub fn min_turn_radius(&self, airspeed: f64) -> f64 {
        airspeed * airspeed / (GRAVITY * self.params.max_bank.tan())
    }

    /// The autopilot's commands for the acceleration `a` in flight state `f`, and the limits
    /// they hit (airspeed, bank, flight path). In the plane (`planar`) γ_c = 0.
    fn commands(&self, a: DVec3, f: &Flight, planar: bool) -> (Commands, [bool; 3]) {
        let c = &self.params;
        let (e, side, up) = f.frame();
        let airspeed = f.v + c.airspeed_time_constant * e.dot(a);
        let bank = (side.dot(a) / (GRAVITY * f.gamma.cos())).atan();
        let flight_path = if planar {
            0.0
        } else {
            f.gamma + c.flight_path_time_constant * up.dot(a) / f.v
        };
        let commands = Commands {
            airspeed: airspeed.clamp(c.min_airspeed, c.max_airspeed),
            bank: bank.clamp(-c.max_bank, c.max_bank),
            flight_path: flight_path.clamp(-c.max_flight_path, c.max_flight_path),
        };
        let hit = [
            commands.airspeed != airspeed,
            commands.bank != bank,
            commands.flight_path != flight_path,
        ];
        (commands, hit)
    }

    /// The time derivative of position and flight state under `commands`.
    fn derivative(&self, f: &Flight, commands: &Commands) -> (DVec3, Flight) {
        let c = &self.params;
        let rate = Flight {
            v: (commands.airspeed - f.v) / c.airspeed_time_constant,
            chi: GRAVITY * f.phi.tan() / f.v,
            phi: (commands.bank - f.phi) / c.bank_time_constant,
            gamma: (commands.flight_path - f.gamma) / c.flight_path_time_constant,
        };
        (f.direction() * f.v, rate)
    }

    /// One RK4 step of length `delta` of position `q` and flight state `f` under `commands`.
    fn rk4(&self, delta: f64, commands: &Commands, q: &mut DVec3, f: &mut Flight) {
        let (dq1, df1) = self.derivative(f, commands);
        let (dq2, df2) = self.derivative(&f.plus(&df1, delta / 2.0), commands);
        let (dq3, df3) = self.derivative(&f.plus(&df2, delta / 2.0), commands);
        let (dq4, df4) = self.derivative(&f.plus(&df3, delta), commands);
        *q += (dq1 + (dq2 + dq3) * 2.0 + dq4) * (delta / 6.0);
        let slope = df1.plus(&df2.plus(&df3, 1.0), 2.0).plus(&df4, 1.0);
        *f = f.plus(&slope, delta / 6.0);
        let c = &self.params;
        f.v = f.v.clamp(c.min_airspeed, c.max_airspeed);
        f.phi = f.phi.clamp(-c.max_bank, c.max_bank);
        f.gamma = f.gamma.clamp(-c.max_flight_path, c.max_flight_path);
        f.chi = wrap_angle(f.chi);
    }

    /// Over the flock's step `h`: the position `q` and flight state `f` under the acceleration
    /// `a`, the limits hit set in `limits`.
    fn fly(
        &self,
        h: f64,
        a: DVec3,
        q: &mut DVec3,
        f: &mut Flight,
        planar: bool,
        limits: &mut [bool],
    ) {
        let delta = self.params.inner_step;
        for _ in inner_loop(inner_steps(h, delta)) {
            let (commands, hit) = self.commands(a, f, planar);
            self.rk4(delta, &commands, q, f);
            for (flag, hit) in limits.iter_mut().zip(hit) {
                *flag |= hit;
            }
        }
    }

    /// Level flight along the horizontal part of `p` (+x when it is zero) at the airspeed
    /// |p| clamped to [V_min, V_max].
    fn level_start(&self, p: DVec3) -> Flight {
        let chi = if p.x == 0.0 && p.y == 0.0 {
            0.0
        } else {
            p.y.atan2(p.x)
        };
        let v = p
            .length()
            .clamp(self.params.min_airspeed, self.params.max_airspeed);
        Flight {
            v,
            chi,
            phi: 0.0,
            gamma: 0.0,
        }
    }
}

/// The autopilot's commands V_c, φ_c, γ_c.
#[derive(Clone, Copy, Debug)]
struct Commands {
    airspeed: f64,
    bank: f64,
    flight_path: f64,
}

/// Airspeed V, course χ, bank φ, flight-path angle γ (or their rates).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Flight {
    v: f64,
    chi: f64,
    phi: f64,
    gamma: f64,
}

impl Flight {
    /// From an agent's state slice (γ = 0 in the plane).
    fn read(state: &[f64]) -> Self {
        Self {
            v: state[0],
            chi: state[1],
            phi: state[2],
            gamma: state.get(3).copied().unwrap_or(0.0),
        }
    }

    /// Into an agent's state slice.
    fn write(&self, state: &mut [f64]) {
        let values = [self.v, self.chi, self.phi, self.gamma];
        let n = state.len();
        state.copy_from_slice(&values[..n]);
    }

    /// `self + rate · dt`, component by component.
    fn plus(&self, rate: &Self, dt: f64) -> Self {
        Self {
            v: self.v + rate.v * dt,
            chi: self.chi + rate.chi * dt,
            phi: self.phi + rate.phi * dt,
            gamma: self.gamma + rate.gamma * dt,
        }
    }

    /// The unit velocity e = (cos χ cos γ, sin χ cos γ, sin γ).
    fn direction(&self) -> DVec3 {
        let (sin_chi, cos_chi) = self.chi.sin_cos();
        let (sin_gamma, cos_gamma) = self.gamma.sin_cos();
        DVec3::new(cos_chi * cos_gamma, sin_chi * cos_gamma, sin_gamma)
    }

    /// The velocity's frame: along track e, sideways (horizontal, left) s, up n.
    fn frame(&self) -> (DVec3, DVec3, DVec3) {
        let (sin_chi, cos_chi) = self.chi.sin_cos();
        let (sin_gamma, cos_gamma) = self.gamma.sin_cos();
        let side = DVec3::new(-sin_chi, cos_chi, 0.0);
        let up = DVec3::new(-cos_chi * sin_gamma, -sin_chi * sin_gamma, cos_gamma);
        (self.direction(), side, up)
    }
}

impl VehicleKind for FixedWing {
    fn name(&self) -> &'static str {
        "FixedWing"
    }

    fn validate(&self) -> Result<(), ParamError> {
        self.params.validate()
    }

    fn inner_step(&self) -> f64 {
        self.params.inner_step
    }

    fn takes_disturbance(&self) -> bool {
        false
    }
}

impl Vehicle<DVec2> for FixedWing {
    fn state_columns(&self) -> &'static [&'static str] {
        STATE_2D
    }

    fn limit_columns(&self) -> &'static [&'static str] {
        LIMITS_2D
    }

    fn start(&self, q: DVec2, p: DVec2, state: &mut [f64]) -> (DVec2, DVec2) {
        let f = self.level_start(p.extend(0.0));
        f.write(state);
        (q, (f.direction() * f.v).truncate())
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
        let mut f = Flight::read(state);
        let mut q3 = q.extend(0.0);
        self.fly(h, command.extend(0.0), &mut q3, &mut f, true, limits);
        f.write(state);
        *q = q3.truncate();
        *p = (f.direction() * f.v).truncate();
    }

    fn heading(&self, _p: DVec2, state: &[f64]) -> DVec2 {
        Flight::read(state).direction().truncate()
    }
}

impl Vehicle<DVec3> for FixedWing {
    fn state_columns(&self) -> &'static [&'static str] {
        STATE_3D
    }

    fn limit_columns(&self) -> &'static [&'static str] {
        LIMITS_3D
    }

    fn start(&self, q: DVec3, p: DVec3, state: &mut [f64]) -> (DVec3, DVec3) {
        let f = self.level_start(p);
        f.write(state);
        (q, f.direction() * f.v)
    }

    fn advance(
        &self,
        h: f64,
        command: DVec3,
        _disturbance: DVec3,
        q: &mut DVec3,
        p: &mut DVec3,
        state: &mut [f64],
        limits: &mut [bool],
    ) {
        let mut f = Flight::read(state);
        self.fly(h, command, q, &mut f, false, limits);
        f.write(state);
        *p = f.direction() * f.v;
    }

    fn heading(&self, _p: DVec3, state: &[f64]) -> DVec3 {
        Flight::read(state).direction()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    const H: f64 = 0.1;

    fn aircraft() -> FixedWing {
        FixedWing::new(FixedWingParams::default()).unwrap()
    }

    /// The steady turn radius measured from the trajectory of an aircraft flying at constant
    /// `airspeed` (V_min = V_max) under a huge lateral command: the path length over the course
    /// change once the bank has settled; with the bank limit hit and the final state.
    fn measured_turn_radius(airspeed: f64) -> (f64, bool, [f64; 3]) {
        let plane = FixedWing::new(FixedWingParams {
            min_airspeed: airspeed,
            max_airspeed: airspeed,
            ..FixedWingParams::default()
        })
        .unwrap();
        let mut state = [0.0; 3];
        let (mut q, mut p) =
            Vehicle::<DVec2>::start(&plane, DVec2::ZERO, DVec2::new(airspeed, 0.0), &mut state);
        let mut limits = [false; 2];
        let (mut arc, mut turn) = (0.0, 0.0);
        for k in 0..600 {
            // 100 g to the left of the present velocity, held over the step
            let command = p.perp().normalize() * 1e3;
            let (q0, p0) = (q, p);
            plane.advance(
                H,
                command,
                DVec2::ZERO,
                &mut q,
                &mut p,
                &mut state,
                &mut limits,
            );
            if k >= 100 {
                arc += q0.distance(q);
                turn += p0.angle_to(p);
            }
        }
        (arc / turn, limits[1], state)
    }

    #[test]
    fn turn_radius_at_the_bank_limit_is_v2_over_g_tan_phi_max() {
        let max_bank = FixedWingParams::default().max_bank;
        for airspeed in [18.0, 25.0, 32.0] {
            let (radius, bank_hit, state) = measured_turn_radius(airspeed);
            let expected = airspeed * airspeed / (GRAVITY * max_bank.tan());
            let ratio = radius / expected;
            println!(
                "V = {airspeed}: radius {radius:.4} m, V²/(g tan φ_max) {expected:.4} m, ratio {ratio:.6}"
            );
            assert!((0.99..=1.01).contains(&ratio), "ratio {ratio}");
            assert!(bank_hit);
            assert_eq!(state[0], airspeed);
            assert_relative_eq!(state[2], max_bank, max_relative = 1e-9);
        }
    }

    #[test]
    fn start_enforces_the_stall_speed_and_level_flight() {
        let plane = aircraft();
        let c = *plane.params();
        let mut state = [0.0; 4];
        let (_, p) =
            Vehicle::<DVec3>::start(&plane, DVec3::ZERO, DVec3::new(1.0, 1.0, 0.5), &mut state);
        assert_relative_eq!(p.length(), c.min_airspeed, max_relative = 1e-12);
        assert_eq!(p.z, 0.0);
        assert_relative_eq!(
            p.normalize(),
            DVec3::new(1.0, 1.0, 0.0).normalize(),
            max_relative = 1e-12
        );
        let (_, p) = Vehicle::<DVec3>::start(&plane, DVec3::ZERO, DVec3::ZERO, &mut state);
        assert_eq!(p, DVec3::new(c.min_airspeed, 0.0, 0.0));
        assert_eq!(state, [c.min_airspeed, 0.0, 0.0, 0.0]);
        let mut state = [0.0; 3];
        let (_, p) =
            Vehicle::<DVec2>::start(&plane, DVec2::ZERO, DVec2::new(0.0, -100.0), &mut state);
        assert_relative_eq!(p, DVec2::new(0.0, -c.max_airspeed), epsilon = 1e-12);
        assert_relative_eq!(
            Vehicle::<DVec2>::heading(&plane, p, &state),
            DVec2::NEG_Y,
            epsilon = 1e-15
        );
    }

    #[test]
    fn climb_is_limited_by_the_flight_path_angle() {
        let plane = aircraft();
        let c = *plane.params();
        let mut state = [0.0; 4];
        let (mut q, mut p) =
            Vehicle::<DVec3>::start(&plane, DVec3::ZERO, DVec3::new(25.0, 0.0, 0.0), &mut state);
        let mut limits = [false; 3];
        let mut steepest: f64 = 0.0;
        for _ in 0..200 {
            let command = DVec3::new(0.0, 0.0, 1e3);
            plane.advance(
                H,
                command,
                DVec3::ZERO,
                &mut q,
                &mut p,
                &mut state,
                &mut limits,
            );
            steepest = steepest.max(p.z / p.length());
            assert!(state[3].abs() <= c.max_flight_path);
        }
        assert!(limits[2], "flight path saturated");
        assert!(steepest <= c.max_flight_path.sin() * (1.0 + 1e-12));
        assert_relative_eq!(state[3], c.max_flight_path, max_relative = 1e-6);
        assert_relative_eq!(p.z, state[0] * c.max_flight_path.sin(), max_relative = 1e-6);
    }

    #[test]
    fn plane_and_space_agree_on_horizontal_commands() {
        let plane = aircraft();
        let (mut q2, mut p2, mut s2) = (DVec2::ZERO, DVec2::new(20.0, 5.0), [0.0; 3]);
        let (mut q3, mut p3, mut s3) = (DVec3::ZERO, DVec3::new(20.0, 5.0, 0.0), [0.0; 4]);
        (q2, p2) = Vehicle::<DVec2>::start(&plane, q2, p2, &mut s2);
        (q3, p3) = Vehicle::<DVec3>::start(&plane, q3, p3, &mut s3);
        let (mut l2, mut l3) = ([false; 2], [false; 3]);
        for k in 0..100 {
            let u = DVec2::new((0.1 * k as f64).sin(), 3.0 * (0.05 * k as f64).cos());
            plane.advance(H, u, DVec2::ZERO, &mut q2, &mut p2, &mut s2, &mut l2);
            plane.advance(
                H,
                u.extend(0.0),
                DVec3::ZERO,
                &mut q3,
                &mut p3,
                &mut s3,
                &mut l3,
            );
        }
        assert_eq!(q3, q2.extend(0.0));
        assert_eq!(p3, p2.extend(0.0));
        assert_eq!(s3[..3], s2);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        #[test]
        fn airspeed_bank_and_flight_path_stay_within_limits(
            commands in prop::collection::vec(
                (-60.0..60.0f64, -60.0..60.0f64, -60.0..60.0f64), 1..80),
            start in 0.0..50.0f64,
        ) {
            let plane = aircraft();
            let c = *plane.params();
            let mut state = [0.0; 4];
            let (mut q, mut p) =
                Vehicle::<DVec3>::start(&plane, DVec3::ZERO, DVec3::X * start, &mut state);
            let mut limits = [false; 3];
            for (x, y, z) in commands {
                let command = DVec3::new(x, y, z);
                plane.advance(H, command, DVec3::ZERO, &mut q, &mut p, &mut state, &mut limits);
                let airspeed = state[0];
                prop_assert!((c.min_airspeed..=c.max_airspeed).contains(&airspeed), "V = {airspeed}");
                prop_assert!(state[2].abs() <= c.max_bank);
                prop_assert!(state[3].abs() <= c.max_flight_path);
                prop_assert!((p.length() - state[0]).abs() <= 1e-12 * state[0]);
            }
        }
    }

    #[test]
    fn a_hard_push_or_pull_hits_the_airspeed_limit() {
        let plane = aircraft();
        let c = *plane.params();
        for (push, bound) in [(1e3, c.max_airspeed), (-1e3, c.min_airspeed)] {
            let mut state = [0.0; 3];
            let (mut q, mut p) =
                Vehicle::<DVec2>::start(&plane, DVec2::ZERO, DVec2::new(25.0, 0.0), &mut state);
            let mut limits = [false; 2];
            for _ in 0..300 {
                let command = p.normalize() * push;
                plane.advance(
                    H,
                    command,
                    DVec2::ZERO,
                    &mut q,
                    &mut p,
                    &mut state,
                    &mut limits,
                );
            }
            assert_eq!(limits, [true, false]);
            assert_relative_eq!(state[0], bound, max_relative = 1e-6);
        }
    }

    #[test]
    fn validation_names_the_field() {
        let error = |params: FixedWingParams| params.validate().unwrap_err();
        let base = FixedWingParams::default();
        let stall = error(FixedWingParams {
            min_airspeed: 40.0,
            ..base
        });
        assert_eq!(stall.field, "min_airspeed");
        assert!(stall.fix.contains("max_airspeed"), "{stall}");
        let fields = [
            (
                FixedWingParams {
                    min_airspeed: 0.0,
                    ..base
                },
                "min_airspeed",
            ),
            (
                FixedWingParams {
                    max_airspeed: f64::NAN,
                    ..base
                },
                "max_airspeed",
            ),
            (
                FixedWingParams {
                    max_bank: FRAC_PI_2,
                    ..base
                },
                "max_bank",
            ),
            (
                FixedWingParams {
                    bank_time_constant: -1.0,
                    ..base
                },
                "bank_time_constant",
            ),
            (
                FixedWingParams {
                    airspeed_time_constant: 0.0,
                    ..base
                },
                "airspeed_time_constant",
            ),
            (
                FixedWingParams {
                    max_flight_path: 0.0,
                    ..base
                },
                "max_flight_path",
            ),
            (
                FixedWingParams {
                    flight_path_time_constant: 0.0,
                    ..base
                },
                "flight_path_time_constant",
            ),
            (
                FixedWingParams {
                    inner_step: 0.0,
                    ..base
                },
                "inner_step",
            ),
            (
                FixedWingParams {
                    inner_step: 0.6,
                    ..base
                },
                "inner_step",
            ),
        ];
        for (params, field) in fields {
            assert_eq!(error(params).field, field);
        }
        assert!(base.validate().is_ok());
        let equal = FixedWingParams {
            min_airspeed: 25.0,
            max_airspeed: 25.0,
            ..base
        };
        assert!(FixedWing::new(equal).is_ok());
    }
}
