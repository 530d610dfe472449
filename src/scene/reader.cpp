// Typed, located reading of YAML nodes (see reader.hpp).
#include "reader.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "model/suggest.hpp"

namespace mo2d::scene_detail {

const char* type_name(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return "a scalar";
    case YAML::NodeType::Sequence:
      return "a sequence";
    case YAML::NodeType::Map:
      return "a map";
    case YAML::NodeType::Null:
      return "nothing";
    case YAML::NodeType::Undefined:
      break;
  }
  return "nothing";
}

Location Reader::at(const YAML::Node& node) const {
  Location l;
  l.file = file;
  if (node.IsDefined()) {
    const YAML::Mark m = node.Mark();
    if (!m.is_null()) {
      l.line = m.line + 1;
      l.column = m.column + 1;
    }
  }
  return l;
}

void Reader::fail(const YAML::Node& node, const std::string& message) const {
  throw SceneError(at(node), message);
}

void Reader::check_keys(const YAML::Node& node, std::initializer_list<const char*> allowed,
                        const std::string& what) const {
  if (!node.IsMap()) fail(node, what + ": expected a map, got " + type_name(node));
  const std::vector<std::string> names(allowed.begin(), allowed.end());
  std::set<std::string> seen;
  for (auto it = node.begin(); it != node.end(); ++it) {
    const YAML::Node key = it->first;
    if (!key.IsScalar()) fail(key, what + ": expected a key name, got " + type_name(key));
    const std::string& k = key.Scalar();
    if (std::find(names.begin(), names.end(), k) == names.end()) {
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      fail(key, what + ": unknown key '" + k + "'" + did_you_mean(k, names) +
                    "; expected one of: " + list);
    }
    if (!seen.insert(k).second) fail(key, what + ": key '" + k + "' appears twice");
  }
}

Entries Reader::entries(const YAML::Node& node, const std::string& what) const {
  Entries out;
  if (!node.IsDefined() || node.IsNull()) return out;
  if (!node.IsMap()) fail(node, what + ": expected a map (name: value), got " + type_name(node));
  std::set<std::string> seen;
  for (auto it = node.begin(); it != node.end(); ++it) {
    const YAML::Node key = it->first;
    if (!key.IsScalar() || key.Scalar().empty())
      fail(key, what + ": expected a name, got " + type_name(key));
    if (!seen.insert(key.Scalar()).second)
      fail(key, what + ": '" + key.Scalar() + "' is defined twice");
    out.emplace_back(key, it->second);
  }
  return out;
}

YAML::Node Reader::required(const YAML::Node& map, const char* key, const std::string& what) const {
  const YAML::Node v = map[key];
  if (!v.IsDefined()) fail(map, what + ": missing required key '" + key + "'");
  return v;
}

std::string Reader::string(const YAML::Node& node, const std::string& what) const {
  if (!node.IsScalar()) fail(node, what + ": expected a name, got " + type_name(node));
  return node.Scalar();
}

bool Reader::boolean(const YAML::Node& node, const std::string& what) const {
  if (node.IsScalar()) {
    const std::string& s = node.Scalar();
    if (s == "true" || s == "yes" || s == "on") return true;
    if (s == "false" || s == "no" || s == "off") return false;
  }
  fail(node, what + ": expected true or false, got " +
                 (node.IsScalar() ? "'" + node.Scalar() + "'" : std::string(type_name(node))));
}

int Reader::integer(const YAML::Node& node, const std::string& what) const {
  const double v = number(node, what);
  if (v != std::round(v) || std::abs(v) > 1e9) fail(node, what + ": expected an integer");
  return static_cast<int>(v);
}

Binding Reader::parameter_binding(const std::string& name) const {
  auto it = parameters.find(name);
  if (it == parameters.end()) return {};
  return {Binding::Kind::constant, it->second, -1};
}

Expression Reader::expression(const YAML::Node& node, const std::string& what) const {
  if (!node.IsScalar())
    fail(node, what + ": expected a number or an expression, got " + type_name(node));
  try {
    return Expression::parse(node.Scalar(), functions);
  } catch (const ExpressionError& e) {
    fail_expression(node, e, what);
  }
}

Location Reader::at_column(const YAML::Node& node, int column) const {
  Location l = at(node);
  const bool quoted = node.Tag() == "!";  // yaml-cpp tags quoted scalars "!", plain ones "?"
  const auto pos = static_cast<size_t>(node.Mark().pos);
  const bool block = pos < source.size() && (source[pos] == '|' || source[pos] == '>');
  if (l.line > 0 && !block && node.Scalar().find('\n') == std::string::npos)
    l.column += (quoted ? 1 : 0) + column - 1;
  return l;
}

void Reader::fail_expression(const YAML::Node& node, const ExpressionError& e,
                             const std::string& what) const {
  const Location l = at_column(node, e.column());
  const std::string& text = node.Scalar();
  // quote the expression, but keep the one-line message readable
  const std::string shown = text.size() <= 80 ? text : text.substr(0, 77) + "...";
  throw SceneError(l, what + ": in expression '" + shown + "': " + e.what());
}

double Reader::number(const YAML::Node& node, const std::string& what) const {
  Expression e = expression(node, what);
  try {
    e.bind(
        [&](const std::string& n) {
          if (n == "t")
            throw ExpressionError(
                "a constant is expected here: 't' is only allowed in motions, "
                "forces, torques, efforts and constraints",
                0);
          return parameter_binding(n);
        },
        parameter_names);
  } catch (const ExpressionError& err) {
    if (err.column() == 0) fail(node, what + ": " + err.what());
    fail_expression(node, err, what);
  }
  const double v = e.evaluate().v;
  if (!std::isfinite(v)) fail(node, what + ": '" + node.Scalar() + "' is not a finite number");
  return v;
}

double Reader::number_or(const YAML::Node& map, const char* key, double fallback,
                         const std::string& what) const {
  const YAML::Node v = map[key];
  return v.IsDefined() ? number(v, what + "." + key) : fallback;
}

Vec2 Reader::vec2(const YAML::Node& node, const std::string& what) const {
  if (!node.IsSequence() || node.size() != 2)
    fail(node, what + ": expected a point [x, y], got " +
                   (node.IsSequence() ? std::to_string(node.size()) + " values"
                                      : std::string(type_name(node))));
  return {number(node[0], what + ".x"), number(node[1], what + ".y")};
}

std::vector<std::string> Reader::strings(const YAML::Node& node, const std::string& what) const {
  if (!node.IsSequence()) fail(node, what + ": expected a list of names, got " + type_name(node));
  std::vector<std::string> out;
  for (const auto& n : node) out.push_back(string(n, what));
  return out;
}

std::shared_ptr<const Expression> Reader::time_function(const YAML::Node& node,
                                                        const std::string& what) const {
  auto e = std::make_shared<Expression>(expression(node, what));
  try {
    e->bind(
        [&](const std::string& n) {
          if (n == "t") return Binding{Binding::Kind::time, 0, -1};
          return parameter_binding(n);
        },
        parameter_names);
  } catch (const ExpressionError& err) {
    fail_expression(node, err, what);
  }
  return e;
}

}  // namespace mo2d::scene_detail
