//! [`QuadrotorParams`]: a quadrotor's physical parameters, the gains of Lee et al.'s controller,
//! the inner step, and the three presets with their sources ([the model](super)).

use core::f64::consts::{FRAC_PI_2, PI, SQRT_2};

use glam::DVec3;

use super::super::GRAVITY;
use flock_protocols::error::{ParamError, check};

/// Revolutions per minute in one radian per second, 30/π: a coefficient per rpm² times its square
/// is the coefficient per (rad/s)².
pub(super) const RPM_PER_RAD_S: f64 = 30.0 / PI;

/// The physical parameters of a quadrotor (SI units, rotor speeds in rad/s), the gains of Lee et
/// al.'s controller and the inner step. Three presets, each from one named source:
/// [`QuadrotorParams::crazyflie`] (the default, gym-pybullet-drones' Crazyflie),
/// [`QuadrotorParams::crazyflie_firmware`] (the Crazyflie as its firmware models it) and
/// [`QuadrotorParams::heavy`] (PX4's SIH quadrotor). See [the module](super) for the model.
///
/// # Example
/// ```
/// use flock_sim::vehicle::QuadrotorParams;
///
/// let cf = QuadrotorParams::crazyflie();
/// assert!((cf.thrust_to_weight() - 2.25).abs() < 1e-12);
/// let tiny = QuadrotorParams { thrust_coefficient: 1e-12, ..cf };
/// assert_eq!(tiny.validate().unwrap_err().field, "thrust_coefficient");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields, default)
)]
pub struct QuadrotorParams {
    /// The mass m (kg).
    pub mass: f64,
    /// The principal moments of inertia (J_xx, J_yy, J_zz) (kg m²), J = diag(inertia).
    pub inertia: DVec3,
    /// The arm length l (m): the distance from the centre of mass to each rotor's axis.
    pub arm_length: f64,
    /// The thrust coefficient k_f (N per (rad/s)²): T_i = k_f ω_i².
    pub thrust_coefficient: f64,
    /// The drag-torque coefficient k_m (N m per (rad/s)²): the yaw torque ±k_m ω_i².
    pub drag_coefficient: f64,
    /// The lowest rotor speed ω_min ≥ 0 (rad/s).
    pub rotor_speed_min: f64,
    /// The highest rotor speed ω_max (rad/s).
    pub rotor_speed_max: f64,
    /// The motor time constant τ_m (s) of ω̇ = (ω_cmd − ω)/τ_m.
    pub motor_time_constant: f64,
    /// The position gain k_x (N/m).
    pub k_x: f64,
    /// The velocity gain k_v (N s/m).
    pub k_v: f64,
    /// The attitude gain k_R (N m).
    pub k_r: f64,
    /// The angular-velocity gain k_Ω (N m s).
    pub k_omega: f64,
    /// The largest angle (rad, in (0, π/2)) between the desired thrust direction b3_d and the
    /// vertical.
    pub max_tilt: f64,
    /// The inner step δ (s) of the controller and of the integration.
    pub inner_step: f64,
}

impl Default for QuadrotorParams {
    fn default() -> Self {
        Self::crazyflie()
    }
}

/// The attitude gains that give every axis of the linearised attitude loop
/// J ë + k_Ω ė + k_R e = 0, about the roll axis J_xx, the natural frequency and damping of Lee et
/// al.'s own gains (k_R = 8.81, k_Ω = 2.54 with J_xx = 0.0820 kg m²: ω_n = √(k_R/J) ≈ 10.4 rad/s,
/// ζ = k_Ω/(2√(k_R J)) ≈ 1.49), rounded to ω_n = 10 rad/s, ζ = 1.5. Overdamped, so that the
/// loop with the motor lag (J τ_m s³ + J s² + k_Ω s + k_R) stays stable for τ_m < k_Ω/k_R = 0.3 s.
fn lee_attitude_gains(j_xx: f64) -> (f64, f64) {
    let (omega_n, zeta) = (10.0, 1.5);
    (j_xx * omega_n * omega_n, 2.0 * zeta * j_xx * omega_n)
}

