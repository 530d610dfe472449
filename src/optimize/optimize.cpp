// optimize_scene (mo2d/optimize.hpp): NLopt's BOBYQA (bounds only) or COBYLA (bounds and
// inequality constraints) over the varied parameters scaled to [0, 1], from several starts; the
// wall-time budget checked before every run and given to it; the best design over all starts.
#include "mo2d/optimize.hpp"

#include <nlopt.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <random>

#include "optimize/scene_evaluator.hpp"
#include "run/cpu_time.hpp"
#include "run/format.hpp"

namespace mo2d {

using optimize_detail::SceneEvaluator;

namespace {

double wall_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

const char* status_name(nlopt_result r) {
  switch (r) {
    case NLOPT_SUCCESS:
      return "converged";
    case NLOPT_XTOL_REACHED:
      return "xtol";
    case NLOPT_FTOL_REACHED:
      return "ftol";
    case NLOPT_MAXEVAL_REACHED:
      return "max_evals";
    case NLOPT_MAXTIME_REACHED:
      return "max_seconds";
    case NLOPT_ROUNDOFF_LIMITED:
      return "roundoff";
    case NLOPT_FORCED_STOP:
      return "stopped";
    default:
      return "failure";
  }
}

bool converged(const std::string& status) {
  return status == "converged" || status == "xtol" || status == "ftol";
}

// The state of an optimization shared by the NLopt callbacks.
struct Driver {
  const OptimizeOptions& o;
  SceneEvaluator& ev;
  OptimizeResult& res;
  double t_start = 0, budget = 0;
  nlopt_opt opt = nullptr;
  int start = 0;
  // the last design evaluated (COBYLA asks for the objective, then the constraints, at one x)
  std::vector<double> last_u{};
  SceneEvaluator::Values last{};
  bool have_last = false;
  bool out_of_time = false;
  std::exception_ptr error{};
  // the best design of this start and of all
  OptimizeStart* current = nullptr;
  bool have_best = false;
  SceneEvaluator::Values best{};

  std::vector<double> design(const double* u) const {
    std::vector<double> x(o.vary.size());
    for (std::size_t k = 0; k < x.size(); ++k) {
      const DesignVariable& v = o.vary[k];
      x[k] = std::clamp(v.lo + u[k] * (v.hi - v.lo), v.lo, v.hi);
    }
    return x;
  }
  // Whether a is better than b: feasible before infeasible, then lower objective (or violation).
  bool better(const SceneEvaluator::Values& a, const SceneEvaluator::Values& b) const {
    const bool fa = a.violation <= o.constraint_tol, fb = b.violation <= o.constraint_tol;
    if (fa != fb) return fa;
    return fa ? a.objective < b.objective : a.violation < b.violation;
  }

