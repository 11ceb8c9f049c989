//! [`Warning`]: a valid scenario that is likely to go wrong, as `flocking validate` and
//! `flocking run` print it (the warnings themselves: [`crate::warnings`]).

use std::fmt;

/// A valid scenario that is likely to go wrong, with the field, the value, why and the fix.
#[derive(Clone, Debug, PartialEq)]
pub struct Warning {
    /// The field, as a path.
    pub field: String,
    /// The value given.
    pub value: String,
    /// Why it is likely to go wrong.
    pub why: String,
    /// How to fix it.
    pub fix: String,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "warning: `{}` = {}: {}. Fix: {}.",
            self.field, self.value, self.why, self.fix
        )
    }
}