impl QuadrotorParams {
    /// The Bitcraze Crazyflie 2.x (the default) as gym-pybullet-drones models it, its
    /// `gym_pybullet_drones/assets/cf2x.urdf` (utiasDSL/gym-pybullet-drones, commit 90b178a):
    /// - m = 0.027 kg (its `mass`); J = diag(1.4e-5, 1.4e-5, 2.17e-5) kg m² (its `inertia`);
    ///   l = 0.0397 m (its `arm`; its rotors sit at (±0.028, ±0.028) m, an X);
    /// - k_f = 3.16e-10 N/rpm² = 2.8816e-8 N/(rad/s)²; k_m = 7.94e-12 N m/rpm² =
    ///   7.2404e-10 N m/(rad/s)² (its `kf`, `km` are per rpm², converted by (30/π)²);
    /// - ω_max = √(2.25 m g / (4 k_f)) ≈ 2274 rad/s (≈ 21 700 rpm), from its thrust-to-weight
    ///   ratio `thrust2weight` = 2.25, as gym-pybullet-drones derives its `MAX_RPM` (with our
    ///   g = 9.81); ω_min = 0.
    ///
    /// The URDF links Förster's "System identification of the Crazyflie 2.0 nano quadrocopter"
    /// (ETH BSc thesis 2015), Landry's MIT thesis (2015) and arXiv:1608.05786 as its sources, but
    /// its inertia is **not** Förster's: the identification the Crazyflie firmware and Crazyswarm2
    /// use is J = diag(1.657, 1.666, 2.926)·10⁻⁵ kg m², with l = 0.046 m and m = 0.029–0.034 kg —
    /// [`QuadrotorParams::crazyflie_firmware`]. This preset serves users who compare with
    /// gym-pybullet-drones.
    ///
    /// The motor time constant τ_m = 0.072 s is rotorpy's (`rotorpy/vehicles/crazyflie_params.py`,
    /// spencerfolk/rotorpy, which cites Eschmann, Albani & Loianno, "Data-driven system
    /// identification of quadrotors subject to motor delays", 2024; **not confirmed** in that
    /// paper).
    ///
    /// Gains (ours): k_x = 16 m, k_v = 5.6 m (the k_x/m = 16, k_v/m = 5.6 of Lee et al.'s
    /// numerical example); k_R, k_Ω giving Lee's attitude dynamics (ω_n = 10 rad/s, ζ = 1.5 on
    /// J_xx). Tilt limit 45° and δ = 1 ms: our choices.
    #[must_use]
    pub fn crazyflie() -> Self {
        let mass = 0.027;
        let thrust_coefficient = 3.16e-10 * RPM_PER_RAD_S * RPM_PER_RAD_S;
        Self::with_our_gains(
            mass,
            DVec3::new(1.4e-5, 1.4e-5, 2.17e-5),
            0.0397,
            (thrust_coefficient, 7.94e-12 * RPM_PER_RAD_S * RPM_PER_RAD_S),
            (2.25 * mass * GRAVITY / (4.0 * thrust_coefficient)).sqrt(),
            0.072,
        )
    }

    /// The Crazyflie 2.1 as its own firmware models it (bitcraze/crazyflie-firmware, commit
    /// 2a18fc2, the `cf2` platform with the 2.1+ propellers, its default):
    /// - m = 0.029 kg (`CF_MASS`, `src/platform/interface/platform_defaults_cf2.h`; 0.0325 kg with
    ///   the thrust upgrade kit); l = 0.046 m (`ARM_LENGTH`, the same file);
    /// - J = diag(16.571710, 16.655602, 29.261652)·10⁻⁶ kg m², Förster's identification as the
    ///   firmware's Lee controller takes it (`src/modules/src/controller/controller_lee.c`, citing
    ///   Förster's ETH BSc thesis 2015; Crazyswarm2's simulator, IMRCLab/crazyswarm2
    ///   `crazyflie_sim/backend/np.py`, uses the same J and l with m = 0.034 kg);
    /// - the largest thrust per motor 0.12 N (`THRUST_MAX`) and the yaw torque per unit of thrust
    ///   k_m/k_f = 0.0069928948992470565 m (`THRUST2TORQUE`), the same file;
    /// - the firmware commands thrust, not rotor speed: k_f = 2.3e-8 N/(rad/s)² is rotorpy's
    ///   (`crazyflie_params.py`, `k_eta`, citing Förster 2015), which only sets the scale of ω:
    ///   ω_max = √(0.12 N / k_f) ≈ 2284 rad/s, ω_min = 0. Thrust-to-weight 1.69.
    ///
    /// τ_m = 0.072 s (rotorpy's, as [`QuadrotorParams::crazyflie`]), the gains, the tilt limit
    /// and δ as [`QuadrotorParams::crazyflie`].
    #[must_use]
    pub fn crazyflie_firmware() -> Self {
        let thrust_coefficient = 2.3e-8;
        Self::with_our_gains(
            0.029,
            DVec3::new(16.571710e-6, 16.655602e-6, 29.261652e-6),
            0.046,
            (
                thrust_coefficient,
                0.0069928948992470565 * thrust_coefficient,
            ),
            (0.12 / thrust_coefficient).sqrt(),
            0.072,
        )
    }

