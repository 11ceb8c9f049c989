//! The one-screen summary `flocking run` prints.

use std::fmt;

use flocking::RunSummary;

/// A run summary with its scenario's name, ready to print.
#[derive(Debug)]
pub struct Report<'a> {
    /// The scenario's name.
    pub name: &'a str,
    /// The run.
    pub summary: &'a RunSummary,
}

impl fmt::Display for Report<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = self.summary;
        let m = &s.metrics;
        let rate = (s.agents as f64 * s.steps as f64) / s.elapsed.as_secs_f64().max(1e-9);
        writeln!(
            f,
            "flocking run: {} ({}D, n = {}, {} steps to t = {})",
            self.name, s.dim, s.agents, s.steps, s.t
        )?;
        writeln!(
            f,
            "  connectivity C        {:.4}   ({} component(s))",
            m.connectivity, m.components
        )?;
        writeln!(f, "  giant component C*    {:.4}", m.giant_component)?;
        writeln!(f, "  cohesion radius R     {:.4}", m.cohesion_radius)?;
        writeln!(f, "  deviation energy Ẽ    {:.3e}", m.deviation_energy)?;
        writeln!(
            f,
            "  velocity mismatch K̃   {:.3e}   (within components {:.3e})",
            m.velocity_mismatch, s.component_velocity_mismatch
        )?;
        writeln!(f, "  min distance          {:.4}", m.min_distance)?;
        writeln!(f, "  colliding pairs       {}", m.collisions)?;
        if s.merged.agents > 0 {
            writeln!(
                f,
                "  merged agents         {}   (closer than 10⁻³ d: the α-force cannot separate them)",
                s.merged
            )?;
        }
        for (name, value) in &s.diagnostics {
            writeln!(f, "  {name:<22}{value:.6e}")?;
        }
        writeln!(f, "  lattice               {}", s.lattice)?;
        writeln!(
            f,
            "  energy H              {:.6e} -> {:.6e}",
            s.initial_energy, s.final_energy
        )?;
        write!(
            f,
            "  wall time             {:.3} s ({rate:.3e} agent-steps/s)",
            s.elapsed.as_secs_f64()
        )
    }
}
