#pragma once
// The Butcher tables of mo2d's explicit Runge-Kutta drivers (src/forward/forward_rk.cpp): rk4 and
// dopri5 written out, erk6 and erk8 copied from SUNDIALS ARKODE (ARKodeButcherTable_LoadERK).
#include <array>

#include "mo2d/forward.hpp"

namespace mo2d::detail {

// Explicit Butcher tableau, up to 13 stages. bhat: embedded lower-order weights (adaptive only).
constexpr int kMaxStages = 13;
struct Tableau {
  int stages = 0;
  int order = 0;           // of the propagated solution (b)
  int embedded_order = 0;  // of bhat; the error estimate is O(h^(embedded_order + 1))
  std::array<std::array<double, kMaxStages>, kMaxStages> a{};
  std::array<double, kMaxStages> b{}, bhat{}, c{};
  bool embedded = false;
};

// The table of an explicit integrator (rk4 for any other).
Tableau tableau(Integrator i);

}  // namespace mo2d::detail
