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
#include "mo2d/sketched_body.hpp"
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
NodeList to_nodes(const std::string& body, const py::object& nodes,
                  const std::string& field = "nodes") {
  const std::string what = "add_body('" + body + "'): " + field + ": ";
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

std::vector<NodeDef> to_node_defs(const NodeList& list) {
  std::vector<NodeDef> out;
  for (const auto& [n, p] : list) out.push_back({n, v2(p)});
  return out;
}

// The geometry of add_body, as scene files give it (mo2d/sketched_body.hpp): exact nodes; a
// shape (one point per node) with nodes as its sketch; a bar's length with its two nodes as the
// sketch; or a shape {name: (x, y)} placed approximately by at=((x, y), angle).
BodyDef body_geometry(const std::string& name, const py::object& nodes, const py::object& shape,
                      const std::optional<double>& length, const py::object& at) {
  const std::string what = "add_body('" + name + "'): ";
  if (!at.is_none()) {
    if (!nodes.is_none() || shape.is_none() || length)
      throw py::type_error(what +
                           "at= places a shape={name: (x, y)} given without nodes= or "
                           "length= (the sketch is the placement)");
    std::pair<P2, double> placement;
    try {
      placement = at.cast<std::pair<P2, double>>();
    } catch (const py::cast_error&) {
      throw py::type_error(what + "at: ((x, y), angle), not " + py::repr(at).cast<std::string>());
    }
    return placed_body(name, to_node_defs(to_nodes(name, shape, "shape")),
                       {v2(placement.first), placement.second});
  }
  if (nodes.is_none()) throw py::type_error(what + "nodes= missing (or shape= with at=)");
  std::vector<NodeDef> sketch = to_node_defs(to_nodes(name, nodes));
  if (length) {
    if (!shape.is_none()) throw py::type_error(what + "give either shape= or length=, not both");
    if (sketch.size() != 2)
      throw py::type_error(what +
                           "a bar given by its length has exactly two nodes (the first at "
                           "(0, 0), the second at (length, 0) in its frame)");
    return bar_body(name, *length, std::move(sketch[0]), std::move(sketch[1]));
  }
  BodyDef b{.name = name, .nodes = std::move(sketch)};
  if (!shape.is_none())
    for (const auto& p : shape.cast<std::vector<P2>>()) b.shape.push_back(v2(p));
  return b;
}

void add_body(System& s, const std::string& name, const py::object& nodes, double mass,
              double inertia, const py::object& com, const std::optional<P2>& com_point,
              const py::object& shape, const std::optional<double>& length, const py::object& at) {
  BodyDef b = body_geometry(name, nodes, shape, length, at);
  b.mass = mass;
  b.inertia = inertia;
  b.com = to_com(com, com_point);
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
       py::arg("fy") = py::none(), py::arg("params") = Params{},
       "Add a force applied at a point fixed in a body.\n\n"
       "name: unique in the System; body: the body it acts on; point: (x, y) (m) in the "
       "System's frame at the initial configuration (the body frame for a body given by its "
       "shape); fx, fy: the components (N) in the System's frame, each a law (a number, an "
       "expression string of t and state labels, a callable of t, or a mo2d.Law; None: 0); "
       "params: {name: value} constants of the expressions.\n\n"
       "Example::\n\n"
       "    s.add_force('drag', 'link', (0.5, 0), fx='-2 * link.P.vx')")
      .def(
          "add_torque",
          [](System& s, const std::string& name, const std::string& body, const py::object& torque,
             const Params& params) {
            s.add_torque({name, body, to_law(torque, params)});
          },
          py::arg("name"), py::arg("body"), py::arg("torque"), py::arg("params") = Params{},
          "Add a pure torque (N m, counter-clockwise) on a body; torque: a law (number, "
          "expression string, callable of t or mo2d.Law); params: constants of the "
          "expression.\n\n"
          "Example::\n\n"
          "    s.add_torque('motor', 'crank', '0.5 * sin(t)')")
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
          py::arg("params") = Params{},
          "Add a spring-damper between two points fixed in bodies ('ground' allowed).\n\n"
          "point_a, point_b: (x, y) (m) in the System's frame at the initial configuration. "
          "Linear: tension T = stiffness (l - rest_length) + damping dl/dt, with rest_length "
          "(m, >= 0), stiffness (N/m), damping (N s/m); or tension= a law (N) that may read "
          "'length', 'extension' and 'rate' of this spring (stiffness and damping then 0). A "
          "positive tension pulls the points together. acts: 'both', 'tension_only' (a cable: "
          "slack when it would push) or 'compression_only' (a bump stop).\n\n"
          "Example::\n\n"
          "    s.add_spring('k', 'ground', (0, 1), 'link', (0.5, 0), rest_length=0.8, "
          "stiffness=200)")
      .def(
          "add_torsional_spring",
          [](System& s, const std::string& name, const std::string& joint, double stiffness,
             double damping, std::optional<double> rest, const py::object& torque,
             const Params& params) {
            s.add_torsional_spring({name, joint, stiffness, damping, rest, to_law(torque, params)});
          },
          py::arg("name"), py::arg("joint"), py::arg("stiffness") = 0.0, py::arg("damping") = 0.0,
          py::arg("rest") = py::none(), py::arg("torque") = py::none(),
          py::arg("params") = Params{},
          "Add a torsional spring-damper at a revolute joint: torque -stiffness (theta - rest) "
          "- damping (w2 - w1) on body 2 and the opposite on body 1, theta the bodies' relative "
          "angle. stiffness (N m/rad), damping (N m s/rad), rest (rad; None: the relative "
          "angle at the initial configuration); or torque= a law (N m) that may read 'angle' "
          "(theta - rest) and 'rate' (w2 - w1).\n\n"
          "Example::\n\n"
          "    s.add_torsional_spring('damper', 'pivot', torque=mo2d.Law(['rate'], "
          "lambda x, t: -0.3 * x[0]))")
      .def(
          "add_friction",
          [](System& s, const std::string& name, const std::string& joint, double viscous,
             double mu, double radius, double regularization) {
            s.add_friction({name, joint, viscous, mu, radius, regularization});
          },
          py::arg("name"), py::arg("joint"), py::arg("viscous") = 0.0, py::arg("mu") = 0.0,
          py::arg("radius") = 0.0, py::arg("regularization") = 1e-3,
          "Add friction in a revolute, prismatic or pin-in-slot joint: F = -viscous v - mu N "
          "sgn(v), opposing the joint's relative rate v.\n\n"
          "viscous: N s/m (slide) or N m s/rad (revolute); mu: the Coulomb coefficient (>= 0), "
          "N the normal force from the joint's reaction (a revolute: radius * |reaction|, "
          "radius in m); regularization: v_s (m/s or rad/s) of sgn(v) = tanh(v / v_s) in "
          "forward dynamics (inverse dynamics uses sign(v)).")
      .def(
          "set_gravity", [](System& s, const P2& g) { s.set_gravity(v2(g)); }, py::arg("g"),
          "Set the gravity vector g = (gx, gy) (m/s^2); default (0, 0): none. Example: "
          "s.set_gravity((0, -9.81)).");
}