  // The values at scaled design u (from the cache when it is the last one); false when the
  // optimization must stop (out of time, or an error kept for optimize_scene to rethrow).
  bool evaluate(const double* u) {
    const std::size_t n = o.vary.size();
    if (have_last && std::equal(u, u + n, last_u.begin())) return true;
    const double left = budget - (wall_seconds() - t_start);
    if (left <= 0) {
      out_of_time = true;
      nlopt_force_stop(opt);
      return false;
    }
    const std::vector<double> x = design(u);
    try {
      last = ev.evaluate(x, left);
    } catch (...) {
      if (wall_seconds() - t_start >= budget)  // the run ran out of the optimization's time
        out_of_time = true;
      else
        error = std::current_exception();
      nlopt_force_stop(opt);
      return false;
    }
    last_u.assign(u, u + n);
    have_last = true;
    ++res.evaluations;
    ++current->evaluations;
    OptimizeProgress p;
    p.evaluation = res.evaluations;
    p.start = start;
    p.x = x;
    p.value = last.objective;
    p.violation = last.violation;
    p.feasible = last.violation <= o.constraint_tol;
    if (current->evaluations == 1 || better(last, start_best)) {
      start_best = last;
      current->x = x;
      current->value = last.objective;
      current->violation = last.violation;
    }
    if (!have_best || better(last, best)) {
      have_best = true;
      best = last;
      res.x = x;
      res.value = last.objective;
      res.constraints = last.constraints;
      p.improved = true;
    }
    p.best = best.objective;
    p.seconds = wall_seconds() - t_start;
    if (o.progress) o.progress(p);
    return true;
  }
  SceneEvaluator::Values start_best{};
};

double objective(unsigned /*n*/, const double* u, double* /*grad*/, void* data) {
  auto* d = static_cast<Driver*>(data);
  if (!d->evaluate(u)) return std::numeric_limits<double>::max();
  return d->last.objective;
}

void constraints(unsigned m, double* result, unsigned /*n*/, const double* u, double* /*grad*/,
                 void* data) {
  auto* d = static_cast<Driver*>(data);
  const bool ok = d->evaluate(u);
  for (unsigned k = 0; k < m; ++k)
    result[k] = ok ? d->last.scaled[k] : std::numeric_limits<double>::max();
}

// The starts in [0, 1]^n: the scene's values (clamped into the bounds), then seeded random points.
std::vector<std::vector<double>> start_points(const OptimizeOptions& o, const Scene& s) {
  std::vector<std::vector<double>> out;
  std::vector<double> u0;
  for (const DesignVariable& v : o.vary) {
    double x = v.lo;
    for (const auto& [name, value] : s.parameters)
      if (name == v.name) x = value;
    u0.push_back(std::clamp((x - v.lo) / (v.hi - v.lo), 0.0, 1.0));
  }
  out.push_back(u0);
  std::mt19937_64 gen(o.seed);  // its sequence is fixed by the standard
  for (int k = 1; k < o.starts; ++k) {
    std::vector<double> u;
    for (std::size_t j = 0; j < o.vary.size(); ++j)
      u.push_back(static_cast<double>(gen() >> 11) * 0x1.0p-53);
    out.push_back(u);
  }
  return out;
}

std::string number(double v) {
  return detail::fmt(v, 9);
}

void add_warnings(const OptimizeOptions& o, const SceneEvaluator& ev, OptimizeResult& res,
                  double budget, double violation) {
  if (res.stop == "max_seconds")
    res.warnings.push_back("the wall-time budget of " + number(budget) +
                           " s (--max-seconds) ran out after " + std::to_string(res.evaluations) +
                           " evaluations: the best design so far (" + ev.describe(res.x) +
                           ") is not converged");
  for (std::size_t k = 0; k < res.starts.size(); ++k)
    if (res.starts[k].status == "max_evals")
      res.warnings.push_back("start " + std::to_string(k + 1) + " used its " +
                             std::to_string(o.max_evals) +
                             " evaluations (--max-evals) before converging; its best: " +
                             ev.describe(res.starts[k].x));
  if (!res.feasible)
    res.warnings.push_back(
        "no design evaluated satisfies every constraint: the least infeasible one (" +
        ev.describe(res.x) + ", largest violation " + number(violation) + ") is returned");
  for (std::size_t k = 0; k < o.vary.size(); ++k) {
    const DesignVariable& v = o.vary[k];
    const double tol = 1e-9 * (v.hi - v.lo);
    if (res.x[k] <= v.lo + tol || res.x[k] >= v.hi - tol)
      res.warnings.push_back(v.name + " = " + number(res.x[k]) + " is at its " +
                             (res.x[k] <= v.lo + tol ? "lower" : "upper") +
                             " bound: the optimum may lie outside [" + number(v.lo) + ", " +
                             number(v.hi) + "]");
  }
}

}  // namespace

DesignVariable parse_design_variable(const std::string& text) {
  const auto eq = text.find('=');
  const auto colon = text.find(':', eq == std::string::npos ? 0 : eq);
  auto fail = [&](const std::string& why) -> DesignVariable {
    throw OptimizeInputError("--vary " + text + ": " + why);
  };
  if (eq == std::string::npos || eq == 0 || colon == std::string::npos)
    return fail("expected NAME=LO:HI");
  auto num = [&](const std::string& s) {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v))
      fail("'" + s + "' is not a finite number (expected NAME=LO:HI)");
    return v;
  };
  DesignVariable v{text.substr(0, eq), num(text.substr(eq + 1, colon - eq - 1)),
                   num(text.substr(colon + 1))};
  if (!(v.lo < v.hi)) fail("LO must be below HI");
  return v;
}

