//! Times as people write them: t = k·h rounded to the decimals of the step ([`time_text`]), for
//! the messages of every layer (a blow-up, a merge, a run's summary). It depends on nothing else
//! of the crate, so that the modules below [`run`](mod@crate::run) can use it.

/// A time t = k·h as people write it: rounded to the decimals of the step h (at most 12), trailing
/// zeros dropped — `0.6` where the sum of steps gives 0.6000000000000001.
#[must_use]
pub fn time_text(t: f64, step: f64) -> String {
    let decimals = (0..12)
        .find(|&k| {
            let scaled = step * 10f64.powi(k);
            (scaled - scaled.round()).abs() <= 1e-6
        })
        .unwrap_or(12) as usize;
    let text = format!("{t:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sum_of_steps_is_written_to_the_step_s_decimals() {
        assert_eq!(time_text(0.6000000000000001, 0.01), "0.6");
        assert_eq!(time_text(12.0, 0.05), "12");
        assert_eq!(time_text(0.125, 0.005), "0.125");
    }
}
