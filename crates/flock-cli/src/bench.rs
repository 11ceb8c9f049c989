//! `flocking bench`'s flags: what they parse into for the library's engine
//! ([`flocking::bench`]), which builds, times and reports.

use clap::builder::{PossibleValuesParser, TypedValueParser};
use flocking::bench::{BenchConditions, BenchVehicle, parse_delayed};
use flocking::protocols::conditions::Delayed;
use flocking::workload::Workload;

/// The real conditions `flocking bench` may run under; none set (the default) is the ideal loop.
#[derive(Clone, Copy, Debug, Default, PartialEq, clap::Args)]
pub struct ConditionFlags {
    /// Communication delay τ in seconds, a whole number of steps of 0.01 s (e.g. 0.1).
    #[arg(long, value_name = "SECONDS", conflicts_with = "workload")]
    pub delay: Option<f64>,
    /// Whose states the delay applies to: `neighbours` (each agent's own state is current) or
    /// `all` (its own state is delayed too).
    #[arg(long, value_name = "WHOSE", value_parser = parse_delayed, conflicts_with = "workload")]
    pub delayed: Option<Delayed>,
    /// Bernoulli packet loss: each packet of each directed link lost with probability P.
    #[arg(long, value_name = "P", conflicts_with = "workload")]
    pub loss: Option<f64>,
    /// White sensing noise: standard deviations σ_q (m) on positions and σ_p (m/s) on
    /// velocities; one value gives both.
    #[arg(long, value_name = "SIGMA_Q[,SIGMA_P]", value_parser = parse_noise, conflicts_with = "workload")]
    pub sensing_noise: Option<(f64, f64)>,
    /// Sampled control: the controller runs at this rate (Hz) and holds its input between.
    #[arg(long, value_name = "HZ", conflicts_with = "workload")]
    pub control_rate: Option<f64>,
    /// The commanded acceleration is clipped to this norm (m/s²).
    #[arg(long, value_name = "M_PER_S2", conflicts_with = "workload")]
    pub max_acceleration: Option<f64>,
}

impl From<ConditionFlags> for BenchConditions {
    fn from(f: ConditionFlags) -> Self {
        Self {
            delay: f.delay,
            delayed: f.delayed,
            loss: f.loss,
            sensing_noise: f.sensing_noise,
            control_rate: f.control_rate,
            max_acceleration: f.max_acceleration,
        }
    }
}

/// `SIGMA_Q` or `SIGMA_Q,SIGMA_P` (the first given for both when alone).
fn parse_noise(s: &str) -> Result<(f64, f64), String> {
    let number = |x: &str| {
        x.trim()
            .parse::<f64>()
            .map_err(|e| format!("`{x}` is not a number: {e}"))
    };
    match s.split_once(',') {
        Some((q, p)) => Ok((number(q)?, number(p)?)),
        None => number(s).map(|q| (q, q)),
    }
}

/// `--vehicle`: one of [`BenchVehicle::NAMES`], listed in `--help`.
#[must_use]
pub fn vehicle_parser() -> impl TypedValueParser<Value = BenchVehicle> {
    PossibleValuesParser::new(BenchVehicle::NAMES).try_map(|name| name.parse::<BenchVehicle>())
}

/// `--workload`: one of [`Workload::NAMES`], listed in `--help`.
#[must_use]
pub fn workload_parser() -> impl TypedValueParser<Value = Workload> {
    PossibleValuesParser::new(Workload::NAMES).try_map(|name| name.parse::<Workload>())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn condition_flags_are_the_library_conditions() {
        let flags = ConditionFlags {
            delay: Some(0.1),
            sensing_noise: Some((0.05, 0.02)),
            ..ConditionFlags::default()
        };
        let c = BenchConditions::from(flags);
        assert_eq!((c.delay, c.sensing_noise), (Some(0.1), Some((0.05, 0.02))));
        assert_eq!(
            BenchConditions::from(ConditionFlags::default()),
            BenchConditions::default()
        );
        assert_eq!(parse_noise("0.3"), Ok((0.3, 0.3)));
        assert_eq!(parse_noise("0.3, 0.1"), Ok((0.3, 0.1)));
        assert!(parse_noise("0.3,x").is_err());
    }
}
