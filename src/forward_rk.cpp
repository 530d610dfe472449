// Forward dynamics: fixed-step Runge-Kutta drivers (rk4 with projection; baumgarte without).
#include <algorithm>
#include <cmath>

#include "forward_data.hpp"
#include "mo2d/dynamics.hpp"

namespace mo2d::detail {

void run_rk4(const Model& m, ForwardData& d, const State& s0, const ForwardOptions& o,
             Recorder& rec) {
  const bool baum = o.integrator == Integrator::baumgarte;
  const int n0 = m.n0, n1 = m.n1;
  VectorXd q0 = s0.q0, q1 = s0.q1;
  double W = 0, D = 0, t = o.t0;
  // state derivative: (q1.head(n0), a1, input power u.B^T q1, damper power)
  VectorXd k0[4], k1[4], kw(4), kd(4);
  for (int i = 0; i < 4; ++i) k0[i].resize(n0), k1[i].resize(n1);
  VectorXd y0(n0), y1(n1);
  auto deriv = [&](int i, double tt, const VectorXd& x0, const VectorXd& x1) {
    d.accelerations(tt, x0, x1, baum);
    k0[i] = x1.head(n0);
    k1[i] = d.a;
    kw[i] = d.Bu.dot(x1);
    kd[i] = damping_power(m, x0, x1);
  };
  auto event = [&](double tt, const VectorXd& x0, const VectorXd& x1) {
    return o.stop_when ? o.stop_when(tt, x0, x1) : 1.0;
  };
  const double tol_pos = 1e-13 * m.scale, tol_vel = 1e-13 * m.scale;
  rec.record(t, q0, q1, W, D);
  double g_prev = event(t, q0, q1);
  for (int k = 1; k < o.samples; ++k) {
    const double t_out = o.t0 + (o.t1 - o.t0) * k / (o.samples - 1);
    const int nsteps = std::max(1, static_cast<int>(std::ceil((t_out - t) / o.step - 1e-9)));
    const double h = (t_out - t) / nsteps;
    for (int s = 0; s < nsteps; ++s) {
      auto step = [&](double hh, VectorXd& x0, VectorXd& x1, double& w, double& dd, double tt) {
        deriv(0, tt, x0, x1);
        y0 = x0 + 0.5 * hh * k0[0];
        y1 = x1 + 0.5 * hh * k1[0];
        deriv(1, tt + 0.5 * hh, y0, y1);
        y0 = x0 + 0.5 * hh * k0[1];
        y1 = x1 + 0.5 * hh * k1[1];
        deriv(2, tt + 0.5 * hh, y0, y1);
        y0 = x0 + hh * k0[2];
        y1 = x1 + hh * k1[2];
        deriv(3, tt + hh, y0, y1);
        x0 += (hh / 6) * (k0[0] + 2 * k0[1] + 2 * k0[2] + k0[3]);
        x1 += (hh / 6) * (k1[0] + 2 * k1[1] + 2 * k1[2] + k1[3]);
        w += (hh / 6) * (kw[0] + 2 * kw[1] + 2 * kw[2] + kw[3]);
        dd += (hh / 6) * (kd[0] + 2 * kd[1] + 2 * kd[2] + kd[3]);
        if (!baum) d.project(tt + hh, x0, x1, tol_pos, tol_vel);
        ++d.stats.steps;
      };
      const VectorXd q0s = q0, q1s = q1;
      const double Ws = W, Ds = D, ts = t;
      step(h, q0, q1, W, D, t);
      t = ts + h;
      if (o.stop_when) {
        const double g = event(t, q0, q1);
        if ((g_prev < 0) != (g < 0) && g_prev != 0) {
          // locate the crossing by the secant on the step, then redo the step up to it
          double lo = 0, hi = h, glo = g_prev, ghi = g;
          for (int it = 0; it < 40; ++it) {
            const double mid = lo + (hi - lo) * glo / (glo - ghi);
            VectorXd a0 = q0s, a1 = q1s;
            double w = Ws, dd = Ds;
            step(mid, a0, a1, w, dd, ts);
            const double gm = event(ts + mid, a0, a1);
            if ((gm < 0) == (glo < 0))
              lo = mid, glo = gm;
            else
              hi = mid, ghi = gm;
            if (std::abs(hi - lo) < 1e-13 * std::max(1.0, std::abs(ts)) || gm == 0) {
              q0 = a0, q1 = a1, W = w, D = dd, t = ts + mid;
              break;
            }
          }
          d.stats.stopped_by_event = true;
          d.stats.t_end = t;
          rec.record(t, q0, q1, W, D);
          return;
        }
        g_prev = g;
      }
    }
    t = t_out;
    rec.record(t, q0, q1, W, D);
  }
  d.stats.t_end = t;
}

}  // namespace mo2d::detail
