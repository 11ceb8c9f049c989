//! The [`Potential`] trait: a pairwise potential ψ and its action function φ = dψ/dz.

/// A scalar pairwise potential ψ(z) and its action function φ(z) = dψ/dz.
///
/// What z is depends on the protocol: a σ-norm ‖q_j − q_i‖_σ for TAC 2006, the distance error
/// ‖q_j − q_i‖ − d_α for the 2003 protocols, the distance itself for the Tanner law. Implementors
/// guarantee `action` is the derivative of `potential` (tested against finite differences).
pub trait Potential: Send + Sync {
    /// The action function φ(z) = ψ′(z).
    #[must_use]
    fn action(&self, z: f64) -> f64;
    /// The potential ψ(z).
    #[must_use]
    fn potential(&self, z: f64) -> f64;
}
