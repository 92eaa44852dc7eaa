//! Means over an ensemble of starts and their standard errors.

use flexdem_geom::Real;

/// Consecutive starts per block of [`block_standard_error`].
const BLOCK: usize = 10;

/// Mean of `x`.
pub(super) fn mean(x: &[Real]) -> Real {
    x.iter().sum::<Real>() / x.len().max(1) as Real
}

/// Sample standard deviation of `x`.
pub(super) fn standard_deviation(x: &[Real]) -> Real {
    let m = mean(x);
    (x.iter().map(|v| (v - m).powi(2)).sum::<Real>() / (x.len().max(2) - 1) as Real).sqrt()
}

/// The standard error of the mean of `x` from the means of its blocks of [`BLOCK`]
/// consecutive values: `s_b/√n_b`, where `s_b` is the standard deviation of the `n_b` block
/// means. Values correlated with their neighbours make the block means spread more than
/// `s/√BLOCK`, so this is larger than `s/√n` and does not overstate what the mean knows.
pub(super) fn block_standard_error(x: &[Real]) -> Real {
    let means: Vec<Real> = x.chunks_exact(BLOCK).map(mean).collect();
    standard_deviation(&means) / (means.len() as Real).sqrt()
}

/// `x` in words: its mean ± [`block_standard_error`], standard deviation and range, with
/// `digits` decimals.
pub(super) fn describe(x: &[Real], digits: usize) -> String {
    let low = x.iter().copied().fold(Real::INFINITY, Real::min);
    let high = x.iter().copied().fold(Real::NEG_INFINITY, Real::max);
    format!(
        "mean {:.digits$} ± {:.digits$} (standard error), standard deviation {:.digits$}, \
         {low:.digits$} to {high:.digits$}",
        mean(x),
        block_standard_error(x),
        standard_deviation(x)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn independent_blocks_give_the_usual_standard_error() {
        // 20 blocks whose means are ±1 alternately (s_b = √(20/19)), each block constant
        let x: Vec<Real> =
            (0..200).map(|i| if (i / BLOCK) % 2 == 0 { 1.0 } else { -1.0 }).collect();
        let expected = (20.0 / 19.0 as Real).sqrt() / 20.0f64.sqrt();
        assert!((block_standard_error(&x) - expected).abs() < 1e-12);
        // the same values taken as independent would claim a standard error √10 smaller
        let naive = standard_deviation(&x) / (x.len() as Real).sqrt();
        assert!(block_standard_error(&x) > 3.0 * naive);
    }

    #[test]
    fn mean_and_standard_deviation() {
        let x = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(mean(&x), 2.5);
        assert!((standard_deviation(&x) - (5.0 / 3.0 as Real).sqrt()).abs() < 1e-15);
    }
}
