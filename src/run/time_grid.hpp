// The output grid of every run: `samples` equally spaced times from t0 to t1, the last one t1
// exactly. t0 + (t1 - t0) k / (n - 1) rounds: at k = n - 1 it can land one ulp past t1 (0.123 with
// n = 18, 0.7771 with n = 22), a time no step that ends at t1 reaches, and a driver that waits for
// it takes steps of length 0 for ever. Every driver and recorder takes its times from here.
#pragma once

#include <algorithm>

namespace mo2d::detail {

// t_k of the grid t0 = t_0 <= t_1 <= ... <= t_{n-1} = t1 (non-decreasing in k; t1 exactly at the
// end, t0 exactly at the start; a single sample is at t0)
inline double sample_time(double t0, double t1, long long samples, long long k) {
  if (samples <= 1 || k <= 0) return t0;
  if (k >= samples - 1) return t1;
  return std::min(t1, t0 + (t1 - t0) * static_cast<double>(k) / static_cast<double>(samples - 1));
}

}  // namespace mo2d::detail
