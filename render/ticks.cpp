// Round tick values: steps of 1, 2 or 5 times a power of ten; decades on log axes.
#include <cmath>

#include "mo2d/error.hpp"
#include "mo2d/render/plot.hpp"

namespace mo2d {

namespace {

double nice_step(double raw) {
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / p;
  return (f <= 1.0 + 1e-9 ? 1.0 : f <= 2.0 + 1e-9 ? 2.0 : f <= 5.0 + 1e-9 ? 5.0 : 10.0) * p;
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo))
    throw Error("render: tick range [" + std::to_string(lo) + ", " + std::to_string(hi) +
                "] must be finite with lo < hi");
  const double step = nice_step((hi - lo) / std::max(target, 1));
  std::vector<double> t;
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; k += 1.0)
    t.push_back(std::abs(k) < 0.5 ? 0.0 : k * step);
  return t;
}

std::vector<double> decade_ticks(double lo, double hi) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo > 0) || !(hi > lo))
    throw Error("render: log tick range [" + std::to_string(lo) + ", " + std::to_string(hi) +
                "] must be finite with 0 < lo < hi");
  const int k0 = static_cast<int>(std::ceil(std::log10(lo) - 1e-9));
  const int k1 = static_cast<int>(std::floor(std::log10(hi) + 1e-9));
  const int every = std::max(1, (k1 - k0 + 7) / 8);  // at most about 8 labelled decades
  std::vector<double> t;
  for (int k = k0; k <= k1; k += every) t.push_back(std::pow(10.0, k));
  return t;
}

}  // namespace mo2d