    /// A 1 kg quadrotor: PX4's SIH quadrotor-X simulator defaults as rotorpy transcribes them
    /// (`rotorpy/vehicles/px4_params/sihsim_quadx.py`, spencerfolk/rotorpy, "aligned with PX4 SIH
    /// parameters"): m = 1.0 kg (`SIH_MASS`); J = diag(0.025, 0.025, 0.030) kg m² (`SIH_IXX`,
    /// `SIH_IYY`, `SIH_IZZ`); rotors at d (±1, ±1) with d = 0.17 m, so l = 0.17 √2 ≈ 0.240 m;
    /// k_f = 5e-6 N/(rad/s)² (= `SIH_T_MAX`/ω_max², 5 N per rotor at ω_max); k_m = 1e-7 N m/(rad/s)²
    /// (= `SIH_Q_MAX`/ω_max², 0.1 N m); ω_max = 1000 rad/s, ω_min = 0; τ_m = 0.05 s (`SIH_T_TAU`).
    /// Thrust-to-weight 2.04. These were **not confirmed** against PX4's own parameter
    /// definitions (PX4's `SIH_L_ROLL` arm, for instance, was not read).
    ///
    /// Gains (ours): k_x = 16 m, k_v = 5.6 m and the attitude dynamics of Lee et al.'s gains, as in
    /// [`QuadrotorParams::crazyflie`]; tilt limit 45°; δ = 1 ms.
    #[must_use]
    pub fn heavy() -> Self {
        Self::with_our_gains(
            1.0,
            DVec3::new(0.025, 0.025, 0.030),
            0.17 * SQRT_2,
            (5e-6, 1e-7),
            1000.0,
            0.05,
        )
    }

    /// A quadrotor of mass `mass`, inertia `inertia`, arm `arm_length`, rotors of coefficients
    /// `(k_f, k_m)` up to `rotor_speed_max` (ω_min = 0) lagging by `motor_time_constant`, with our
    /// gains and limits: k_x = 16 m, k_v = 5.6 m (the ratios k_x/m, k_v/m of Lee et al.'s
    /// numerical example), k_R and k_Ω of Lee et al.'s attitude dynamics on J_xx
    /// ([`lee_attitude_gains`]), a tilt limit of 45° and δ = 1 ms.
    fn with_our_gains(
        mass: f64,
        inertia: DVec3,
        arm_length: f64,
        (thrust_coefficient, drag_coefficient): (f64, f64),
        rotor_speed_max: f64,
        motor_time_constant: f64,
    ) -> Self {
        let (k_r, k_omega) = lee_attitude_gains(inertia.x);
        Self {
            mass,
            inertia,
            arm_length,
            thrust_coefficient,
            drag_coefficient,
            rotor_speed_min: 0.0,
            rotor_speed_max,
            motor_time_constant,
            k_x: 16.0 * mass,
            k_v: 5.6 * mass,
            k_r,
            k_omega,
            max_tilt: core::f64::consts::FRAC_PI_4,
            inner_step: 1e-3,
        }
    }

    /// The rotor speed of hover, √(m g / (4 k_f)) (rad/s).
    #[inline]
    #[must_use]
    pub fn hover_speed(&self) -> f64 {
        (self.mass * GRAVITY / (4.0 * self.thrust_coefficient)).sqrt()
    }

    /// The thrust-to-weight ratio 4 k_f ω_max² / (m g).
    #[inline]
    #[must_use]
    pub fn thrust_to_weight(&self) -> f64 {
        4.0 * self.thrust_coefficient * self.rotor_speed_max * self.rotor_speed_max
            / (self.mass * GRAVITY)
    }

    /// Checks every parameter, naming the field, the value and the fix.
    ///
    /// # Errors
    /// The first parameter outside its domain: a non-positive mass, inertia, arm, coefficient,
    /// gain, motor time constant or inner step; ω_min ≥ ω_max; a thrust-to-weight ratio below 1
    /// (named `thrust_coefficient`) or a least thrust above the weight (`rotor_speed_min`); a
    /// tilt limit outside (0, π/2); an attitude loop the motor lag destabilises (`k_omega`); an
    /// inner step too long for the attitude loop.
    pub fn validate(&self) -> Result<(), ParamError> {
        check::positive("mass", self.mass)?;
        for (axis, j) in ["x", "y", "z"].iter().zip(self.inertia.to_array()) {
            check::positive(&format!("inertia.{axis}"), j)?;
        }
        check::length("arm_length", self.arm_length)?;
        check::positive("thrust_coefficient", self.thrust_coefficient)?;
        check::positive("drag_coefficient", self.drag_coefficient)?;
        self.validate_rotors()?;
        check::positive("motor_time_constant", self.motor_time_constant)?;
        check::positive("k_x", self.k_x)?;
        check::positive("k_v", self.k_v)?;
        check::positive("k_r", self.k_r)?;
        check::positive("k_omega", self.k_omega)?;
        check::finite("max_tilt", self.max_tilt)?;
        check::require(
            self.max_tilt > 0.0 && self.max_tilt < FRAC_PI_2,
            "max_tilt",
            self.max_tilt,
            "the tilt limit must lie in (0, π/2) rad: at π/2 the thrust no longer carries the weight",
            "give an angle in radians below 1.5707963 (e.g. 0.785398, 45°)",
        )?;
        check::positive("inner_step", self.inner_step)?;
        self.validate_loop()
    }

