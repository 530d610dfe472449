// Branch watch of the forward cross-check; see box2d_branch.hpp.
#include "box2d_branch.hpp"

#include <cmath>
#include <cstdio>

namespace mo2d::crosscheck_detail {

namespace {

// sin(theta_2 - theta_1) in mo2d (from q0) and in Box2D (its bodies' angles: the same up to the
// constant alpha_b of each body, added back).
double mo2d_indicator(const Model& m, int b1, int b2, const Eigen::VectorXd& q0) {
  const double t1 = b1 < 0 ? 0.0 : body_angle(m.bodies[b1], q0);
  const double t2 = b2 < 0 ? 0.0 : body_angle(m.bodies[b2], q0);
  return std::sin(t2 - t1);
}

double box2d_indicator(const Box2DWorld& w, int b1, int b2) {
  auto theta = [&w](int b) {
    return b < 0 ? 0.0 : w.bodies[b].body->GetAngle() + w.bodies[b].alpha;
  };
  return std::sin(theta(b2) - theta(b1));
}

}  // namespace

BranchWatch::BranchWatch(const Model& m, const Box2DWorld& w, const Eigen::VectorXd& q0) {
  for (const JointMap& j : w.joints) {
    if (j.kind != JointKind::revolute) continue;
    const bool o1 = j.body1 < 0 || w.bodies[j.body1].oriented;
    const bool o2 = j.body2 < 0 || w.bodies[j.body2].oriented;
    if (!o1 || !o2) continue;
    const double s = mo2d_indicator(m, j.body1, j.body2, q0);
    if (std::fabs(s) < 1e-3) continue;  // starts at a singular position: no branch to keep
    joints_.push_back(
        {.name = j.name, .body1 = j.body1, .body2 = j.body2, .sign0 = s > 0 ? 1. : -1.});
  }
}

void BranchWatch::sample(const Model& m, const Box2DWorld& w, const Eigen::VectorXd& q0, double t) {
  for (Joint& j : joints_) {
    const double sm = mo2d_indicator(m, j.body1, j.body2, q0);
    const double sb = box2d_indicator(w, j.body1, j.body2);
    if (j.sign0 * sm < j.mo2d_min) {
      j.mo2d_min = j.sign0 * sm;
      j.mo2d_min_time = t;
    }
    if (j.flip_time < 0 && j.sign0 * sb < 0) {
      j.flip_time = t;
      j.flip_box2d = sb;
      j.flip_mo2d = sm;
    }
  }
}

std::string BranchWatch::report() const {
  for (const Joint& j : joints_) {
    if (j.flip_time < 0 || !(j.mo2d_min > 0)) continue;  // Box2D kept it, or mo2d changed too
    char b[512];
    std::snprintf(b, sizeof b,
                  "Box2D left the assembly branch at joint '%s' near t = %.4g s: the branch "
                  "indicator sin(theta2 - theta1) is %+.3g in Box2D and %+.3g in mo2d there; "
                  "mo2d's keeps its sign over the whole run (closest to the singular position "
                  "%+.3g at t = %.4g s), so the motion differs from then on because of Box2D's "
                  "step across the singular position, not because of mo2d",
                  j.name.c_str(), j.flip_time, j.flip_box2d, j.flip_mo2d, j.sign0 * j.mo2d_min,
                  j.mo2d_min_time);
    return b;
  }
  return "";
}

}  // namespace mo2d::crosscheck_detail
