//! [`ParamError`]: a parameter outside the domain the theory needs, with the field, the value, why
//! and the fix; and the domain checks every parameter type of the workspace uses ([`check`]).

use core::fmt;

/// A parameter outside its domain: the field (a path such as `r`, or `alpha.r` once
/// [`ParamError::within`] an enclosing value), the value given, why it cannot be used and how to
/// fix it.
///
/// # Example
/// ```
/// use flock_protocols::{AlphaParams, ParamError};
///
/// let params = AlphaParams { r: 6.0, ..AlphaParams::default() };
/// let error: ParamError = params.validate().unwrap_err().within("alpha");
/// assert_eq!(error.field, "alpha.r");
/// assert!(error.to_string().starts_with("`alpha.r` = 6.0: must exceed"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParamError {
    /// The field, as a path (`r`, `alpha.r`, `algorithm.beta.h`).
    pub field: String,
    /// The value given, as printed.
    pub value: String,
    /// Why it cannot be used.
    pub why: String,
    /// How to fix it.
    pub fix: String,
    /// Whether the value is valid but needs more memory than the machine gives (a delay line of a
    /// long delay; the bytes are in `why`), rather than out of its domain.
    pub memory: bool,
}

impl ParamError {
    /// `field = value` is invalid because `why`; `fix` says what to write instead.
    #[must_use]
    pub fn new(
        field: impl Into<String>,
        value: impl fmt::Debug,
        why: impl Into<String>,
        fix: impl Into<String>,
    ) -> Self {
        Self {
            field: field.into(),
            value: plain_value(&value),
            why: why.into(),
            fix: fix.into(),
            memory: false,
        }
    }

    /// `field = value` needs `bytes` of memory (for `what`) that could not be allocated; `fix`
    /// says how to need less.
    #[must_use]
    pub fn out_of_memory(
        field: impl Into<String>,
        value: impl fmt::Debug,
        (what, bytes): (&str, u64),
        fix: impl Into<String>,
    ) -> Self {
        Self {
            memory: true,
            ..Self::new(
                field,
                value,
                format!(
                    "needs {:.1} GB for {what}, which this machine cannot allocate",
                    bytes as f64 / 1e9
                ),
                fix,
            )
        }
    }

    /// The same error with its field inside `prefix` (`r` within `alpha` is `alpha.r`).
    #[must_use]
    pub fn within(mut self, prefix: &str) -> Self {
        self.field = format!("{prefix}.{}", self.field);
        self
    }
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "`{}` = {}: {}; {}",
            self.field, self.value, self.why, self.fix
        )
    }
}

impl std::error::Error for ParamError {}

/// The domain checks of parameters: each passes or names the field, the value, why and the fix.
///
/// Lengths, gains and times are bounded by [`MAX_VALUE`](check::MAX_VALUE) (beyond it the
/// energies, quadratic in lengths and linear in gains summed over pairs, overflow) and lengths
/// below by [`MIN_LENGTH`](check::MIN_LENGTH) (below it 64-bit floats cannot resolve them).
pub mod check {
    use super::ParamError;

    /// The outcome of a check.
    pub type Check = Result<(), ParamError>;

    /// The largest coordinate, length, gain, time or speed accepted.
    pub const MAX_VALUE: f64 = 1e9;

    /// The smallest length (and potential bound a, b) accepted.
    pub const MIN_LENGTH: f64 = 1e-9;

    /// Why lengths are bounded.
    pub const WHY_BOUNDED: &str = "where 64-bit floats keep too few digits to resolve the lattice distance (and squares of distances overflow)";

    /// Fails with `why` and `fix` unless `ok`.
    ///
    /// # Errors
    /// When `ok` is false.
    pub fn require(
        ok: bool,
        field: &str,
        value: impl core::fmt::Debug,
        why: &str,
        fix: &str,
    ) -> Check {
        if ok {
            Ok(())
        } else {
            Err(ParamError::new(field, value, why, fix))
        }
    }

    /// A finite number.
    ///
    /// # Errors
    /// NaN or ±∞.
    pub fn finite(field: &str, value: f64) -> Check {
        require(
            value.is_finite(),
            field,
            value,
            "must be a finite number",
            "write a finite decimal value",
        )
    }

