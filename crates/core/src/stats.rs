//! Sample statistics: mean, sample standard deviation, standard error, median.
//!
//! One copy for the whole crate (figures, tables and benchmarks), so that "median" and "SD" mean
//! the same thing wherever a number is printed.

/// The arithmetic mean; NaN for an empty sample.
///
/// # Examples
/// ```
/// assert_eq!(hw3_core::stats::mean(&[1.0, 2.0, 6.0]), 3.0);
/// assert!(hw3_core::stats::mean(&[]).is_nan());
/// ```
#[must_use]
pub fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len() as f64
}

/// The sample standard deviation (Bessel's n − 1 divisor); NaN for fewer than two values.
///
/// # Examples
/// ```
/// assert_eq!(hw3_core::stats::sample_sd(&[1.0, 3.0]), 2f64.sqrt());
/// assert!(hw3_core::stats::sample_sd(&[1.0]).is_nan());
/// ```
#[must_use]
pub fn sample_sd(values: &[f64]) -> f64 {
    if values.len() < 2 {
        return f64::NAN;
    }
    let m = mean(values);
    (values.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (values.len() - 1) as f64).sqrt()
}

/// The standard error of the mean, `sample_sd / √n`; NaN for fewer than two values.
///
/// # Examples
/// ```
/// let se = hw3_core::stats::standard_error(&[1.0, 3.0, 1.0, 3.0]);
/// assert!((se - 1.0 / 3f64.sqrt()).abs() < 1e-15); // SD √(4/3) over √4
/// ```
#[must_use]
pub fn standard_error(values: &[f64]) -> f64 {
    sample_sd(values) / (values.len() as f64).sqrt()
}

/// The median as an observed value: the element at index `n / 2` of the sorted sample (for an
/// even `n`, the upper of the two middle values, never their average). Sorts `values` in place,
/// NaN last ([`f64::total_cmp`]).
///
/// # Panics
/// If `values` is empty.
///
/// # Examples
/// ```
/// assert_eq!(hw3_core::stats::median(&mut [3.0, 1.0, 2.0]), 2.0);
/// assert_eq!(hw3_core::stats::median(&mut [4.0, 1.0, 2.0, 3.0]), 3.0);
/// ```
#[must_use]
pub fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sd_and_standard_error_of_a_known_sample() {
        // 2, 4, 4, 4, 5, 5, 7, 9: mean 5, squared deviations sum to 32, so SD = √(32/7).
        let sample = [2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0];
        assert_eq!(mean(&sample), 5.0);
        assert!((sample_sd(&sample) - (32.0_f64 / 7.0).sqrt()).abs() < 1e-15);
        assert!((standard_error(&sample) - (32.0_f64 / 7.0 / 8.0).sqrt()).abs() < 1e-15);
        assert_eq!(median(&mut sample.clone()), 5.0);
    }
}
