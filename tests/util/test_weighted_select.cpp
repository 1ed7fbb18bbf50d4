// Weighted quantiles by selection against a sort of the values and a scan of their weights.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "util/random.hpp"
#include "util/weighted_select.hpp"

using frictal::util::ValueWeight;
using frictal::util::weighted_select;

namespace {

// The reference: sort by value, add the weights up, the first value whose sum reaches t (the
// last value where none does).
double scan_quantile(std::vector<ValueWeight> e, double t) {
  std::stable_sort(e.begin(), e.end(), [](const ValueWeight& x, const ValueWeight& y) { return x.v < y.v; });
  double cum = 0;
  for (const ValueWeight& x : e) {
    cum += x.w;
    if (cum >= t) return x.v;
  }
  return e.back().v;
}

}  // namespace

TEST(WeightedSelect, HandWorkedQuantiles) {
  // Sorted: 1 (weight 1), 2 (weight 2), 3 (weight 1): cumulative 1, 3, 4.
  const std::vector<ValueWeight> e0{{3, 1}, {1, 1}, {2, 2}};
  const double thr[] = {0.5, 1.0, 1.5, 3.0, 3.5, 5.0};
  const double want[] = {1, 1, 2, 2, 3, 3};  // a threshold past the total: the greatest value
  std::vector<ValueWeight> e = e0;
  double out[6];
  weighted_select(e.data(), e.size(), 0.0, thr, 6, out);
  for (int j = 0; j < 6; ++j) EXPECT_EQ(out[j], want[j]) << "threshold " << thr[j];
}

TEST(WeightedSelect, MatchesSortAndScanWithTiesAndExactSums) {
  // Weights in eighths (every partial sum exact, in any order), values with many ties, sets from
  // 1 to 3000 values: the selection must give the scan's value at every threshold, including
  // thresholds that fall exactly on a jump of the cumulative weight.
  frictal::util::Rng rng(7);
  for (int trial = 0; trial < 400; ++trial) {
    const std::size_t n = 1 + static_cast<std::size_t>(rng.uniform() * (trial < 300 ? 40 : 3000));
    const int distinct = 1 + static_cast<int>(rng.uniform() * static_cast<double>(n));
    std::vector<ValueWeight> e(n);
    double total = 0;
    for (ValueWeight& x : e) {
      x.v = 0.25 * static_cast<int>(rng.uniform() * distinct) - 3;
      x.w = (1 + static_cast<int>(rng.uniform() * 16)) / 8.0;
      total += x.w;
    }
    std::vector<double> thr;
    for (double q : {0.05, 0.25, 0.5, 0.95}) thr.push_back(q * total);
    thr.push_back(e[0].w);  // on a jump (or inside a tie group)
    thr.push_back(total);
    thr.push_back(total * 2);  // never reached: the greatest value
    std::sort(thr.begin(), thr.end());
    std::vector<double> out(thr.size());
    std::vector<ValueWeight> work = e;
    weighted_select(work.data(), work.size(), 0.0, thr.data(), thr.size(), out.data());
    for (std::size_t j = 0; j < thr.size(); ++j)
      ASSERT_EQ(out[j], scan_quantile(e, thr[j])) << "trial " << trial << " n " << n << " threshold " << thr[j];
    // Partitions cut short (the sort that bounds the worst case) give the same values.
    std::vector<ValueWeight> cut = e;
    std::vector<double> out_cut(thr.size());
    weighted_select(cut.data(), cut.size(), 0.0, thr.data(), thr.size(), out_cut.data(), trial % 3);
    EXPECT_EQ(out_cut, out) << "trial " << trial;
    // The values are only reordered.
    std::vector<double> a, b;
    for (const ValueWeight& x : e) a.push_back(x.v * 100 + x.w);
    for (const ValueWeight& x : work) b.push_back(x.v * 100 + x.w);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b);
  }
}
