// Warnings for reduced unilateral springs whose tension has the wrong sign (dynamics/slack.hpp).
#include "dynamics/slack.hpp"

#include <cmath>
#include <sstream>

namespace mo2d::detail {

void reduced_spring_slack(const Model& m, const Trajectory& r, std::vector<std::string>& warnings) {
  const Eigen::Index N = r.reactions.rows();
  for (const ReducedSpring& s : m.reduced_springs) {
    if (s.spring.acts == SpringActs::both || s.reaction >= r.reactions.cols()) continue;
    // the sign the spring cannot carry: a rope pushing (T < 0), a bump stop pulling (T > 0)
    const double sign = s.spring.acts == SpringActs::tension_only ? -1 : 1;
    const auto T = r.reactions.col(s.reaction);
    const double tol = 1e-9 * T.cwiseAbs().maxCoeff();
    Eigen::Index first = -1, worst = -1, count = 0;
    for (Eigen::Index k = 0; k < N; ++k) {
      if (!(sign * T[k] > tol)) continue;
      if (first < 0) first = k;
      if (worst < 0 || sign * T[k] > sign * T[worst]) worst = k;
      ++count;
    }
    if (first < 0) continue;
    std::ostringstream w;
    w << "spring '" << s.spring.name
      << "' (reduced to a constraint, acts: " << (sign < 0 ? "tension" : "compression")
      << ") would " << (sign < 0 ? "go slack" : "pull") << " at t = " << r.time[first]
      << " s: tension " << T[first] << " N (" << count << " of " << N << " output samples, worst "
      << T[worst] << " N at t = " << r.time[worst]
      << " s); the constraint held it there: model it as a spring (no reduce) where it can "
         "go slack";
    warnings.push_back(w.str());
  }
}

}  // namespace mo2d::detail
