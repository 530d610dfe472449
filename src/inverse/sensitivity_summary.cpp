// The summary values of a column and their derivatives to a parameter (mo2d/sensitivity.hpp,
// summary_derivative): the values as mo2d optimize reads them (optimize/run_values.cpp), the
// derivatives by the chain rule through the same formulas.
#include <cmath>

#include "mo2d/sensitivity.hpp"

namespace mo2d {

namespace {

// Time integral of f over the samples (trapezoid rule, as optimize/run_values.cpp).
double integral(const Eigen::Ref<const Eigen::VectorXd>& t,
                const Eigen::Ref<const Eigen::VectorXd>& f) {
  double s = 0;
  for (Eigen::Index k = 1; k < t.size(); ++k) s += 0.5 * (f[k] + f[k - 1]) * (t[k] - t[k - 1]);
  return s;
}

}  // namespace

SummaryDerivative summary_derivative(const Eigen::Ref<const Eigen::VectorXd>& t,
                                     const Eigen::Ref<const Eigen::VectorXd>& x,
                                     const Eigen::Ref<const Eigen::VectorXd>& dx) {
  SummaryDerivative s;
  if (x.size() == 0) return s;
  Eigen::Index kpeak = 0, kmax = 0, kmin = 0;
  s.peak = x.cwiseAbs().maxCoeff(&kpeak);
  s.max = x.maxCoeff(&kmax);
  s.min = x.minCoeff(&kmin);
  // |x| at its largest sample: the sign of x there (a peak of 0 has no derivative: +dx taken)
  s.d_peak = x[kpeak] < 0 ? -dx[kpeak] : dx[kpeak];
  s.d_max = dx[kmax];
  s.d_min = dx[kmin];
  s.peak_to_peak = s.max - s.min;
  s.d_peak_to_peak = s.d_max - s.d_min;
  const double T = t.size() > 1 ? t[t.size() - 1] - t[0] : 0;
  if (T > 0) {
    s.mean = integral(t, x) / T;
    s.d_mean = integral(t, dx) / T;
    s.rms = std::sqrt(integral(t, x.cwiseAbs2()) / T);
    // d/dp sqrt(I / T) = (dI/dp) / (2 T rms), dI/dp = trapezoid of 2 x dx
    s.d_rms = s.rms > 0 ? integral(t, x.cwiseProduct(dx)) / (T * s.rms) : 0.0;
  } else {
    s.mean = x[0];
    s.d_mean = dx[0];
    s.rms = std::abs(x[0]);
    s.d_rms = x[0] < 0 ? -dx[0] : dx[0];
  }
  return s;
}

}  // namespace mo2d