OptimizeResult optimize_scene(const OptimizeOptions& o) {
  const double t_start = wall_seconds(), cpu_start = detail::cpu_seconds();
  if (o.starts < 1) throw OptimizeInputError("optimize: --starts must be >= 1");
  if (o.max_evals < 1) throw OptimizeInputError("optimize: --max-evals must be >= 1");
  if (!(o.xtol > 0 && o.xtol < 1)) throw OptimizeInputError("optimize: --xtol must be in (0, 1)");
  SceneEvaluator ev(o);
  OptimizeResult res;
  for (const DesignVariable& v : o.vary) res.names.push_back(v.name);
  const double budget = o.max_seconds > 0 ? o.max_seconds : ev.scene().run.max_seconds;
  const auto n = static_cast<unsigned>(o.vary.size());
  const auto m = static_cast<unsigned>(o.subject_to.size());
  const nlopt_algorithm algorithm = m == 0 ? NLOPT_LN_BOBYQA : NLOPT_LN_COBYLA;
  res.method = m == 0 ? "BOBYQA" : "COBYLA";
  Driver d{o, ev, res, t_start, budget};
  const std::vector<double> lo(n, 0.0), hi(n, 1.0), tol(m, o.constraint_tol);
  for (const std::vector<double>& u0 : start_points(o, ev.scene())) {
    nlopt_opt opt = nlopt_create(algorithm, n);
    if (!opt) throw Error("optimize: NLopt cannot create its optimizer");
    nlopt_set_lower_bounds(opt, lo.data());
    nlopt_set_upper_bounds(opt, hi.data());
    nlopt_set_min_objective(opt, objective, &d);
    if (m > 0) nlopt_add_inequality_mconstraint(opt, m, constraints, &d, tol.data());
    nlopt_set_xtol_abs1(opt, o.xtol);
    nlopt_set_maxeval(opt, o.max_evals);
    nlopt_set_initial_step1(opt, 0.1);
    res.starts.push_back({});
    OptimizeStart& st = res.starts.back();
    st.x0 = d.design(u0.data());
    d.opt = opt;
    d.current = &st;
    d.have_last = false;
    std::vector<double> u = u0;
    double f = 0;
    const nlopt_result r = nlopt_optimize(opt, u.data(), &f);
    nlopt_destroy(opt);
    if (d.error) std::rethrow_exception(d.error);
    st.status = d.out_of_time ? "max_seconds" : status_name(r);
    if (r < 0 && !d.out_of_time && r != NLOPT_FORCED_STOP && r != NLOPT_ROUNDOFF_LIMITED)
      throw Error(std::string("optimize: NLopt's ") + res.method + " failed (code " +
                  std::to_string(static_cast<int>(r)) + ") in start " +
                  std::to_string(res.starts.size()));
    if (d.out_of_time) break;
    ++d.start;
  }
  if (!d.have_best)
    throw Error("optimize: the wall-time budget of " + number(budget) +
                " s (--max-seconds) ran out before the first run ended");
  res.feasible = d.best.violation <= o.constraint_tol;
  const OptimizeStart* found = nullptr;  // the start that found the best design
  for (const OptimizeStart& st : res.starts)
    if (!found && st.evaluations > 0 && st.x == res.x) found = &st;
  res.stop = d.out_of_time                        ? "max_seconds"
             : found && !converged(found->status) ? found->status
                                                  : "converged";
  if (res.stop == "roundoff") res.stop = "converged";
  add_warnings(o, ev, res, budget, d.best.violation);
  const Scene best = ev.scene_at(res.x);
  res.parameters = best.parameters;
  res.scene_text = ev.text_at(res.x);
  res.wall_seconds = wall_seconds() - t_start;
  res.cpu_seconds = detail::cpu_seconds() - cpu_start;
  return res;
}

}  // namespace mo2d
