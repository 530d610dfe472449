#include <cmath>
#include <cstdio>
#include <mo2d/scene.hpp>
int main() {  // fourbar.yaml: the crank does no net work over one revolution
  const mo2d::Scene scene = mo2d::load_scene("fourbar.yaml");
  const mo2d::Trajectory r = mo2d::inverse_dynamics(mo2d::build_scene_model(scene), scene.motion,
                                                    mo2d::inverse_options(scene));
  const Eigen::VectorXd power = r.efforts.col(r.effort("crank_pivot.torque")) * 2 * M_PI;
  double work = 0;  // the trapezoidal rule over the samples
  for (int k = 1; k < r.time.size(); ++k)
    work += (power[k] + power[k - 1]) / 2 * (r.time[k] - r.time[k - 1]);
  std::printf("peak power %.3f W, work per revolution %.1e J\n", power.cwiseAbs().maxCoeff(), work);
  return std::abs(work) < 1e-9 ? 0 : 1;
}
