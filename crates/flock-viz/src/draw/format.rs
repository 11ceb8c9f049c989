//! Number formatting shared by titles, tick labels and the player's data: fixed decimals with
//! trailing zeros trimmed, never `-0`, so the same number always prints the same way.

/// `x` with at most `decimals` decimals, trailing zeros (and a trailing point) removed, `-0` as
/// `0`; `nan`, `inf`, `-inf` for non-finite values.
pub(crate) fn number(x: f64, decimals: usize) -> String {
    if !x.is_finite() {
        return if x.is_nan() {
            "nan".to_owned()
        } else if x > 0.0 {
            "inf".to_owned()
        } else {
            "-inf".to_owned()
        };
    }
    let mut s = format!("{x:.decimals$}");
    if s.contains('.') {
        while s.ends_with('0') {
            s.pop();
        }
        if s.ends_with('.') {
            s.pop();
        }
    }
    if s == "-0" {
        s = "0".to_owned();
    }
    s
}

/// A tick label: plain decimals for moderate magnitudes, `1e-5`/`2.5e3` style otherwise.
pub(crate) fn tick(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 || (1e-3..1e5).contains(&a) {
        number(x, 4)
    } else {
        let exponent = a.log10().floor();
        let mantissa = x / 10f64.powf(exponent);
        // Rounding may give a mantissa of 10: renormalise.
        let (mantissa, exponent) = if number(mantissa.abs(), 2) == "10" {
            (mantissa / 10.0, exponent + 1.0)
        } else {
            (mantissa, exponent)
        };
        let m = number(mantissa, 2);
        if m == "1" {
            format!("1e{exponent}")
        } else if m == "-1" {
            format!("-1e{exponent}")
        } else {
            format!("{m}e{exponent}")
        }
    }
}

/// A cell label: `digits` significant digits for moderate magnitudes (`-39.2`, `3.86`, `0.85`),
/// the exponent form of [`tick`] otherwise, so that a label fits in a heatmap cell.
pub(crate) fn significant(x: f64, digits: i32) -> String {
    let a = x.abs();
    if a == 0.0 || !(1e-3..1e5).contains(&a) {
        return tick(x);
    }
    let decimals = (digits - 1 - a.log10().floor() as i32).max(0);
    number(x, decimals as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_trim_and_never_print_minus_zero() {
        assert_eq!(number(12.5, 2), "12.5");
        assert_eq!(number(12.0, 2), "12");
        assert_eq!(number(-0.0001, 2), "0");
        assert_eq!(number(f64::NAN, 2), "nan");
        assert_eq!(number(1234.5678, 0), "1235");
    }

    #[test]
    fn ticks_switch_to_exponents() {
        assert_eq!(tick(0.5), "0.5");
        assert_eq!(tick(1e-6), "1e-6");
        assert_eq!(tick(2.5e-7), "2.5e-7");
        assert_eq!(tick(1e6), "1e6");
        assert_eq!(tick(0.0), "0");
    }

    #[test]
    fn cell_labels_keep_three_significant_digits() {
        assert_eq!(significant(-39.2396, 3), "-39.2");
        assert_eq!(significant(3.8585, 3), "3.86");
        assert_eq!(significant(0.85, 3), "0.85");
        assert_eq!(significant(1.0, 3), "1");
        assert_eq!(significant(1234.6, 3), "1235");
        assert_eq!(significant(2.5e-7, 3), "2.5e-7");
    }
}