    /// The rotor speeds: 0 ≤ ω_min < ω_max, thrust-to-weight at least 1, least thrust below the
    /// weight.
    fn validate_rotors(&self) -> Result<(), ParamError> {
        check::non_negative("rotor_speed_min", self.rotor_speed_min)?;
        check::positive("rotor_speed_max", self.rotor_speed_max)?;
        check::require(
            self.rotor_speed_max > self.rotor_speed_min,
            "rotor_speed_max",
            self.rotor_speed_max,
            &format!("must exceed rotor_speed_min = {}", self.rotor_speed_min),
            "raise rotor_speed_max or lower rotor_speed_min",
        )?;
        let ratio = self.thrust_to_weight();
        check::require(
            ratio >= 1.0,
            "thrust_coefficient",
            self.thrust_coefficient,
            &format!(
                "the thrust-to-weight ratio 4 k_f ω_max² / (m g) is {ratio:.4} < 1: the rotors cannot lift the mass"
            ),
            &format!(
                "raise thrust_coefficient (k_f, N per (rad/s)², not per rpm²) to at least {:e}, or rotor_speed_max, or lower the mass",
                self.mass * GRAVITY / (4.0 * self.rotor_speed_max * self.rotor_speed_max)
            ),
        )?;
        let least = 4.0 * self.thrust_coefficient * self.rotor_speed_min * self.rotor_speed_min;
        check::require(
            least < self.mass * GRAVITY,
            "rotor_speed_min",
            self.rotor_speed_min,
            "the least thrust 4 k_f ω_min² is at least the weight: the vehicle cannot hover",
            &format!(
                "lower rotor_speed_min below the hover speed {:.1} rad/s",
                self.hover_speed()
            ),
        )
    }

    /// The attitude loop: stable with the motor lag, resolved by the inner step; then the
    /// position loop, resolved by the inner step.
    fn validate_loop(&self) -> Result<(), ParamError> {
        check::require(
            self.k_omega > self.motor_time_constant * self.k_r,
            "k_omega",
            self.k_omega,
            &format!(
                "with the motor lag τ_m = {} s the linearised attitude loop J τ_m s³ + J s² + k_Ω s + k_R is unstable unless k_Ω > τ_m k_R = {:e} (Routh)",
                self.motor_time_constant,
                self.motor_time_constant * self.k_r
            ),
            "raise k_omega (or lower k_r, or motor_time_constant)",
        )?;
        let j_min = self.inertia.min_element();
        let rate = (self.k_omega / j_min).max((self.k_r / j_min).sqrt());
        check::require(
            self.inner_step * rate <= 0.5,
            "inner_step",
            self.inner_step,
            &format!(
                "the attitude loop's fastest rate max(k_Ω/J, √(k_R/J)) = {rate:.4} s⁻¹ is not resolved: δ times it exceeds 0.5"
            ),
            &format!("lower inner_step to at most {:e} s", 0.5 / rate),
        )?;
        // issue 49: a mass of 1e-300 kg validated and blew up at the first step
        let rate = (self.k_v / self.mass).max((self.k_x / self.mass).sqrt());
        let least =
            (2.0 * self.inner_step * self.k_v).max(4.0 * self.inner_step.powi(2) * self.k_x);
        check::require(
            self.inner_step * rate <= 0.5,
            "mass",
            self.mass,
            &format!(
                "under the gains k_x = {}, k_v = {} the position loop's fastest rate max(k_v/m, √(k_x/m)) = {rate:.4e} s⁻¹ is not resolved: the inner step δ = {} s times it exceeds 0.5",
                self.k_x, self.k_v, self.inner_step
            ),
            &format!(
                "give a mass of at least {least:e} kg, or gains in proportion to the mass (the presets take k_x = 16 m, k_v = 5.6 m), or a shorter inner_step"
            ),
        )
    }
}