void bind_system_class(py::module_& m) {
  py::class_<System, std::shared_ptr<System>> c(
      m, "System",
      "A mechanism as written: ground nodes, bodies, joints, coordinates, loads "
      "(mo2d/system.hpp), SI units, angles counter-clockwise.\n\n"
      "Names are local to a System; labels name its parts: 'body.node.x', 'joint.torque', "
      "'instance.body.node'. mo2d.build_model(system) makes the Model the runs take.\n\n"
      "Example::\n\n"
      "    s = mo2d.System('pendulum')\n"
      "    s.add_ground_node('O', (0, 0))\n"
      "    s.add_body('link', nodes={'O': (0, 0), 'P': (0.5, 0)}, mass=2.0, com='P')\n"
      "    s.add_revolute('pivot', 'ground.O', 'link.O', actuated=True)\n"
      "    s.add_coordinate('link.angle', rate=[('link.w', 1.0)])\n"
      "    s.set_gravity((0, -9.81))\n"
      "    model = mo2d.build_model(s)");
  c.def(py::init<std::string>(), py::arg("name") = "root",
        "An empty System named `name` (the prefix of nothing: labels are local to it).")
      .def_property_readonly("name", &System::name, "The System's name (str).")
      .def(
          "add_ground_node",
          [](System& s, const std::string& name, const P2& p) { s.add_ground_node(name, v2(p)); },
          py::arg("name"), py::arg("position"),
          "Add a node of the ground (fixed) at position (x, y) (m); joints name it "
          "'ground.<name>'.")
      .def("add_body", &add_body, py::arg("name"), py::arg("nodes") = py::none(),
           py::arg("mass") = 0.0, py::arg("inertia") = 0.0, py::arg("com") = py::none(),
           py::arg("com_point") = py::none(), py::arg("shape") = py::none(),
           py::arg("length") = py::none(), py::arg("at") = py::none(),
           "Add a rigid body.\n\n"
           "name: unique in the System; nodes: {name: (x, y)} (m, in the System's frame; or a "
           "list of (name, (x, y))), its points that joints and loads refer to as "
           "'body.node'; mass (kg, >= 0); inertia (kg m^2) about the centre of mass; com: the "
           "centre of mass, a node name, or (node_i, node_j, gamma[, rho]) (the fraction gamma "
           "along node_i -> node_j, rho across), default the first node; com_point: (x, y) "
           "(m) instead.\n\n"
           "Lengths and a sketch instead of exact positions, as scene files write them "
           "(mo2d/sketched_body.hpp): shape= the node coordinates in the body's own frame (one "
           "per node, exact) turns `nodes` into a sketch; length=L (m) is a bar, its first node "
           "at (0, 0) and its second at (L, 0) in its frame, `nodes` its two sketched "
           "positions; shape={name: (x, y)} with at=((x, y), angle) (m, rad) places the shape "
           "approximately, without nodes. build_model places such a body rigidly where the "
           "joints close, nearest to the sketch (which picks the branch); points given on it "
           "(com_point, a force's point) are in its frame. Raises TypeError for malformed or "
           "conflicting arguments, mo2d.Error for a length that is not > 0.\n\n"
           "Example::\n\n"
           "    s.add_body('crank', nodes={'A': (0, 0), 'B': (0.1, 0)}, mass=0.5, "
           "inertia=1e-3, com=('A', 'B', 0.5))\n"
           "    s.add_body('coupler', length=0.35, nodes={'A': (0, 0.1), 'B': (0.3, 0.3)}, "
           "mass=0.5)")
      .def(
          "add_revolute",
          [](System& s, const std::string& name, const std::string& a, const std::string& b,
             bool actuated) {
            s.add_revolute({name, a, b, actuated});
          },
          py::arg("name"), py::arg("node_a"), py::arg("node_b"), py::arg("actuated") = false,
          "Add a revolute joint: node_a of body 1 and node_b of body 2 coincide ('body.node' "
          "or 'ground.node'). actuated=True adds the input '<name>.torque' (N m, on body 2, "
          "the opposite on body 1); the reactions '<name>.Fx', '<name>.Fy' (N) are the force "
          "of body 1 on body 2.")
      .def(
          "add_prismatic",
          [](System& s, const std::string& name, const std::string& from, const std::string& to,
             const std::string& slider, bool actuated) {
            s.add_prismatic({name, from, to, slider, actuated});
          },
          py::arg("name"), py::arg("axis_from"), py::arg("axis_to"), py::arg("slider"),
          py::arg("actuated") = false,
          "Add a prismatic joint: the slider node of body 2 slides on the axis axis_from -> "
          "axis_to (two nodes of body 1, 'ground.node' allowed), the relative rotation locked. "
          "Adds the coordinate '<name>.q' (m, the slider's signed distance from axis_from); "
          "actuated=True adds the input '<name>.force' (N, along +axis on body 2).")
      .def(
          "add_pin_in_slot",
          [](System& s, const std::string& name, const std::string& from, const std::string& to,
             const std::string& pin, bool slide, bool rotation) {
            s.add_pin_in_slot({name, from, to, pin, slide, rotation});
          },
          py::arg("name"), py::arg("axis_from"), py::arg("axis_to"), py::arg("pin"),
          py::arg("actuated_slide") = false, py::arg("actuated_rotation") = false,
          "Add a pin-in-slot joint: the pin node of body 2 slides on the axis axis_from -> "
          "axis_to of body 1 and turns freely. Adds the coordinate '<name>.q' (m); "
          "actuated_slide adds the input '<name>.force' (N), actuated_rotation the input "
          "'<name>.torque' (N m, between the two bodies).")
      .def(
          "add_coordinate",
          [](System& s, const std::string& name,
             const std::vector<std::pair<std::string, double>>& rate,
             std::optional<double> initial) {
            s.add_coordinate({name, rate, initial});
          },
          py::arg("name"), py::arg("rate"), py::arg("initial") = py::none(),
          "Add an extra coordinate defined by its rate: d/dt name = sum of weight * "
          "quasi-velocity over rate=[(rate label, weight)], e.g. rate=[('crank.w', 1.0)] for "
          "the crank's angle (rad). initial: its value at the initial configuration (None: "
          "the value the configuration implies). Coordinates are what inverse dynamics "
          "prescribes and forward dynamics starts from.\n\n"
          "Example::\n\n"
          "    s.add_coordinate('link.angle', rate=[('link.w', 1.0)])")
      .def(
          "add_point",
          [](System& s, const std::string& name, const std::string& body, const P2& p) {
            s.add_point({name, body, v2(p)});
          },
          py::arg("name"), py::arg("body"), py::arg("point"),
          "Add a named point fixed in a body ('ground' allowed), at (x, y) (m) in the System's "
          "frame at the initial configuration: laws may read its '<name>.x', '<name>.vy', ... "
          "and every run outputs them.")
      .def(
          "add_instance",
          [](System& s, const std::string& name, const System& sub, const P2& offset,
             double angle) {
            s.add_instance(name, sub, {v2(offset), angle});
          },
          py::arg("name"), py::arg("system"), py::arg("offset") = P2{0, 0}, py::arg("angle") = 0.0,
          "Add an instance of another System as a subsystem named `name`, rotated by angle "
          "(rad) then shifted by offset (x, y) (m); its parts are then '<name>.body.node', "
          "'<name>.joint', ... (the System is copied: later changes to it are not seen).")
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
  py::class_<Law>(
      m, "Law",
      "A load law, a value of time and of the state: a force component (N), a torque (N m), a "
      "spring's tension, an effort.\n\n"
      "Law(labels, f): f(x, t) -> float, x the tuple of the values of the state labels "
      "('crank.angle', 'link.w', a spring's 'rate', ...); its derivatives are central "
      "differences (docs/python.md). Law(expression, params): an expression string of the "
      "scene language, derived exactly.\n\n"
      "Example::\n\n"
      "    damper = mo2d.Law(['rate'], lambda x, t: -0.3 * x[0])\n"
      "    damper([2.0], 0.0)    # -0.6")
      .def(py::init([](std::vector<std::string> labels, py::object f) {
             return callable_law(std::move(labels), std::move(f));
           }),
           py::arg("labels"), py::arg("f"),
           "A law f(x, t) of the values x of `labels` (a list of state labels) and the time t "
           "(s); f returns a float. Raises mo2d.Error if f is not callable.")
      .def(py::init([](const std::string& text, const Params& params) {
             return expression_law(text, params);
           }),
           py::arg("expression"), py::arg("params") = Params{},
           "A law from an expression string (docs/scene-format.md) of t, state labels and the "
           "constants params={name: value}. Raises mo2d.Error for a syntax error (with its "
           "column).")
      .def_readonly("labels", &Law::args,
                    "The state labels the law reads (list of str), in the order of x.")
      .def_property_readonly(
          "depends_on_state", &Law::depends_on_state,
          "True when the law reads the state (labels given), False for a function of t "
          "only.")
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
          py::arg("x"), py::arg("t"),
          "The law's value at the values x of its labels and the time t (s), a float (for "
          "tests and plots). Raises mo2d.Error when len(x) differs from len(labels).");
  bind_system_class(m);
  bind_runs(m);
}

}  // namespace mo2d::py_bind
