//! A value of `runs.csv` as a figure shows it: an enum variant as the scenario file writes it,
//! a number to three significant digits when that is shorter.

/// A value for a title or a category: as written, or to 3 significant digits when that is
/// shorter (0.006324555320336759 is 0.00632); an enum variant and its fields (JSON in runs.csv)
/// as the scenario writes it.
#[must_use]
pub fn shown(field: &str) -> String {
    if field.starts_with('{') || field.starts_with('[') {
        // a whole value (an enum variant and its fields) as the scenario writes it
        if let Ok(value) = flocking::serde_json::from_str::<flocking::serde_json::Value>(field) {
            return as_scenario_writes(&value);
        }
    }
    let Some(x) = field
        .parse::<f64>()
        .ok()
        .filter(|x| x.is_finite() && *x != 0.0)
    else {
        return field.to_owned();
    };
    let decimals = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    let short = format!("{x:.decimals$}");
    if short.len() < field.len() {
        short
    } else {
        field.to_owned()
    }
}

/// A value of `runs.csv` as a scenario file writes it: `{"Quadrotor":{"inner_step":0.001}}` is
/// `Quadrotor(inner_step: 0.001)`, `{"Bernoulli":{"p":0.1}}` is `Bernoulli(p: 0.1)`.
fn as_scenario_writes(value: &flocking::serde_json::Value) -> String {
    use flocking::serde_json::{Map, Value};
    let fields = |map: &Map<String, Value>| {
        map.iter()
            .map(|(name, v)| format!("{name}: {}", as_scenario_writes(v)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match value {
        Value::Object(map) if map.len() == 1 => {
            let (variant, inner) = map.iter().next().expect("one entry");
            match inner {
                Value::Null => variant.clone(),
                Value::Object(inner) => format!("{variant}({})", fields(inner)),
                other => format!("{variant}({})", as_scenario_writes(other)),
            }
        }
        Value::Object(map) => format!("({})", fields(map)),
        Value::Array(items) => format!(
            "[{}]",
            items
                .iter()
                .map(as_scenario_writes)
                .collect::<Vec<_>>()
                .join(", ")
        ),
        Value::String(text) => text.clone(),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::shown;

    /// A panel's value as the scenario writes it: an enum variant with its fields, a bare one,
    /// numbers shortened, text as it is.
    #[test]
    fn values_are_shown_as_the_scenario_writes_them() {
        assert_eq!(
            shown(r#"{"Quadrotor":{"inner_step":0.001}}"#),
            "Quadrotor(inner_step: 0.001)"
        );
        assert_eq!(shown(r#"{"Bernoulli":{"p":0.1}}"#), "Bernoulli(p: 0.1)");
        assert_eq!(shown("PointMass"), "PointMass");
        assert_eq!(shown("0.123456789"), "0.123");
    }
}
