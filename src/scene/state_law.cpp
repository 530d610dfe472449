// Laws of scene expressions (mo2d/law.hpp): an expression of t, the parameters and quantities of
// the state, whose names other than parameters and t become the law's arguments.
#include <algorithm>
#include <memory>

#include "load_system.hpp"

namespace mo2d::scene_detail {

Law state_law(const Reader& r, const YAML::Node& node, const std::string& what,
              const std::string& element, std::vector<std::pair<std::string, Location>>* uses) {
  if (!node.IsDefined()) return {};
  auto e = std::make_shared<Expression>(r.expression(node, what));
  // names: parameters, then t, then the quantities of the state it reads (its arguments, in
  // order of first use), which build_model resolves
  std::vector<std::string> args;
  try {
    e->bind([&](const std::string& n) {
      if (auto b = r.parameter_binding(n); b.kind != Binding::Kind::unbound) return b;
      if (n == "t") return Binding{Binding::Kind::time, 0, -1};
      auto it = std::find(args.begin(), args.end(), n);
      if (it == args.end()) it = args.insert(args.end(), n);
      return Binding{Binding::Kind::variable, 0, static_cast<int>(it - args.begin())};
    });
  } catch (const ExpressionError& err) {
    r.fail_expression(node, err, what);
  }
  if (uses)  // where each argument is written: an unknown one is reported at its column
    for (const auto& a : args)
      uses->emplace_back(element + "/" + a, r.at_column(node, e->column(a)));
  if (args.empty()) {  // a function of time only
    return Law([e](double t) { return e->evaluate({}, Jet(t)).v; });
  }
  return Law(std::move(args), [e](std::span<const Jet> x, Jet t) { return e->evaluate(x, t); });
}

}  // namespace mo2d::scene_detail
