#pragma once
// Statistics of the racing tuner (engine/tune): ranks within a block, the
// Friedman test and irace's elimination by Conover's post-hoc test, the paired
// Wilcoxon signed-rank test, quantiles, medians and a bootstrap interval.
// +inf (a run that missed its target) ranks after every finite value and ties
// with other +inf.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace chaosweep {

// Ranks 1..n of v, ties given their mean rank.
std::vector<double> ranks_with_ties(std::span<const double> v);

// Friedman test of k treatments (columns) over `blocks` blocks (rows) of
// `values` (row-major, blocks x k). rank_sums[j]: sum over blocks of column
// j's within-block rank. statistic: the tie-corrected Friedman statistic
// T1 = (k-1) * sum_j (R_j - b(k+1)/2)^2 / (A1 - C1), with A1 = sum of squared ranks,
// C1 = b k (k+1)^2 / 4 (Conover 1999, as irace and R's friedman.test); p_value from
// chi-square with k-1 degrees of freedom; when A1 == C1 (all tied) statistic 0, p 1.
// Throws std::invalid_argument when values.size() != blocks * k.
struct FriedmanResult {
  double statistic = 0;
  double p_value = 1;
  std::vector<double> rank_sums;
};
FriedmanResult friedman(std::span<const double> values, std::size_t blocks, std::size_t k);

// irace's F-race elimination at `confidence` (e.g. 0.95): when the Friedman
// p-value < 1 - confidence, keep the configurations j with
// |R_j - R_best| <= t_{1-alpha/2, (b-1)(k-1)} * sqrt(2 b (A1 - sum_j R_j^2 / b) / ((b-1)(k-1))),
// R_best the smallest rank sum (Conover's pairwise comparison, as irace's race.R
// does); else keep all. Needs blocks >= 2 and k >= 2 (k == 1: keep it). Returns a keep mask (size k).
// With k == 2, irace uses the same formula; do likewise.
std::vector<bool> friedman_survivors(std::span<const double> values, std::size_t blocks, std::size_t k,
                                     double confidence);

// Two-sided p-value of the paired Wilcoxon signed-rank test of a vs b
// (differences a_i - b_i; zero differences dropped (Wilcoxon's method); +inf - +inf counts as 0;
// +inf - finite as +inf: ranks of |d| with ties averaged, so infinite
// differences rank highest). Exact distribution when n <= 50 and there are no ties among |d|,
// else the normal approximation with tie correction and continuity correction (as R's wilcox.test).
// n == 0 (all differences zero): 1. Throws std::invalid_argument when a and b differ in size.
double wilcoxon_signed_rank_p(std::span<const double> a, std::span<const double> b);

// Distribution functions and quantiles (p in (0, 1), df > 0).
double chi2_cdf(double x, double df);
double chi2_quantile(double p, double df);
double student_t_cdf(double x, double df);
double student_t_quantile(double p, double df);

// The median (the mean of the two middle values for an even count; +inf when
// either middle value is +inf); NaN for an empty span.
double median(std::span<const double> v);

// Percentile bootstrap interval of the median at `level` (e.g. 0.95) from
// `resamples` resamples drawn with a splitmix64 stream seeded by `seed`
// (deterministic: same inputs, same interval, on every machine). Bounds may
// be +inf. Empty input: {NaN, NaN}. The bounds are order statistics of the
// resampled medians (no interpolation, so an infinite bound stays exact):
// with R resamples and alpha = 1 - level, lo is the floor(R alpha/2)+1-th
// smallest and hi the ceil(R (1 - alpha/2))-th; resamples < 1 counts as 1.
struct Interval {
  double lo = 0, hi = 0;
};
Interval bootstrap_median_interval(std::span<const double> v, double level, int resamples, std::uint64_t seed);

}  // namespace chaosweep
