//! Tabulates φ_α, ψ_α (TAC 2006 eq. 16–17) and φ_β, ψ_β (eq. 56) for the papers' parameters.
//!
//! `cargo run -p flock-math --example potentials`

use flock_math::{Bump, BumpedAction, Potential, SigmaNorm, UnevenSigmoid};

fn main() {
    let sigma = SigmaNorm::new(0.1);
    let (d, r) = (7.0, 8.4);
    let alpha = BumpedAction::alpha(
        UnevenSigmoid::new(5.0, 5.0),
        Bump::tac(0.2),
        sigma.of_length(d),
        sigma.of_length(r),
    );
    let beta = BumpedAction::beta(Bump::tac(0.9), sigma.of_length(0.6 * d));
    println!("distance,z_sigma,phi_alpha,psi_alpha,phi_beta,psi_beta");
    for i in 0..=45 {
        let distance = 0.2 * f64::from(i);
        let z = sigma.of_length(distance);
        println!(
            "{distance:.1},{z:.4},{:.6},{:.6},{:.6},{:.6}",
            alpha.action(z),
            alpha.potential(z),
            beta.action(z),
            beta.potential(z)
        );
    }
}
