// Laws and motions from Python values (laws.hpp).
#include "laws.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "mo2d/error.hpp"
#include "mo2d/expression.hpp"

namespace mo2d::py_bind {

namespace py = pybind11;

namespace {

// The Python callable of a law, released with the GIL held (the interpreter may be finishing).
struct Callable {
  std::shared_ptr<py::object> f;
  explicit Callable(py::object fn)
      : f(new py::object(std::move(fn)), [](py::object* p) {
          py::gil_scoped_acquire gil;
          delete p;
        }) {}
};

// Value of a Python call as a double; anything else is an Error naming the law's labels.
double to_double(const py::object& v, const char* what) {
  try {
    return v.cast<double>();
  } catch (const py::cast_error&) {
    throw Error(std::string(what) + ": a Python law returned " +
                py::str(py::type::of(v)).cast<std::string>() + ", not a number");
  }
}

// int, float, NumPy scalars
bool is_number(const py::object& v) {
  return py::hasattr(v, "__float__");
}

// f at the point s of the curve x(s) = x.v + s x.d + s^2/2 x.dd (and t likewise) that the Jets
// describe.
double call_at(const Callable& c, std::span<const Jet> x, Jet t, double s) {
  py::tuple values(x.size());
  for (std::size_t k = 0; k < x.size(); ++k)
    values[k] = py::float_(x[k].v + s * (x[k].d + 0.5 * s * x[k].dd));
  return to_double((*c.f)(values, t.v + s * (t.d + 0.5 * s * t.dd)), "law");
}

// The Jet of a Python law f(x, t): a callable sees floats, so where a caller asks for derivatives
// (the exact Jacobian of CVODE BDF, linearization: mo2d/jacobian.hpp) they are central differences
// of f along the curve, the step h such that no argument moves by more than 6e-6 of max(1, |x|)
// (near cbrt(eps): truncation and rounding balanced, about 1e-10 relative in f' and 1e-5 in f'').
// Without a direction, one call.
Jet along_curve(const Callable& c, std::span<const Jet> x, Jet t) {
  double rate = 0;  // largest |dx_k/ds| / max(1, |x_k|)
  auto track = [&rate](Jet a) {
    rate =
        std::max(rate, (std::abs(a.d) + std::sqrt(std::abs(a.dd))) / std::max(1.0, std::abs(a.v)));
  };
  for (const Jet& a : x) track(a);
  track(t);
  const double f0 = call_at(c, x, t, 0);
  if (rate == 0) return Jet(f0);
  const double h = 6e-6 / rate;
  const double fp = call_at(c, x, t, h), fm = call_at(c, x, t, -h);
  return {f0, (fp - fm) / (2 * h), (fp - 2 * f0 + fm) / (h * h)};
}

}  // namespace

Law expression_law(const std::string& text, const Params& params) {
  auto e = std::make_shared<Expression>(Expression::parse(text));
  std::vector<std::string> labels;
  e->bind([&](const std::string& name) {
    if (name == "t") return Binding{Binding::Kind::time, 0, -1};
    if (auto it = params.find(name); it != params.end())
      return Binding{Binding::Kind::constant, it->second, -1};
    auto at = std::find(labels.begin(), labels.end(), name);
    if (at == labels.end()) at = labels.insert(labels.end(), name);
    return Binding{Binding::Kind::variable, 0, static_cast<int>(at - labels.begin())};
  });
  return Law(std::move(labels), [e](std::span<const Jet> x, Jet t) { return e->evaluate(x, t); });
}

Law callable_law(std::vector<std::string> labels, py::object f) {
  if (!PyCallable_Check(f.ptr())) throw Error("mo2d.Law: the function is not callable");
  Callable c(std::move(f));
  if (labels.empty())
    return Law([c](double t) {
      py::gil_scoped_acquire gil;
      return to_double((*c.f)(t), "law of t");
    });
  return Law(std::move(labels), [c](std::span<const Jet> x, Jet t) {
    py::gil_scoped_acquire gil;
    return along_curve(c, x, t);
  });
}

Law to_law(const py::object& value, const Params& params) {
  if (value.is_none()) return Law{};
  if (py::isinstance<Law>(value)) return value.cast<Law>();
  if (py::isinstance<py::str>(value)) return expression_law(value.cast<std::string>(), params);
  if (PyCallable_Check(value.ptr())) return callable_law({}, value);
  if (is_number(value)) return Law::constant(value.cast<double>());
  throw Error("a law is a number, an expression string, a callable of t or a mo2d.Law, not " +
              py::str(py::type::of(value)).cast<std::string>());
}

Prescribed to_motion(const std::string& coordinate, const py::object& value, const Params& params) {
  if (py::isinstance<py::str>(value)) {
    auto e = std::make_shared<Expression>(Expression::parse(value.cast<std::string>()));
    e->bind([&](const std::string& name) {
      if (name == "t") return Binding{Binding::Kind::time, 0, -1};
      if (auto it = params.find(name); it != params.end())
        return Binding{Binding::Kind::constant, it->second, -1};
      return Binding{};
    });
    return {coordinate, [e](Jet t) { return e->evaluate({}, t); }};
  }
  if (!PyCallable_Check(value.ptr()) && is_number(value)) {
    const double s = value.cast<double>();
    return {coordinate, [s](Jet) { return Jet(s); }};
  }
  if (!PyCallable_Check(value.ptr()))
    throw Error("motion of '" + coordinate +
                    "': an expression of t or a callable returning (s, s_dot, s_ddot)",
                coordinate);
  Callable c(value);
  return {coordinate, [c, coordinate](Jet t) {
            py::gil_scoped_acquire gil;
            const py::object v = (*c.f)(t.v);
            py::tuple s;
            try {
              s = v.cast<py::tuple>();
            } catch (const py::cast_error&) {
            }
            if (s.size() != 3)
              throw Error(
                  "motion of '" + coordinate + "': the callable must return (s, s_dot, s_ddot)",
                  coordinate, t.v);
            // chain rule along t's own direction (t.d = 1, t.dd = 0 when called with t itself)
            const double s0 = to_double(s[0], "motion"), s1 = to_double(s[1], "motion"),
                         s2 = to_double(s[2], "motion");
            return chain(t, s0, s1, s2);
          }};
}

}  // namespace mo2d::py_bind
