// Objective and constraint expressions of an optimization (criterion.hpp).
#include "optimize/criterion.hpp"

#include <algorithm>
#include <cmath>

#include "mo2d/optimize.hpp"

namespace mo2d::optimize_detail {

void fail_criterion(const Criterion& c, int column, const std::string& message) {
  std::string where = c.what + " '" + c.text + "'";
  if (column > 0) where += ", column " + std::to_string(column);
  throw OptimizeInputError(where + ": " + message);
}

namespace {

// The top-level comparison operators of text (outside parentheses): their 0-based positions and
// spellings.
struct Comparison {
  std::size_t at = 0;
  std::string op{};
};
std::vector<Comparison> comparisons(const std::string& s) {
  std::vector<Comparison> out;
  int depth = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const char ch = s[k];
    if (ch == '(') ++depth;
    if (ch == ')') --depth;
    if (depth != 0) continue;
    const bool two = k + 1 < s.size() && s[k + 1] == '=';
    if (ch == '<' || ch == '>' || ((ch == '=' || ch == '!') && two)) {
      out.push_back({k, s.substr(k, two ? 2 : 1)});
      if (two) ++k;
    }
  }
  return out;
}

}  // namespace

Criterion parse_criterion(const std::string& text, const std::string& what,
                          bool comparison_allowed) {
  Criterion c;
  c.text = text;
  c.what = what;
  const std::vector<Comparison> cmp = comparisons(text);
  if (!cmp.empty()) {
    const Comparison& k = cmp.front();
    const int column = static_cast<int>(k.at) + 1;
    if (!comparison_allowed)
      fail_criterion(c, column,
                     "an objective is a number to minimize, not a comparison ('" + k.op + "')");
    if (cmp.size() > 1)
      fail_criterion(c, static_cast<int>(cmp[1].at) + 1,
                     "a constraint has one comparison (g <= h or g >= h)");
    if (k.op != "<=" && k.op != ">=")
      fail_criterion(c, column,
                     "'" + k.op + "': a constraint is g <= h, g >= h or g (meaning g <= 0)");
    c.has_rhs = true;
    c.sign = k.op == "<=" ? 1 : -1;
    c.rhs_offset = static_cast<int>(k.at) + 2;
  }
  const std::string lhs = c.has_rhs ? text.substr(0, cmp.front().at) : text;
  try {
    c.lhs = Expression::parse(lhs);
  } catch (const ExpressionError& e) {
    fail_criterion(c, e.column(), e.what());
  }
  if (c.has_rhs) {
    try {
      c.rhs = Expression::parse(text.substr(static_cast<std::size_t>(c.rhs_offset)));
    } catch (const ExpressionError& e) {
      fail_criterion(c, e.column() + c.rhs_offset, e.what());
    }
  }
  return c;
}

double criterion_value(const Criterion& c, const std::vector<Jet>& values) {
  const double l = c.lhs.evaluate(values).v;
  if (!c.has_rhs) return l;
  return c.sign * (l - c.rhs.evaluate(values).v);
}

double criterion_scale(const Criterion& c, const std::vector<Jet>& values) {
  return c.has_rhs ? std::max(1.0, std::abs(c.rhs.evaluate(values).v)) : 1.0;
}

}  // namespace mo2d::optimize_detail
