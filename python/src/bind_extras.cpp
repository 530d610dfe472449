// The rest of the public API in Python: lookup tables (mo2d/table.hpp), PD controllers
// (mo2d/control.hpp), efforts replayed from inverse dynamics or from a run (mo2d/forward.hpp),
// inverse dynamics by Lagrange multipliers, the units of a result's columns, the lumped
// transmission (mo2d/transmission.hpp), and the System's gears, racks and user constraints
// (mo2d/system.hpp). Constraints are expressions only: their Jacobian needs exact derivatives,
// which an expression gives and a Python callable does not.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <array>
#include <memory>
#include <utility>

#include "bindings.hpp"
#include "mo2d/control.hpp"
#include "mo2d/csv.hpp"
#include "mo2d/error.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/system.hpp"
#include "mo2d/table.hpp"
#include "mo2d/transmission.hpp"
#include "run_args.hpp"

namespace mo2d::py_bind {

namespace {

using P2 = std::array<double, 2>;

TableOptions table_options(const std::string& interpolation, const std::string& extrapolation) {
  TableOptions o;
  if (interpolation == "linear")
    o.interpolation = Interpolation::linear;
  else if (interpolation != "cubic")
    throw Error("table interpolation: 'cubic' or 'linear', not '" + interpolation + "'");
  if (extrapolation == "clamp")
    o.extrapolation = Extrapolation::clamp;
  else if (extrapolation == "periodic")
    o.extrapolation = Extrapolation::periodic;
  else if (extrapolation != "error")
    throw Error("table extrapolation: 'error', 'clamp' or 'periodic', not '" + extrapolation + "'");
  return o;
}

using Table = std::shared_ptr<const LookupTable>;

void bind_table(py::module_& m) {
  py::class_<LookupTable, std::shared_ptr<LookupTable>>(
      m, "Table",
      "A lookup table y(x) interpolated between its points: a cubic spline (not-a-knot) or a "
      "polyline (mo2d/table.hpp).\n\n"
      "table(x) evaluates it at a float or a NumPy array, table.derivatives(x) gives (S, S', "
      "S''). Use it in a Python law or motion (expression strings cannot call it).\n\n"
      "Example::\n\n"
      "    cam = mo2d.Table('cam', [0, 1, 2, 3], [0, 0.2, 0.1, 0], extrapolation='clamp')\n"
      "    cam(0.5), cam.derivatives(0.5)")
      .def(py::init([](std::string name, std::vector<double> x, std::vector<double> y,
                       const std::string& interpolation, const std::string& extrapolation) {
             return std::make_shared<LookupTable>(std::move(name), std::move(x), std::move(y),
                                                  table_options(interpolation, extrapolation));
           }),
           py::arg("name"), py::arg("x"), py::arg("y"), py::arg("interpolation") = "cubic",
           py::arg("extrapolation") = "error",
           "A table named `name` (its errors name it) through the points (x[k], y[k]), x "
           "strictly increasing; interpolation: 'cubic' or 'linear'; extrapolation beyond the "
           "ends: 'error' (a mo2d.Error naming x and the range), 'clamp' (the end value) or "
           "'periodic' (period x[-1] - x[0]). Raises mo2d.Error for x not increasing, too few "
           "points or non-finite values.")
      .def_property_readonly("name", &LookupTable::name, "The table's name (str).")
      .def_property_readonly(
          "x", [](const LookupTable& t) { return std::vector<double>(t.x().begin(), t.x().end()); },
          "The abscissas of the points (list of float), increasing.")
      .def_property_readonly(
          "y", [](const LookupTable& t) { return std::vector<double>(t.y().begin(), t.y().end()); },
          "The ordinates of the points (list of float).")
      .def(
          "__call__", [](const LookupTable& t, double x) { return t(x); }, py::arg("x"),
          "The interpolated value S(x), a float (or a NumPy array for an array x).")
      .def(
          "__call__",
          [](const LookupTable& t, const py::array_t<double>& x) {
            return py::vectorize([&t](double v) { return t(v); })(x);
          },
          py::arg("x"))
      .def(
          "derivatives",
          [](const LookupTable& t, double x) {
            const Jet s = t(Jet(x, 1, 0));
            return std::array<double, 3>{s.v, s.d, s.dd};
          },
          py::arg("x"),
          "(S(x), S'(x), S''(x)): the interpolant and its first two derivatives at x, e.g. a "
          "prescribed motion lambda t: tuple(table.derivatives(t)).");
  m.def(
      "read_table_csv",
      [](const py::object& path, std::string name, std::string x, std::string y, double scale_x,
         double scale_y, const std::string& interpolation, const std::string& extrapolation) {
        const CsvColumns columns{std::move(x), std::move(y), scale_x, scale_y};
        return std::make_shared<LookupTable>(
            read_table_csv(py::str(path).cast<std::string>(), std::move(name), columns,
                           table_options(interpolation, extrapolation)));
      },
      py::arg("path"), py::arg("name"), py::arg("x") = "", py::arg("y") = "",
      py::arg("scale_x") = 1.0, py::arg("scale_y") = 1.0, py::arg("interpolation") = "cubic",
      py::arg("extrapolation") = "error",
      "A mo2d.Table read from a CSV file with a header of column names.\n\n"
      "x, y: the header names of the columns (default: the first two); scale_x, scale_y: "
      "factors applied to the values read (e.g. math.pi / 180 for degrees); interpolation, "
      "extrapolation: as in mo2d.Table. Raises mo2d.Error naming the file and the line "
      "(an unknown column with the closest name, a cell that is not a number, x not "
      "increasing).\n\n"
      "Example::\n\n"
      "    cam = mo2d.read_table_csv('cam.csv', 'cam', x='angle', y='lift',\n"
      "                              scale_x=math.pi / 180)");
}

// A law of time only as a time function (a feed-forward); a law that reads the state is refused.
std::function<double(double)> time_function(const py::object& value, const Params& params,
                                            const std::string& what) {
  Law law = to_law(value, params);
  if (!law) return {};
  if (law.depends_on_state()) throw Error(what + ": a function of t only, not of the state");
  return [law](double t) { return law.f({}, Jet(t)).v; };
}

void bind_control(py::module_& m) {
  m.def(
      "pd_control",
      [](const std::string& coordinate, double kp, double kd, const py::object& reference,
         const std::string& rate, const py::object& feed_forward, const Params& params) {
        PdControl c{coordinate, rate, {}, kp, kd, {}};
        if (!reference.is_none()) c.reference = to_motion(coordinate, reference, params).motion;
        c.feed_forward = time_function(feed_forward, params, "pd_control feed_forward");
        return pd_control(std::move(c));
      },
      py::arg("coordinate"), py::arg("kp"), py::arg("kd"), py::arg("reference") = py::none(),
      py::arg("rate") = "", py::arg("feed_forward") = py::none(), py::arg("params") = Params{},
      "A PD controller as an effort law: u = u_ff(t) + kp (r - x) + kd (r' - x').\n\n"
      "coordinate: the controlled coordinate label x ('bar.angle', 'slide.q'); kp (N m/rad or "
      "N/m), kd (N m s/rad or N s/m): the gains (>= 0); reference: r(t), an expression of t or "
      "a callable returning (r, r', r'') (None: 0); rate: the quasi-velocity label of x "
      "(default rate_label(coordinate)); feed_forward: a law of t only (None: 0); params: "
      "constants of the expressions. Returns a mo2d.Law for forward_dynamics(efforts=...).\n\n"
      "Example::\n\n"
      "    law = mo2d.pd_control('bar.angle', kp=5.0, kd=1.0, reference='0.4 * sin(2 * t)')\n"
      "    r = mo2d.forward_dynamics(model, x0, duration=2.0, efforts=[('pivot.torque', law)])");
  m.def("rate_label", &rate_label, py::arg("coordinate"),
        "The quasi-velocity label of a coordinate label, as build_model names them: "
        "'crank.A.x' -> 'crank.A.vx', 'rail.q' -> 'rail.v', an extra coordinate 'crank.angle' "
        "-> 'crank.angle.rate'.");
  m.def(
      "efforts_from_inverse",
      [](const Model& model, const Motions& motion, const Params& params) {
        std::vector<Law> out;
        for (auto& f : efforts_from_inverse(model, to_motions(motion, params))) out.emplace_back(f);
        return out;
      },
      py::arg("model"), py::arg("motion"), py::arg("params") = Params{},
      "The feed-forward efforts of a motion: one mo2d.Law of t per input (in the order of "
      "model.input_labels), each solving inverse dynamics of `motion` ([(coordinate label, "
      "s(t))], as in inverse_dynamics) at the t it is called with.\n\n"
      "Example::\n\n"
      "    ff, = mo2d.efforts_from_inverse(model, [('bar.angle', '0.4 * sin(2 * t)')])");
}

TransmissionShaft to_shaft(const py::dict& d) {
  TransmissionShaft s;
  for (const auto& [k, v] : d) {
    const auto key = k.cast<std::string>();
    if (key == "mass")
      s.mass = v.cast<double>();
    else if (key == "inertia")
      s.inertia = v.cast<double>();
    else if (key == "axis")
      s.axis = Vec2(v.cast<P2>()[0], v.cast<P2>()[1]);
    else if (key == "ratio")
      s.ratio = v.cast<double>();
    else
      throw Error("transmission shaft: unknown key '" + key + "' (mass, inertia, axis, ratio)");
  }
  return s;
}

py::dict lumped_dict(const LumpedTransmission& l) {
  py::dict d;
  d["housing_mass"] = l.housing.mass;
  d["housing_com"] = P2{l.housing.com.x(), l.housing.com.y()};
  d["housing_inertia"] = l.housing.inertia;
  d["axis"] = P2{l.axis.x(), l.axis.y()};
  d["shaft_mass"] = l.shaft_mass;
  d["inertia_a"] = l.inertia_a;
  d["inertia_b"] = l.inertia_b;
  d["ratio"] = l.ratio;
  d["sigma"] = l.sigma;
  d["s"] = l.s;
  d["p"] = l.p;
  return d;
}

void bind_transmission(py::module_& m) {
  m.def(
      "lump_transmission",
      [](double mass, const P2& com, double inertia, const std::vector<py::dict>& shafts,
         const std::string& name) {
        std::vector<TransmissionShaft> s;
        s.reserve(shafts.size());
        for (const auto& d : shafts) s.push_back(to_shaft(d));
        return lumped_dict(lump_transmission({mass, Vec2(com[0], com[1]), inertia}, s, name));
      },
      py::arg("housing_mass"), py::arg("housing_com"), py::arg("housing_inertia"),
      py::arg("shafts"), py::arg("name") = "transmission",
      "The lumped equivalent (Gamba 2009) of a gear train in a housing: two shafts A and B "
      "and the housing that carry the same inertia.\n\n"
      "housing_mass (kg), housing_com (x, y) (m, housing frame), housing_inertia (kg m^2): the "
      "housing's own mass data; shafts: [dict(mass (kg), inertia (kg m^2 about its axis), "
      "axis (x, y) (m), ratio (its rate relative to the reference shaft's, both relative to "
      "the housing))]. Returns a dict: ratio, inertia_a, inertia_b, shaft_mass, axis, "
      "housing_mass, housing_com, housing_inertia and the invariants sigma, s, p. Raises "
      "mo2d.Error (element `name`) for negative masses, no shafts or no rotational inertia.");
}

// Runs of a second formulation and replayed results: inverse_dynamics_lagrange, efforts from a
// sampled run (cubic Hermite), and the units of a result's columns.
void bind_run_extras(py::module_& m) {
  m.def(
      "inverse_dynamics_lagrange",
      [](const std::shared_ptr<Model>& model, const Motions& motion, double t0,
         const py::object& duration, const py::object& samples, const Params& params,
         const py::object& t1) {
        InverseOptions o;
        o.t0 = t0;
        o.t1 = end_time("inverse_dynamics_lagrange", t0, duration, t1, 1.0);
        o.samples = to_count(samples, "samples");
        return make_result(model, inverse_dynamics_lagrange(*model, to_motions(motion, params), o));
      },
      py::arg("model"), py::arg("motion"), py::arg("t0") = 0.0, py::arg("duration") = py::none(),
      py::arg("samples") = py::int_(501), py::arg("params") = Params{}, py::kw_only(),
      py::arg("t1") = py::none(),
      "Inverse dynamics by Lagrange multipliers (a second formulation, to check "
      "inverse_dynamics against) on a model built with reduction='none'.\n\n"
      "motion, t0 (s), duration (s, default 1), samples, params: as in inverse_dynamics; t1: "
      "the end time, deprecated (use duration). Returns a mo2d.Result.");
  m.def(
      "efforts_from_samples",
      [](const Result& r) {
        std::vector<Law> out;
        for (auto& f : efforts_from_samples(r.trajectory)) out.emplace_back(f);
        return out;
      },
      py::arg("result"),
      "The efforts of a run replayed: one mo2d.Law of t per input (the order of "
      "result.effort_labels), cubic Hermite between the samples; e.g. the efforts of "
      "inverse dynamics fed to forward dynamics.");
  const py::object result = m.attr("Result");  // bound by bind_results
  py::class_<Result> c(result);
  c.def_property_readonly(
      "units", [](const Result& r) { return trajectory_csv_units(*r.model, r.trajectory); },
      "The SI unit of every column, a list parallel to r.columns ('s', 'm', 'rad', 'N', "
      "'N m', 'J', ...; '' where the model cannot say).");
}

void bind_system_extras(py::module_& m) {
  const py::object system = m.attr("System");  // bound by bind_system_class
  py::class_<System, std::shared_ptr<System>> c(system);
  c.def(
       "add_gear",
       [](System& s, const std::string& name, const std::string& body, const std::string& driver,
          const std::string& carrier, double ratio) {
         s.add_gear({name, body, driver, carrier, ratio});
       },
       py::arg("name"), py::arg("body"), py::arg("driver"), py::arg("carrier") = "ground",
       py::arg("ratio") = 1.0,
       "Add a gear pair: the driving body `driver` turns the driven body `body`, both carried "
       "by `carrier` ('ground' allowed): omega_body - omega_carrier = ratio (omega_driver - "
       "omega_carrier); ratio = -z_driver / z_body for external spur gears. Adds the "
       "coordinate '<name>.phi' and the reactions '<name>.torque' (N m, the mesh torque on "
       "body) and '<name>.carrier_torque'.")
      .def(
          "add_rack",
          [](System& s, const std::string& name, const std::string& slide,
             const std::string& pinion, double radius) {
            s.add_rack({name, slide, pinion, radius});
          },
          py::arg("name"), py::arg("slide"), py::arg("pinion"), py::arg("radius"),
          "Add a rack and pinion: the slide coordinate q of the prismatic or pin-in-slot "
          "joint `slide` follows the pinion's rotation relative to the slide's axis body: q' = "
          "radius (omega_pinion - omega_carrier), radius (m) signed and non-zero. Adds the "
          "coordinate '<name>.phi' and the reaction '<name>.force' (N, on the rack along the "
          "axis).")
      .def(
          "add_constraint",
          [](System& s, const std::string& name, const std::string& psi, const Params& params) {
            Law law = expression_law(psi, params);
            s.add_constraint(PositionConstraintDef{name, law.args, law.f});
          },
          py::arg("name"), py::arg("psi"), py::arg("params") = Params{},
          "Add a position constraint psi(x, t) = 0: psi an expression string of coordinate "
          "labels ('m.P.x', 'slide.q', ...) and t, with the constants params; derived exactly. "
          "Its multiplier is the reaction '<name>.lambda'.\n\n"
          "Example::\n\n"
          "    s.add_constraint('rod', 'm.P.x^2 + m.P.y^2 - L^2', params={'L': 0.7})")
      .def(
          "add_velocity_constraint",
          [](System& s, const std::string& name, const std::string& g, const Params& params) {
            Law law = expression_law(g, params);
            VelocityConstraintDef v;
            v.name = name;
            v.labels = law.args;
            v.g_labels = law.f;
            s.add_constraint(std::move(v));
          },
          py::arg("name"), py::arg("g"), py::arg("params") = Params{},
          "Add a velocity constraint g = 0 (non-holonomic, e.g. rolling without slipping): g "
          "an expression string linear in quasi-velocity labels ('m.P.vx', 'crank.w'), its "
          "coefficients functions of coordinate labels and t; build_model refuses a g that is "
          "not linear in the rates. Its multiplier is '<name>.lambda'.\n\n"
          "Example::\n\n"
          "    s.add_velocity_constraint('diagonal', 'm.P.vx - m.P.vy')");
}

}  // namespace

void bind_extras(py::module_& m) {
  bind_table(m);
  bind_control(m);
  bind_transmission(m);
  bind_run_extras(m);
  bind_system_extras(m);
}

}  // namespace mo2d::py_bind
