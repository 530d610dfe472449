#pragma once
// Private to mo2d_box2d: whether Box2D left the assembly branch mo2d stays on (a forward
// cross-check's disagreement caused by Box2D itself).
//
// The indicator of a revolute joint between two oriented bodies (or one and the ground) is
// s = sin(theta_2 - theta_1): on which side of body 1's line body 2 lies, the "elbow up / down"
// of a loop closed at that joint. A loop can only change branch through a singular position, where
// s = 0 for one of its joints. When mo2d's s keeps its sign over the whole run (it approaches the
// singular position and turns back) while Box2D's changes sign, Box2D's first-order step has
// crossed the singular position: the motion differs from then on because of Box2D.
//
// A second indicator covers branches that differ by a relative angle (the double four-bar's
// parallelogram, whose cranks stay parallel, against its anti-parallelogram): the relative angle
// of two bodies that mo2d keeps constant over the whole run (within 1e-6 rad: an invariant of its
// branch) while Box2D's moves away from it by more than 0.05 rad.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "box2d_world.hpp"

namespace mo2d::crosscheck_detail {

class BranchWatch {
 public:
  BranchWatch(const Model& m, const Box2DWorld& w, const Eigen::VectorXd& q0);
  // One compared instant: mo2d's coordinates q0 and Box2D's bodies at time t.
  void sample(const Model& m, const Box2DWorld& w, const Eigen::VectorXd& q0, double t);
  // "" if no joint's indicator changed sign in Box2D alone; else the evidence (joint, times,
  // values).
  std::string report(const Model& m) const;

 private:
  struct Joint {
    std::string name;
    int body1 = -1, body2 = -1;
    double sign0 = 0;                      // sign of mo2d's s at t0
    double mo2d_min = 1e300;               // min over the run of sign0 * s (mo2d)
    double mo2d_min_time = 0;              // its time
    double flip_time = -1;                 // first instant Box2D's sign0 * s < 0 (-1: none)
    double flip_box2d = 0, flip_mo2d = 0;  // s of both engines then
  };
  std::vector<Joint> joints_;
  struct Pair {
    int body1 = -1, body2 = -1;
    double phi0 = 0;             // mo2d's theta_2 - theta_1 at t0
    double mo2d_drift = 0;       // max |mo2d's phi - phi0| over the run
    double box2d_drift = 0;      // max |Box2D's phi - phi0|
    double departure_time = -1;  // first instant Box2D's |phi - phi0| > 0.05 rad
  };
  std::vector<Pair> pairs_;
};

}  // namespace mo2d::crosscheck_detail