    /// At most [`MAX_VALUE`].
    ///
    /// # Errors
    /// Above [`MAX_VALUE`].
    pub fn not_huge(field: &str, value: f64) -> Check {
        require(
            value <= MAX_VALUE,
            field,
            value,
            &format!("exceeds {MAX_VALUE:e}, where the energies and forces overflow"),
            "use a value of at most 1e9 (rescale time or length if needed)",
        )
    }

    /// A finite value in (0, [`MAX_VALUE`]].
    ///
    /// # Errors
    /// Not finite, not positive, or too large.
    pub fn positive(field: &str, value: f64) -> Check {
        finite(field, value)?;
        above_zero(field, value)?;
        not_huge(field, value)
    }

    /// `value` > 0, or "must be > 0; give a positive value".
    fn above_zero(field: &str, value: f64) -> Check {
        require(
            value > 0.0,
            field,
            value,
            "must be > 0",
            "give a positive value",
        )
    }

    /// A finite value in [0, [`MAX_VALUE`]].
    ///
    /// # Errors
    /// Not finite, negative, or too large.
    pub fn non_negative(field: &str, value: f64) -> Check {
        finite(field, value)?;
        require(
            value >= 0.0,
            field,
            value,
            "must be ≥ 0",
            "give a non-negative value",
        )?;
        not_huge(field, value)
    }

    /// A value strictly between 0 and 1.
    ///
    /// # Errors
    /// Outside (0, 1) or not finite.
    pub fn unit_interval(field: &str, value: f64) -> Check {
        finite(field, value)?;
        require(
            value > 0.0 && value < 1.0,
            field,
            value,
            "must lie in (0, 1)",
            "choose a value strictly between 0 and 1",
        )
    }

    /// A length in [[`MIN_LENGTH`], [`MAX_VALUE`]].
    ///
    /// # Errors
    /// Outside that range or not finite.
    pub fn length(field: &str, value: f64) -> Check {
        within_scale(field, value, WHY_BOUNDED)
    }

    /// A finite value in [[`MIN_LENGTH`], [`MAX_VALUE`]], where `why` says what breaks outside.
    ///
    /// # Errors
    /// Outside that range or not finite.
    pub fn within_scale(field: &str, value: f64, why: &str) -> Check {
        finite(field, value)?;
        // zero or less is not a matter of scale: the fix is a positive value, not a rescaling
        above_zero(field, value)?;
        require(
            (MIN_LENGTH..=MAX_VALUE).contains(&value),
            field,
            value,
            &format!("lies outside [{MIN_LENGTH:e}, {MAX_VALUE:e}], {why}"),
            "rescale the scenario so that it stays within [1e-9, 1e9]",
        )
    }

    /// Finite coordinates within ±[`MAX_VALUE`].
    ///
    /// # Errors
    /// A coordinate that is not finite or too large.
    pub fn coordinates(field: &str, v: &[f64]) -> Check {
        require(
            v.iter().all(|x| x.is_finite()),
            field,
            v,
            "has a non-finite component",
            "use finite numbers",
        )?;
        require(
            v.iter().all(|x| x.abs() <= MAX_VALUE),
            field,
            v,
            &format!("has a component beyond ±{MAX_VALUE:e}, {WHY_BOUNDED}"),
            "rescale the scenario (or move its origin) so that every coordinate stays within ±1e9",
        )
    }
}

/// A value's `Debug` text without Rust's type names, as a scenario writes it: glam's
/// `DVec2(NaN, 1.0)` is `(NaN, 1.0)`.
///
/// # Example
/// ```
/// use flock_protocols::plain_value;
///
/// assert_eq!(plain_value(&glam::DVec2::new(f64::NAN, 1.0)), "(NaN, 1.0)");
/// assert_eq!(plain_value(&0.5), "0.5");
/// ```
#[must_use]
pub fn plain_value(value: &impl fmt::Debug) -> String {
    format!("{value:?}")
        .replace("DVec2(", "(")
        .replace("DVec3(", "(")
}
