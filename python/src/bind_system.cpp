// System in Python: the definition structs of mo2d/system.hpp as keyword arguments, laws from
// numbers, expressions or callables (laws.hpp), then build_model.
#include <pybind11/stl.h>

#include <array>
#include <memory>
#include <optional>
#include <utility>

#include "bindings.hpp"
#include "laws.hpp"
#include "mo2d/error.hpp"
#include "mo2d/system.hpp"

namespace mo2d::py_bind {

namespace {

using P2 = std::array<double, 2>;
using NodeList = std::vector<std::pair<std::string, P2>>;

Vec2 v2(const P2& p) {
  return {p[0], p[1]};
}

std::string type_name(const py::handle& v) {
  return py::str(py::type::handle_of(v).attr("__name__")).cast<std::string>();
}

// nodes={"O": (0, 0), "A": (0, 0.1)} (insertion order kept) or [("O", (0, 0)), ...]; anything
// else is a TypeError naming the body and the node (not pybind11's "Unable to cast").
NodeList to_nodes(const std::string& body, const py::object& nodes) {
  const std::string what = "add_body('" + body + "'): nodes: ";
  const std::string form = "a dict {name: (x, y)} or a list [(name, (x, y)), ...]";
  if (py::isinstance<py::str>(nodes) || py::isinstance<py::bytes>(nodes) ||
      !(py::isinstance<py::dict>(nodes) || py::isinstance<py::sequence>(nodes)))
    throw py::type_error(what + form + ", not " + type_name(nodes));
  py::list items;
  if (py::isinstance<py::dict>(nodes))
    for (const auto& [k, v] : nodes.cast<py::dict>()) items.append(py::make_tuple(k, v));
  else
    items = py::list(nodes);
  NodeList out;
  for (const auto& item : items) {
    const std::string at = what + "item " + std::to_string(out.size()) + ": ";
    if (!py::isinstance<py::sequence>(item) || py::isinstance<py::str>(item) || py::len(item) != 2)
      throw py::type_error(at + "(name, (x, y)), not " + py::repr(item).cast<std::string>());
    const py::sequence pair = item.cast<py::sequence>();
    if (!py::isinstance<py::str>(pair[0]))
      throw py::type_error(at + "the name is a str, not " + type_name(pair[0]));
    const std::string name = pair[0].cast<std::string>();
    try {
      out.emplace_back(name, pair[1].cast<P2>());
    } catch (const py::cast_error&) {
      throw py::type_error(what + "node '" + name + "': a position (x, y) of two numbers, not " +
                           py::repr(pair[1]).cast<std::string>());
    }
  }
  return out;
}

// com=None (first node), "O" (a node), ("O", "A", gamma[, rho]); com_point=(x, y)
std::optional<CenterOfMass> to_com(const py::object& com, const std::optional<P2>& point) {
  if (point) return CenterOfMass::at_point(v2(*point));
  if (com.is_none()) return std::nullopt;
  if (py::isinstance<py::str>(com)) return CenterOfMass::at_node(com.cast<std::string>());
  const auto t = com.cast<py::tuple>();
  if (t.size() != 3 && t.size() != 4)
    throw Error("com: a node name, or (node_i, node_j, gamma[, rho])");
  return CenterOfMass::between(t[0].cast<std::string>(), t[1].cast<std::string>(),
                               t[2].cast<double>(), t.size() == 4 ? t[3].cast<double>() : 0.0);
}

SpringActs to_acts(const std::string& s) {
  if (s == "both") return SpringActs::both;
  if (s == "tension_only") return SpringActs::tension_only;
  if (s == "compression_only") return SpringActs::compression_only;
  throw Error("spring acts: 'both', 'tension_only' or 'compression_only', not '" + s + "'", s);
}

void add_body(System& s, const std::string& name, const py::object& nodes, double mass,
              double inertia, const py::object& com, const std::optional<P2>& com_point,
              const std::vector<P2>& shape) {
  BodyDef b{.name = name, .mass = mass, .inertia = inertia, .com = to_com(com, com_point)};
  for (const auto& [n, p] : to_nodes(name, nodes)) b.nodes.push_back({n, v2(p)});
  for (const auto& p : shape) b.shape.push_back(v2(p));
  s.add_body(std::move(b));
}

void bind_system_loads(py::class_<System, std::shared_ptr<System>>& c) {
  c.def(
       "add_force",
       [](System& s, const std::string& name, const std::string& body, const P2& point,
          const py::object& fx, const py::object& fy, const Params& params) {
         s.add_force({name, body, v2(point), to_law(fx, params), to_law(fy, params)});
       },
       py::arg("name"), py::arg("body"), py::arg("point"), py::arg("fx") = py::none(),
       py::arg("fy") = py::none(), py::arg("params") = Params{})
      .def(
          "add_torque",
          [](System& s, const std::string& name, const std::string& body, const py::object& torque,
             const Params& params) {
            s.add_torque({name, body, to_law(torque, params)});
          },
          py::arg("name"), py::arg("body"), py::arg("torque"), py::arg("params") = Params{})
      .def(
          "add_spring",
          [](System& s, const std::string& name, const std::string& body_a, const P2& point_a,
             const std::string& body_b, const P2& point_b, double rest_length, double stiffness,
             double damping, const py::object& tension, const std::string& acts,
             const Params& params) {
            s.add_spring({name, body_a, v2(point_a), body_b, v2(point_b), rest_length, stiffness,
                          damping, to_law(tension, params), to_acts(acts)});
          },
          py::arg("name"), py::arg("body_a"), py::arg("point_a"), py::arg("body_b"),
          py::arg("point_b"), py::arg("rest_length") = 0.0, py::arg("stiffness") = 0.0,
          py::arg("damping") = 0.0, py::arg("tension") = py::none(), py::arg("acts") = "both",
          py::arg("params") = Params{})
      .def(
          "add_torsional_spring",
          [](System& s, const std::string& name, const std::string& joint, double stiffness,
             double damping, std::optional<double> rest, const py::object& torque,
             const Params& params) {
            s.add_torsional_spring({name, joint, stiffness, damping, rest, to_law(torque, params)});
          },
          py::arg("name"), py::arg("joint"), py::arg("stiffness") = 0.0, py::arg("damping") = 0.0,
          py::arg("rest") = py::none(), py::arg("torque") = py::none(),
          py::arg("params") = Params{})
      .def(
          "add_friction",
          [](System& s, const std::string& name, const std::string& joint, double viscous,
             double mu, double radius, double regularization) {
            s.add_friction({name, joint, viscous, mu, radius, regularization});
          },
          py::arg("name"), py::arg("joint"), py::arg("viscous") = 0.0, py::arg("mu") = 0.0,
          py::arg("radius") = 0.0, py::arg("regularization") = 1e-3)
      .def(
          "set_gravity", [](System& s, const P2& g) { s.set_gravity(v2(g)); }, py::arg("g"));
}

void bind_system_class(py::module_& m) {
  py::class_<System, std::shared_ptr<System>> c(
      m, "System", "A mechanism as written: bodies, joints, loads (mo2d/system.hpp)");
  c.def(py::init<std::string>(), py::arg("name") = "root")
      .def_property_readonly("name", &System::name)
      .def(
          "add_ground_node",
          [](System& s, const std::string& name, const P2& p) { s.add_ground_node(name, v2(p)); },
          py::arg("name"), py::arg("position"))
      .def("add_body", &add_body, py::arg("name"), py::arg("nodes"), py::arg("mass") = 0.0,
           py::arg("inertia") = 0.0, py::arg("com") = py::none(), py::arg("com_point") = py::none(),
           py::arg("shape") = std::vector<P2>{})
      .def(
          "add_revolute",
          [](System& s, const std::string& name, const std::string& a, const std::string& b,
             bool actuated) {
            s.add_revolute({name, a, b, actuated});
          },
          py::arg("name"), py::arg("node_a"), py::arg("node_b"), py::arg("actuated") = false)
      .def(
          "add_prismatic",
          [](System& s, const std::string& name, const std::string& from, const std::string& to,
             const std::string& slider, bool actuated) {
            s.add_prismatic({name, from, to, slider, actuated});
          },
          py::arg("name"), py::arg("axis_from"), py::arg("axis_to"), py::arg("slider"),
          py::arg("actuated") = false)
      .def(
          "add_pin_in_slot",
          [](System& s, const std::string& name, const std::string& from, const std::string& to,
             const std::string& pin, bool slide, bool rotation) {
            s.add_pin_in_slot({name, from, to, pin, slide, rotation});
          },
          py::arg("name"), py::arg("axis_from"), py::arg("axis_to"), py::arg("pin"),
          py::arg("actuated_slide") = false, py::arg("actuated_rotation") = false)
      .def(
          "add_coordinate",
          [](System& s, const std::string& name,
             const std::vector<std::pair<std::string, double>>& rate,
             std::optional<double> initial) {
            s.add_coordinate({name, rate, initial});
          },
          py::arg("name"), py::arg("rate"), py::arg("initial") = py::none(),
          "extra coordinate d/dt name = sum w * rate_label, rate=[('crank.w', 1.0)]")
      .def(
          "add_point",
          [](System& s, const std::string& name, const std::string& body, const P2& p) {
            s.add_point({name, body, v2(p)});
          },
          py::arg("name"), py::arg("body"), py::arg("point"))
      .def(
          "add_instance",
          [](System& s, const std::string& name, const System& sub, const P2& offset,
             double angle) {
            s.add_instance(name, sub, {v2(offset), angle});
          },
          py::arg("name"), py::arg("system"), py::arg("offset") = P2{0, 0}, py::arg("angle") = 0.0)
      .def("__repr__", [](const System& s) {
        return "<mo2d.System '" + s.name() + "': " + std::to_string(s.bodies().size()) +
               " bodies, " +
               std::to_string(s.revolutes().size() + s.prismatics().size() + s.slots().size()) +
               " joints>";
      });
  bind_system_loads(c);
}

}  // namespace

void bind_runs(py::module_& m);  // bind_runs.cpp

void bind_system(py::module_& m) {
  py::class_<Law>(m, "Law",
                  "A load law: Law(labels, f) with f(x, t) -> float, x the tuple of the labels' "
                  "values (no derivatives: see docs/python.md); Law(expression, params)")
      .def(py::init([](std::vector<std::string> labels, py::object f) {
             return callable_law(std::move(labels), std::move(f));
           }),
           py::arg("labels"), py::arg("f"))
      .def(py::init([](const std::string& text, const Params& params) {
             return expression_law(text, params);
           }),
           py::arg("expression"), py::arg("params") = Params{})
      .def_readonly("labels", &Law::args)
      .def_property_readonly("depends_on_state", &Law::depends_on_state)
      .def(
          "__call__",
          [](const Law& law, const std::vector<double>& x, double t) {
            if (!law) return 0.0;
            if (x.size() != law.args.size())
              throw Error("law: " + std::to_string(law.args.size()) + " values expected, got " +
                          std::to_string(x.size()));
            std::vector<Jet> j(x.begin(), x.end());
            return law.f(j, Jet(t)).v;
          },
          py::arg("x"), py::arg("t"), "the law's value (for tests and plots)");
  bind_system_class(m);
  bind_runs(m);
}

}  // namespace mo2d::py_bind
