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

// Body angles (ground: 0) in mo2d and in Box2D (its angle plus the constant alpha_b).
double theta_mo2d(const Model& m, int b, const Eigen::VectorXd& q0) {
  return b < 0 ? 0.0 : body_angle(m.bodies[b], q0);
}

double theta_box2d(const Box2DWorld& w, int b) {
  return b < 0 ? 0.0 : w.bodies[b].body->GetAngle() + w.bodies[b].alpha;
}

}  // namespace

BranchWatch::BranchWatch(const Model& m, const Box2DWorld& w, const Eigen::VectorXd& q0) {
  for (int b1 = -1; b1 < static_cast<int>(m.bodies.size()); ++b1)
    for (int b2 = b1 + 1; b2 < static_cast<int>(m.bodies.size()); ++b2) {
      if ((b1 >= 0 && !w.bodies[b1].oriented) || !w.bodies[b2].oriented) continue;
      pairs_.push_back(
          {.body1 = b1, .body2 = b2, .phi0 = theta_mo2d(m, b2, q0) - theta_mo2d(m, b1, q0)});
    }
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
  for (Pair& p : pairs_) {
    const double dm =
        std::fabs(wrap_angle(theta_mo2d(m, p.body2, q0) - theta_mo2d(m, p.body1, q0) - p.phi0));
    const double db =
        std::fabs(wrap_angle(theta_box2d(w, p.body2) - theta_box2d(w, p.body1) - p.phi0));
    p.mo2d_drift = std::fmax(p.mo2d_drift, dm);
    p.box2d_drift = std::fmax(p.box2d_drift, db);
    if (p.departure_time < 0 && db > 0.05) p.departure_time = t;
  }
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

std::string BranchWatch::report(const Model& m) const {
  for (const Pair& p : pairs_) {
    if (p.departure_time < 0 || !(p.mo2d_drift < 1e-6)) continue;
    auto name = [&m](int b) { return b < 0 ? std::string("ground") : m.bodies[b].name; };
    char b[640];
    std::snprintf(b, sizeof b,
                  "Box2D left the assembly branch near t = %.4g s: the angle between '%s' and "
                  "'%s' is constant on mo2d's branch (it moves %.2g rad over the run) but "
                  "departs from it by more than 0.05 rad in Box2D at t = %.4g s (%.3g rad at "
                  "most): Box2D's first-order step crossed a singular position onto another "
                  "branch, so the motion differs from then on because of Box2D, not mo2d",
                  p.departure_time, name(p.body1).c_str(), name(p.body2).c_str(), p.mo2d_drift,
                  p.departure_time, p.box2d_drift);
    return b;
  }
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
