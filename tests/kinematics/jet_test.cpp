// Jet: exact first and second derivatives of every function a motion or a user constraint uses.
#include <gtest/gtest.h>

#include <cmath>

#include "mo2d/mo2d.hpp"

using namespace mo2d;

TEST(Jet, DerivativesMatchFiniteDifferences) {
  auto f = [](Jet t) {
    return sin(2 * t) * exp(t / 3) / (1 + t * t) + pow(t + 2, 1.5) + atan2(t + 0.3, 1 - t) +
           sqrt(t + 4) * log(t + 3) + tan(t / 4);
  };
  const double h = 1e-4;
  for (double t : {-0.7, 0.1, 0.9}) {
    const Jet j = f(Jet(t, 1, 0));
    const double fp = f(Jet(t + h)).v, fm = f(Jet(t - h)).v, f0 = f(Jet(t)).v;
    EXPECT_NEAR(j.v, f0, 1e-15);
    EXPECT_NEAR(j.d, (fp - fm) / (2 * h), 1e-7);
    EXPECT_NEAR(j.dd, (fp - 2 * f0 + fm) / (h * h), 1e-5);
  }
}
