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
      "y(x) at points, a cubic spline (not-a-knot) or a polyline (mo2d/table.hpp); "
      "table(x) for floats or NumPy arrays, table.derivatives(x) -> (S, S', S'')")
      .def(py::init([](std::string name, std::vector<double> x, std::vector<double> y,
                       const std::string& interpolation, const std::string& extrapolation) {
             return std::make_shared<LookupTable>(std::move(name), std::move(x), std::move(y),
                                                  table_options(interpolation, extrapolation));
           }),
           py::arg("name"), py::arg("x"), py::arg("y"), py::arg("interpolation") = "cubic",
           py::arg("extrapolation") = "error")
      .def_property_readonly("name", &LookupTable::name)
      .def_property_readonly(
          "x", [](const LookupTable& t) { return std::vector<double>(t.x().begin(), t.x().end()); })
      .def_property_readonly(
          "y", [](const LookupTable& t) { return std::vector<double>(t.y().begin(), t.y().end()); })
      .def(
          "__call__", [](const LookupTable& t, double x) { return t(x); }, py::arg("x"))
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
          py::arg("x"), "(S(x), S'(x), S''(x)) of the interpolant");
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
      "a Table from a CSV file (header of column names; x, y: the columns, default the first two)");
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
      "the effort law u = u_ff(t) + kp (r - x) + kd (r' - x') (a mo2d.Law for efforts=); "
      "reference: an expression of t or a callable returning (r, r', r'')");
  m.def("rate_label", &rate_label, py::arg("coordinate"),
        "the quasi-velocity label of a coordinate label ('crank.A.x' -> 'crank.A.vx')");
  m.def(
      "efforts_from_inverse",
      [](const Model& model, const Motions& motion, const Params& params) {
        std::vector<Law> out;
        for (auto& f : efforts_from_inverse(model, to_motions(motion, params))) out.emplace_back(f);
        return out;
      },
      py::arg("model"), py::arg("motion"), py::arg("params") = Params{},
      "one mo2d.Law of t per input: the inverse-dynamics effort of the motion, solved at each t");
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
      "the lumped equivalent (Gamba 2009) of a gear train: shafts=[{mass, inertia, axis, ratio}]");
}

// Runs of a second formulation and replayed results: inverse_dynamics_lagrange, efforts from a
// sampled run (cubic Hermite), and the units of a result's columns.
void bind_run_extras(py::module_& m) {
  m.def(
      "inverse_dynamics_lagrange",
      [](const std::shared_ptr<Model>& model, const Motions& motion, double t0, double t1,
         const py::object& samples, const Params& params) {
        InverseOptions o;
        o.t0 = t0;
        o.t1 = t1;
        o.samples = to_count(samples, "samples");
        return make_result(model, inverse_dynamics_lagrange(*model, to_motions(motion, params), o));
      },
      py::arg("model"), py::arg("motion"), py::arg("t0") = 0.0, py::arg("t1") = 1.0,
      py::arg("samples") = py::int_(501), py::arg("params") = Params{},
      "inverse dynamics by Lagrange multipliers on a model built with reduction='none'");
  m.def(
      "efforts_from_samples",
      [](const Result& r) {
        std::vector<Law> out;
        for (auto& f : efforts_from_samples(r.trajectory)) out.emplace_back(f);
        return out;
      },
      py::arg("result"), "one mo2d.Law of t per input: the run's efforts, cubic Hermite in t");
  const py::object result = m.attr("Result");  // bound by bind_results
  py::class_<Result> c(result);
  c.def_property_readonly(
      "units", [](const Result& r) { return trajectory_csv_units(*r.model, r.trajectory); },
      "the SI unit of every column of r.columns ('' where the model cannot say)");
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
       "gear pair: omega_body - omega_carrier = ratio (omega_driver - omega_carrier)")
      .def(
          "add_rack",
          [](System& s, const std::string& name, const std::string& slide,
             const std::string& pinion, double radius) {
            s.add_rack({name, slide, pinion, radius});
          },
          py::arg("name"), py::arg("slide"), py::arg("pinion"), py::arg("radius"),
          "rack and pinion: q' = radius (omega_pinion - omega_carrier)")
      .def(
          "add_constraint",
          [](System& s, const std::string& name, const std::string& psi, const Params& params) {
            Law law = expression_law(psi, params);
            s.add_constraint(PositionConstraintDef{name, law.args, law.f});
          },
          py::arg("name"), py::arg("psi"), py::arg("params") = Params{},
          "position constraint psi(x, t) = 0, an expression of coordinate labels and t")
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
          "velocity constraint g = 0, an expression linear in quasi-velocity labels");
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
