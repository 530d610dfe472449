// The Butcher tables of the explicit Runge-Kutta drivers (rk_tableau.hpp).
#include "forward/rk_tableau.hpp"

#include <cstdio>
#include <string>
// after <cstdio>: arkode_butcher.h uses FILE without including <stdio.h>
#include <arkode/arkode_butcher_erk.h>

#include "mo2d/error.hpp"

namespace mo2d::detail {
namespace {

Tableau classical_rk4() {
  Tableau t;
  t.stages = 4;
  t.order = 4;
  t.a[1][0] = 0.5;
  t.a[2][1] = 0.5;
  t.a[3][2] = 1.0;
  t.b = {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6};
  t.c = {0, 0.5, 0.5, 1};
  return t;
}

// Dormand & Prince (1980), "A family of embedded Runge-Kutta formulae", J. Comp. Appl. Math. 6:
// RK5(4)7M. The 5th-order weights propagate the solution (local extrapolation).
Tableau dormand_prince_54() {
  Tableau t;
  t.stages = 7;
  t.order = 5;
  t.embedded_order = 4;
  t.embedded = true;
  t.c = {0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1, 1};
  t.a[1] = {1.0 / 5};
  t.a[2] = {3.0 / 40, 9.0 / 40};
  t.a[3] = {44.0 / 45, -56.0 / 15, 32.0 / 9};
  t.a[4] = {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729};
  t.a[5] = {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656};
  t.a[6] = {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84};
  t.b = {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0};
  t.bhat = {5179.0 / 57600, 0,       7571.0 / 16695, 393.0 / 640, -92097.0 / 339200,
            187.0 / 2100,   1.0 / 40};
  return t;
}

// An embedded table of ARKODE (b: the propagated solution, d: the embedding), copied.
Tableau arkode_table(ARKODE_ERKTableID id) {
  ARKodeButcherTable bt = ARKodeButcherTable_LoadERK(id);
  if (bt == nullptr || bt->stages > kMaxStages || bt->d == nullptr) {
    ARKodeButcherTable_Free(bt);
    throw Error("forward dynamics: SUNDIALS ARKODE did not provide Butcher table " +
                std::to_string(static_cast<int>(id)));
  }
  Tableau t;
  t.stages = bt->stages;
  t.order = bt->q;
  t.embedded_order = bt->p;
  t.embedded = true;
  for (int i = 0; i < t.stages; ++i) {
    for (int j = 0; j < i; ++j) t.a[i][j] = bt->A[i][j];
    t.b[i] = bt->b[i];
    t.bhat[i] = bt->d[i];
    t.c[i] = bt->c[i];
  }
  ARKodeButcherTable_Free(bt);
  return t;
}

}  // namespace

Tableau tableau(Integrator i) {
  switch (i) {
    case Integrator::dopri5:
      return dormand_prince_54();
    case Integrator::erk6:  // Verner (1978) 6(5), 8 stages
      return arkode_table(ARKODE_VERNER_8_5_6);
    case Integrator::erk8:  // Fehlberg (1968) 8(7), 13 stages
      return arkode_table(ARKODE_FEHLBERG_13_7_8);
    default:
      return classical_rk4();
  }
}

}  // namespace mo2d::detail
