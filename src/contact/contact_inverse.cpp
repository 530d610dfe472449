// Inverse dynamics with contacts (mo2d/contact_inverse.hpp): the contacts closed at the start held
// as position constraints psi = -g(q) = 0, and the report of their normal forces.
//
// The constraint is a user position constraint of the System (constraints/user.hpp), its
// arguments the coordinates of the nodes its points are made of: a body point is linear in its
// two nodes (Example 2.6 (b); dynamics/points.hpp, combine_point), so psi(x) is the gap of
// point_line.hpp / circle_circle.hpp / profile.hpp evaluated on Jets, and the constraint stage
// takes its Jacobian A = -J, its rate and its J' q1 from those Jets exactly. With M a1 = f + B u -
// A^T lambda, the contact's generalized force is lambda J^T: its multiplier is the normal force N,
// > 0 pushing the bodies apart.
#include "mo2d/contact_inverse.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <utility>

#include "contact/circle_circle.hpp"
#include "contact/contact_run.hpp"
#include "contact/contact_set.hpp"
#include "contact/point_line.hpp"
#include "contact/profile.hpp"
#include "mo2d/error.hpp"
#include "run/format.hpp"

namespace mo2d {

namespace {

using detail::fmt;

// times and the forces of the report to 10 digits
std::string fmt10(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

// A node as arguments of psi: x at args[arg], y at args[arg + 1]; arg -1: fixed at `fixed`.
struct ArgNode {
  int arg = -1;
  Vec2 fixed{0, 0};
};
// A body point as arguments: node i alone, or (1 - gamma) i + gamma j + rho z x (j - i).
struct ArgPoint {
  ArgNode i, j;
  bool two = false;
  double gamma = 0, rho = 0;
};
using JetPoint = std::array<Jet, 2>;

ArgNode arg_node(const Model& m, const NodeRef& n, std::vector<std::string>& args) {
  if (n.var < 0) return {-1, n.fixed};
  const std::string& x = m.coordinate_labels[static_cast<size_t>(n.var)];
  for (size_t k = 0; k + 1 < args.size(); k += 2)
    if (args[k] == x) return {static_cast<int>(k), {0, 0}};
  args.push_back(x);
  args.push_back(m.coordinate_labels[static_cast<size_t>(n.var) + 1]);
  return {static_cast<int>(args.size()) - 2, {0, 0}};
}

ArgPoint arg_point(const Model& m, const BodyPoint& p, std::vector<std::string>& args) {
  ArgPoint out;
  if (p.body < 0) {
    out.i.fixed = p.fixed;
    return out;
  }
  const Body& b = m.bodies[static_cast<size_t>(p.body)];
  out.i = arg_node(m, b.nodes[static_cast<size_t>(p.ci)], args);
  if (p.cj >= 0) {
    out.two = true;
    out.j = arg_node(m, b.nodes[static_cast<size_t>(p.cj)], args);
    out.gamma = p.gamma;
    out.rho = p.rho;
  }
  return out;
}

JetPoint at(const ArgNode& n, std::span<const Jet> x) {
  if (n.arg < 0) return {Jet(n.fixed.x()), Jet(n.fixed.y())};
  return {x[static_cast<size_t>(n.arg)], x[static_cast<size_t>(n.arg) + 1]};
}

JetPoint at(const ArgPoint& p, std::span<const Jet> x) {
  const JetPoint a = at(p.i, x);
  if (!p.two) return a;
  const JetPoint b = at(p.j, x);
  const double g = p.gamma, r = p.rho;  // combine_point of dynamics/points.hpp
  return {(1 - g) * a[0] + r * a[1] + g * b[0] - r * b[1],
          -r * a[0] + (1 - g) * a[1] + r * b[0] + g * b[1]};
}

// The position constraint -g(q) = 0 of contact c (compiled against m), named like it.
PositionConstraintDef gap_constraint(const Model& m, const detail::CompiledContact& c) {
  PositionConstraintDef def;
  def.name = c.def.name;
  const ArgPoint P = arg_point(m, c.p, def.args), A = arg_point(m, c.a, def.args);
  const bool two =
      c.def.target == ContactDef::Target::line || c.def.target == ContactDef::Target::profile;
  const ArgPoint B = two ? arg_point(m, c.b, def.args) : A;
  const ContactDef d = c.def;
  def.psi = [P, A, B, d, phi = c.phi](std::span<const Jet> x, Jet) mutable {
    const JetPoint p = at(P, x), a = at(A, x);
    if (d.target == ContactDef::Target::profile) {
      const JetPoint b = at(B, x);
      return -detail::profile_gap(*d.profile, p[0], p[1], a[0], a[1], b[0], b[1], d.radius, phi,
                                  d.name);
    }
    if (d.target == ContactDef::Target::line) {
      const JetPoint b = at(B, x);
      return -detail::point_line_gap(p[0], p[1], a[0], a[1], b[0], b[1], d.radius);
    }
    const double sign = d.target == ContactDef::Target::circle ? 1.0 : -1.0;
    return -detail::circle_circle_gap(p[0], p[1], a[0], a[1], d.target_radius, d.radius, sign);
  };
  return def;
}

// One more inverse sample of the run's model at any t, continued from a sample of the run (its
// positions, rates and accelerations predict the next positions, as between the run's samples).
class SampleAt {
 public:
  SampleAt(const Model& m, std::span<const Prescribed> motion, const InverseOptions& o)
      : m_(m), d_(m, motion, o) {}
  void continue_from(const Trajectory& r, int k) {
    d_.q0 = d_.q0_prev = r.q0.row(k).transpose();
    d_.q1_prev = r.q1.row(k).transpose();
    d_.a1_prev = r.a1.row(k).transpose();
    d_.t_prev = r.time[k];
    d_.has_previous = true;
    d_.det_sign_prev = 0;  // (no singular-passage warning: d_'s warnings are not reported)
  }
  const InverseData& at(double t) {
    inverse_dynamics_sample(m_, d_, t);
    return d_;
  }

 private:
  const Model& m_;
  InverseData d_;
};

// The first root of f on [a, b], f(a) >= 0 > f(b): bisection and secant (Illinois) until the
// bracket is a few ulps wide; returns its negative end.
template <class F>
double first_negative(F&& f, double a, double b, double fa, double fb) {
  int side = 0;
  for (int it = 0; it < 200 && b - a > 4e-16 * std::max(std::abs(a), std::abs(b)); ++it) {
    double t = (a * fb - b * fa) / (fb - fa);
    if (!(t > a && t < b)) t = 0.5 * (a + b);
    const double ft = f(t);
    if (ft < 0) {
      b = t, fb = ft;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {
      a = t, fa = ft;
      if (side == 1) fb *= 0.5;
      side = 1;
    }
  }
  return b;
}

// The least value of f on [a, c] by golden sections (f smooth with one minimum there).
template <class F>
std::pair<double, double> least(F&& f, double a, double c) {
  const double r = 0.5 * (std::sqrt(5.0) - 1);
  double x1 = c - r * (c - a), x2 = a + r * (c - a);
  double f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 100 && c - a > 1e-13 * std::max(std::abs(a), std::abs(c)); ++it) {
    if (f1 <= f2) {
      c = x2, x2 = x1, f2 = f1;
      x1 = c - r * (c - a), f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + r * (c - a), f2 = f(x2);
    }
  }
  return f1 <= f2 ? std::pair{x1, f1} : std::pair{x2, f2};
}

double contact_tolerance(const Model& m) {
  return detail::kContactGapTolerance * m.scale;
}

// A contact left out: its gap at every sample; where the motion closes it, an Error at the
// located time.
void check_left_out(const Model& m, const ContactDef& def, InverseContact& c, SampleAt& sample,
                    const Trajectory& r) {
  const detail::CompiledContact cc = detail::compile_contact(m, def);
  const Eigen::Index n = r.time.size();
  Eigen::VectorXd q;
  double prev = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    q = r.q0.row(k).transpose();
    const double g = detail::gap_only(m, cc, q);
    if (k == 0 || g < c.min_gap) c.min_gap = g, c.t_min_gap = r.time[k];
    if (g >= -contact_tolerance(m)) {
      prev = g;
      continue;
    }
    double t = r.time[k];
    if (k > 0 && prev >= 0) {  // where it closes: g = 0
      sample.continue_from(r, static_cast<int>(k - 1));
      t = first_negative([&](double s) { return detail::gap_only(m, cc, sample.at(s).q0); },
                         r.time[k - 1], r.time[k], prev, g);
    } else if (k > 0) {
      t = r.time[k - 1];
    }
    const bool rigid = def.law.kind == ContactLaw::Kind::rigid;
    throw Error("contact '" + def.name + "': the prescribed motion closes it at t = " + fmt10(t) +
                    " s (gap " + fmt(g) + " m at the sample t = " + fmt(r.time[k]) + " s): " +
                    (rigid ? "inverse dynamics holds closed only the contacts closed at the start"
                           : "a compliant contact's force as a load of inverse dynamics is not "
                             "supported yet"),
                def.name, t);
  }
}

// A held contact: its force's least value and first negative time, located between samples.
void report_held(const Model& m, InverseContact& c, SampleAt& sample, const Trajectory& r) {
  const std::vector<std::string> labels = m.reaction_labels();
  int col = -1;
  for (size_t k = 0; k < labels.size(); ++k)
    if (labels[k] == c.column) col = static_cast<int>(k);
  if (col < 0) throw Error("contact '" + c.name + "': no column '" + c.column + "'", c.name);
  const auto N = r.reactions.col(col);
  const Eigen::Index n = N.size();
  if (n == 0) return;
  auto force = [&](double t) { return sample.at(t).reactions[col]; };
  Eigen::Index kmin = 0;
  c.min_force = N.minCoeff(&kmin);
  c.t_min = r.time[kmin];
  if (n > 1) {  // the least between the samples around the least sample
    const Eigen::Index lo = std::max<Eigen::Index>(kmin - 1, 0), hi = std::min(kmin + 1, n - 1);
    sample.continue_from(r, static_cast<int>(lo));
    const auto [t, v] = least(force, r.time[lo], r.time[hi]);
    if (v < c.min_force) c.min_force = v, c.t_min = t;
  }
  if (!(c.min_force < 0)) return;
  c.pulls = true;
  c.preload = -c.min_force;
  Eigen::Index k = 0;
  while (k < n && !(N[k] < 0)) ++k;
  if (k == 0) {
    c.t_negative = r.time[0];
  } else if (k < n) {
    sample.continue_from(r, static_cast<int>(k - 1));
    c.t_negative = first_negative(force, r.time[k - 1], r.time[k], N[k - 1], N[k]);
  } else {  // every sample >= 0, a dip between them: from the sample before the least
    Eigen::Index j = 0;
    while (j + 1 < n && r.time[j + 1] < c.t_min) ++j;
    sample.continue_from(r, static_cast<int>(j));
    c.t_negative = first_negative(force, r.time[j], c.t_min, N[j], c.min_force);
  }
}

}  // namespace

ContactInverseModel hold_closed_contacts(const System& system, const BuildOptions& options,
                                         const Model& m, const std::vector<ContactDef>& contacts) {
  ContactInverseModel out;
  System s = system;
  const double tol = contact_tolerance(m);
  for (const ContactDef& def : contacts) {
    const detail::CompiledContact cc = detail::compile_contact(m, def);
    InverseContact c;
    c.name = def.name;
    c.gap = detail::gap_only(m, cc, m.q0);
    if (!(c.gap >= -tol))
      throw Error("contact '" + def.name + "': it starts penetrated (gap " + fmt(c.gap) +
                      " m at the initial configuration; tolerance " + fmt(tol) + " m)",
                  def.name);
    c.held = def.law.kind == ContactLaw::Kind::rigid && c.gap <= tol;
    if (c.held) {
      c.column = def.name + ".normal_force";
      s.add_constraint(gap_constraint(m, cc));
    }
    out.contacts.push_back(std::move(c));
  }
  out.model = build_model(s, options);
  for (const InverseContact& c : out.contacts)
    if (c.held)
      for (Reaction& r : out.model.reactions)
        if (r.label == c.name + ".lambda") r.label = c.column;  // psi = -g: lambda is N
  return out;
}

void report_contact_forces(const Model& m, std::span<const ContactDef> contacts,
                           std::vector<InverseContact>& report, std::span<const Prescribed> motion,
                           const InverseOptions& options, Trajectory& r) {
  if (report.empty()) return;
  if (report.size() != contacts.size())
    throw Error("report_contact_forces: " + std::to_string(contacts.size()) + " contacts and " +
                std::to_string(report.size()) + " reports");
  SampleAt sample(m, motion, options);
  for (size_t k = 0; k < report.size(); ++k) {
    InverseContact& c = report[k];
    if (!c.held) {
      check_left_out(m, contacts[k], c, sample, r);
      continue;
    }
    report_held(m, c, sample, r);
    if (c.pulls)
      r.stats.warnings.push_back("contact '" + c.name +
                                 "': the prescribed motion needs a negative (pulling) contact "
                                 "force from t = " +
                                 fmt10(c.t_negative) +
                                 " s: the contact would open there (a follower "
                                 "lifts off); the least force is " +
                                 fmt10(c.min_force) + " N at t = " + fmt10(c.t_min) +
                                 " s: an extra force of " + fmt10(c.preload) +
                                 " N pressing the contact closed (a "
                                 "spring's preload) prevents it");
  }
}

}  // namespace mo2d
