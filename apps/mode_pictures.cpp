// Mode pictures (mode_pictures.hpp): three configurations rendered with one view, then blended.
#include "mode_pictures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "mo2d/error.hpp"
#include "mo2d/render.hpp"

namespace mo2d::cli {

namespace {

// The configurations q0(z* + s_k dz) as the samples of a Motion (times `time`). Where the
// constraints leave no configuration that far along the mode (a crank's tip cannot go beyond its
// circle), the amplitude is halved (up to 6 times) and the picture says so on stdout.
Motion along_mode_once(const Model& m, const StateSpace& ss, const Eigen::VectorXd& dz,
                       const std::vector<double>& s, const std::vector<double>& time);

Motion along_mode(const Model& m, const StateSpace& ss, const Eigen::VectorXd& dz,
                  const std::vector<double>& s, const std::vector<double>& time) {
  for (int halvings = 0;; ++halvings) {
    try {
      const Motion mo = along_mode_once(m, ss, std::ldexp(1.0, -halvings) * dz, s, time);
      if (halvings > 0)
        std::printf("  note: mode drawn at 1/%d of the amplitude asked (no configuration beyond)\n",
                    1 << halvings);
      return mo;
    } catch (const Error& e) {
      if (halvings == 6)
        throw Error(std::string("mode picture: no configuration along the mode even at 1/64 of the "
                                "amplitude asked: use a smaller --amplitude (the largest node "
                                "displacement, a fraction of the size; default 0.1); at 1/64: ") +
                        e.what(),
                    "--amplitude");
    }
  }
}

Motion along_mode_once(const Model& m, const StateSpace& ss, const Eigen::VectorXd& dz,
                       const std::vector<double>& s, const std::vector<double>& time) {
  Motion mo;
  mo.time.resize(static_cast<Eigen::Index>(s.size()));
  mo.q0.resize(static_cast<Eigen::Index>(s.size()), m.n0);
  for (size_t k = 0; k < s.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    mo.time[i] = time[k];
    mo.q0.row(i) = chart_positions(m, ss, s[k] * dz).transpose();
  }
  return mo;
}

// channel-wise: fade a toward white by `keep` (1: unchanged)
std::uint32_t faded(std::uint32_t px, double keep) {
  std::uint32_t out = 0xFF000000u;
  for (int sh = 0; sh <= 16; sh += 8) {
    const double c = (px >> sh) & 0xFFu;
    out |= static_cast<std::uint32_t>(std::lround(255 - (255 - c) * keep)) << sh;
  }
  return out;
}

std::uint32_t darker(std::uint32_t a, std::uint32_t b) {
  std::uint32_t out = 0xFF000000u;
  for (int sh = 0; sh <= 16; sh += 8) out |= std::min((a >> sh) & 0xFFu, (b >> sh) & 0xFFu) << sh;
  return out;
}

}  // namespace

std::string mode_title(const Mode& mode, int number) {
  char buf[160];
  if (mode.oscillatory)
    std::snprintf(buf, sizeof buf, "mode %d: %.4g Hz, damping ratio %.3g", number, mode.hz,
                  mode.damping_ratio);
  else
    std::snprintf(buf, sizeof buf, "mode %d: not oscillatory, \u03BB = %.4g 1/s", number,
                  mode.eigenvalue.real());
  return buf;
}

std::string write_mode_picture(const Model& m, const StateSpace& ss, const Mode& mode, int number,
                               double amplitude, const std::string& path) {
  const Eigen::VectorXd dz = mode_step(m, mode, amplitude);
  const Motion mo = along_mode(m, ss, dz, {0.0, 1.0, -1.0}, {ss.t, ss.t, ss.t});
  FrameOptions f;
  f.show_time = false;
  f.show_efforts = false;
  f.title = mode_title(mode, number);
  const Image eq = render_frame(m, mo, 0, f);
  const Image plus = render_frame(m, mo, 1, f);
  const Image minus = render_frame(m, mo, 2, f);
  Image out = plus;
  for (size_t i = 0; i < out.argb.size(); ++i)
    out.argb[i] = darker(darker(plus.argb[i], minus.argb[i]), faded(eq.argb[i], 0.3));
  write_png(out, path);
  return path;
}

std::string write_mode_filmstrip(const Model& m, const StateSpace& ss, const Mode& mode, int number,
                                 double amplitude, const std::string& path) {
  const Eigen::VectorXd dz = mode_step(m, mode, amplitude);
  const double period = mode.oscillatory ? 2 * std::numbers::pi / mode.omega_d : 1.0;
  std::vector<double> s, time;
  for (int k = 0; k < 8; ++k) {
    s.push_back(std::sin(2 * std::numbers::pi * k / 8));
    time.push_back(period * k / 8);
  }
  const Motion mo = along_mode(m, ss, dz, s, time);
  FilmstripOptions fo;
  fo.frames = 8;
  fo.columns = 4;
  fo.tile.show_efforts = false;
  fo.tile.title = mode_title(mode, number);
  write_filmstrip(m, mo, fo, path);
  return path;
}

}  // namespace mo2d::cli
