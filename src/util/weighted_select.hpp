// Weighted quantiles by selection: the value at which the cumulative weight of values taken in
// increasing order first reaches a threshold, without sorting (the hold analysis' statistics).
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>

namespace frictal::util {

/// A value and its weight.
struct ValueWeight {
  double v, w;
};

/// The weighted quantiles of e[0..n) (reordered in place) at cumulative weights thr[0..k)
/// (increasing): out[j] = the least value v whose cumulative weight W(<= v) reaches thr[j] (the
/// greatest value where none does), i.e. the value at which a scan of the values sorted by value,
/// adding up their weights, first reaches thr[j]. By selection (three-way partitions around a
/// median of three, recursing into the parts that hold a threshold): expected linear time, no
/// sort. The weights are added up in another order than such a scan's, so the sums may differ
/// from its by rounding. `below`: the weight of the values below e[0..n) (0 for a whole set).
/// `depth`: partitions before it sorts what is left (worst case O(n log n), as introsort).
inline void weighted_select(ValueWeight* e, std::size_t n, double below, const double* thr, std::size_t k, double* out,
                            int depth = 64) {
  while (k > 0) {
    if (n == 0) return;
    if (n <= 16 || depth-- <= 0) {  // a few values (or unlucky pivots, as introsort): sort and scan
      std::sort(e, e + n, [](const ValueWeight& x, const ValueWeight& y) { return x.v < y.v; });
      double cum = below;
      std::size_t i = 0;
      for (std::size_t j = 0; j < k; ++j) {
        while (i + 1 < n && !(cum + e[i].w >= thr[j])) cum += e[i++].w;
        out[j] = e[i].v;
      }
      return;
    }
    // Median of three values as the pivot.
    double a = e[0].v, b = e[n / 2].v, c = e[n - 1].v;
    if (b < a) std::swap(a, b);
    if (c < b) b = std::max(a, c);
    const double pv = b;
    // Three-way partition: [0, lt) < pv, [lt, gt) == pv, [gt, n) > pv (Dutch national flag).
    std::size_t lt = 0, i = 0, gt = n;
    while (i < gt) {
      if (e[i].v < pv)
        std::swap(e[lt++], e[i++]);
      else if (pv < e[i].v)
        std::swap(e[i], e[--gt]);
      else
        ++i;
    }
    double wl = below, we = 0;
    for (std::size_t q = 0; q < lt; ++q) wl += e[q].w;
    for (std::size_t q = lt; q < gt; ++q) we += e[q].w;
    // Thresholds reached within the lower part, at the pivot, above it.
    std::size_t jl = 0;
    while (jl < k && thr[jl] <= wl) ++jl;
    std::size_t je = jl;
    while (je < k && (thr[je] <= wl + we || gt == n)) out[je++] = pv;
    if (jl > 0) weighted_select(e, lt, below, thr, jl, out, depth);
    // The upper part, iteratively.
    e += gt;
    n -= gt;
    below = wl + we;
    thr += je;
    out += je;
    k -= je;
  }
}

}  // namespace frictal::util
