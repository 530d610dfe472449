// Forward dynamics: why the step size collapsed (RunBudget ends the run, run/budget.cpp), named
// from the state where it did: a blow-up (the motion grows without bound), a singular position
// (the constraint Jacobian loses rank), or else a stiff or non-smooth law; each with what helps.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "forward/forward_run.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/kinematics.hpp"

namespace mo2d::detail {

namespace {

// Kinetic energy above this many times the mechanism's energy scale (total mass x max(|g|,
// 1 m/s^2) x its size) is a blow-up: the state grows without bound. (A flywheel of 0.1 kg m^2 at
// 1000 rad/s against 1 kg x 9.81 x 1 m: 5e3.)
constexpr double kBlowUp = 1e6;

const char* singular_help(Integrator i) {
  switch (i) {
    case Integrator::cvode_bdf:
      return "rk4, dopri5, erk6 and erk8 step over singular instants (or --accuracy, which picks "
             "one of them); other tolerances (rtol/atol) may let cvode_bdf pass";
    case Integrator::cvode_adams:
    case Integrator::baumgarte:
      return "cvode_bdf, rk4, dopri5, erk6 and erk8 project on the constraints and pass singular "
             "positions";
    default:
      return "other tolerances (rtol/atol) or rk4 with a fixed step move the steps' stages off "
             "the singular instant";
  }
}

}  // namespace

std::string collapse_cause(ForwardData& d, double t, const double* y,
                           const std::vector<int>& terms) {
  const Model& m = d.m;
  if (y == nullptr) return {};
  const VectorXd q0 = Eigen::Map<const VectorXd>(y, m.n0);
  const VectorXd q1 = Eigen::Map<const VectorXd>(y + m.n0, m.n1);
  if (!q0.allFinite() || !q1.allFinite()) return {};
  double mass = 0;
  for (const auto& b : m.bodies) mass += b.mass;
  const double g = std::max(1.0, std::hypot(m.gravity.x(), m.gravity.y()));
  const double scale = std::max(1e-300, mass * g * m.scale);
  const double kinetic = kinetic_energy(m, q1);
  if (kinetic > kBlowUp * scale) {
    int fastest = 0;  // the quasi-velocity of the largest speed (q1 / col_scale: m/s)
    for (int j = 1; j < m.n1; ++j)
      if (std::abs(q1[j] / d.col_scale[j]) > std::abs(q1[fastest] / d.col_scale[fastest]))
        fastest = j;
    double work = 0;  // of the loads and inputs, integrated with the state
    for (std::size_t k = 0; k < terms.size(); ++k)
      if (terms[k] == kInputWork || terms[k] == kLoadWork) work += y[m.n0 + m.n1 + k];
    const std::string grown =
        "the kinetic energy has grown to " + fmt(kinetic) + " J, " + fmt(kinetic / scale) +
        " times the mechanism's energy scale (mass x g x size = " + fmt(scale) + " J), '" +
        m.rate_labels[fastest] + "' = " + fmt(q1[fastest]);
    if (work >= 0.5 * kinetic)
      return "a blow-up: " + grown + ", supplied by the work of the loads and inputs (" +
             fmt(work) + " J): a load or effort law drives the motion without bound (e.g. one " +
             "growing like exp(t)); no integrator or tolerance follows it: bound the law, or end " +
             "the run earlier";
    return "an instability of the integrator: " + grown + ", not supplied by the loads and " +
           "inputs (their work " + fmt(work) + " J): a stiff element (a stiff spring, a large " +
           "gain) beyond " + to_string(d.o.integrator) + "'s stability: " +
           (d.o.integrator == Integrator::cvode_bdf ? "tighter rtol/atol"
                                                    : "cvode_bdf (stiff mechanisms)") +
           ", or a softer element";
  }
  if (m.m1 > 0) {
    // below kDirectAccept the accelerations are regularized (ForwardData): the step collapses
    // next to a singular position, not only below singular_warning (the 20-loop chain on
    // cvode_bdf before the fix of its Newton matrix: 4.7e-5 of the Cholesky estimate, above
    // 1e-4 by the pivot ratio, at t = 0.7262 s)
    const double piv = d.pivot_indicator(t, q0);
    if (piv < std::max(d.o.singular_warning, ForwardData::kDirectAccept)) {
      const SingularDirection s = singular_direction(d.dense_velocity_rows(t, q0), d.col_scale,
                                                     m.velocity_row_labels, m.rate_labels);
      return "a singular position: the constraint Jacobian is near-singular there "
             "(dimensionless pivot ratio " +
             fmt(piv) + "; nearly dependent constraints " + s.rows +
             ", nearly undetermined motion of " + s.variables +
             "): " + singular_help(d.o.integrator);
    }
  }
  const bool implicit = d.o.integrator == Integrator::cvode_bdf;
  return std::string("neither a singular position nor a blow-up (kinetic energy ") + fmt(kinetic) +
         " J): a stiff element or a law that is not smooth (a jump, a kink, a very " +
         "stiff spring or gain) holds the step down there: " +
         (implicit ? "smooth the law, or loosen rtol/atol"
                   : "cvode_bdf (stiff mechanisms), a smoother law, or looser rtol/atol");
}

}  // namespace mo2d::detail
