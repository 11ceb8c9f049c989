//! The integration scheme of a run's ideal (acceleration) update.

/// The integration scheme.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Integrator {
    /// Semi-implicit (symplectic) Euler: p ← p + h u(t, q, p), then q ← q + h p. First order,
    /// one net per step, and free of the energy drift of explicit Euler.
    #[default]
    SymplecticEuler,
    /// Classical fourth-order Runge–Kutta: four evaluations of u (four nets) per step. Under
    /// [conditions](crate::Simulation::with_conditions) the input is held over the step, and RK4 of the
    /// held input a is its closed form q ← q + h p + ½ h² a, p ← p + h a (to round-off;
    /// [`integrate`](crate::step::integrate)).
    Rk4,
}
