// Recursive-descent parser and Jet evaluator of scene expressions (grammar: mo2d/expression.hpp).
#include "mo2d/expression.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <numeric>

#include "model/suggest.hpp"

namespace mo2d {

namespace {

struct Function1 {
  const char* name;
  Jet (*f)(Jet);
};
struct Function2 {
  const char* name;
  Jet (*f)(Jet, Jet);
};
struct Function3 {
  const char* name;
  Jet (*f)(Jet, Jet, Jet);
};
const Function1 kFunctions1[] = {
    {"sin", [](Jet a) { return sin(a); }},   {"cos", [](Jet a) { return cos(a); }},
    {"tan", [](Jet a) { return tan(a); }},   {"exp", [](Jet a) { return exp(a); }},
    {"log", [](Jet a) { return log(a); }},   {"sqrt", [](Jet a) { return sqrt(a); }},
    {"abs", [](Jet a) { return abs(a); }},   {"floor", [](Jet a) { return floor(a); }},
    {"ceil", [](Jet a) { return ceil(a); }}, {"round", [](Jet a) { return round(a); }},
    {"sign", [](Jet a) { return sign(a); }}};
const Function2 kFunctions2[] = {{"min", [](Jet a, Jet b) { return min(a, b); }},
                                 {"max", [](Jet a, Jet b) { return max(a, b); }},
                                 {"atan2", [](Jet a, Jet b) { return atan2(a, b); }},
                                 {"hypot", [](Jet a, Jet b) { return hypot(a, b); }},
                                 {"mod", [](Jet a, Jet b) { return mod(a, b); }}};
const Function3 kFunctions3[] = {{"clamp", [](Jet x, Jet lo, Jet hi) { return clamp(x, lo, hi); }}};
// special forms, evaluated lazily: if(c, a, b), piecewise(c1, v1, ..., default)
const char* const kSpecialForms[] = {"if", "piecewise"};

enum Comparison { kLess, kLessEqual, kGreater, kGreaterEqual, kEqual, kNotEqual };

Jet compare(int kind, double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return Jet(std::numeric_limits<double>::quiet_NaN());
  bool r = false;
  switch (kind) {
    case kLess:
      r = a < b;
      break;
    case kLessEqual:
      r = a <= b;
      break;
    case kGreater:
      r = a > b;
      break;
    case kGreaterEqual:
      r = a >= b;
      break;
    case kEqual:
      r = a == b;
      break;
    default:
      r = a != b;
      break;
  }
  return Jet(r ? 1.0 : 0.0);
}

std::string arguments(size_t n) {
  return std::to_string(n) + (n == 1 ? " argument" : " arguments");
}

bool name_start(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
}

}  // namespace

class ExpressionParser {
 public:
  ExpressionParser(Expression& e, std::string_view text, std::span<const NamedFunction> functions)
      : e_(e), s_(text), user_(functions) {}

  void run() {
    skip();
    if (pos_ >= s_.size()) fail("expected an expression, got nothing");
    e_.root_ = expr(0);
    skip();
    if (pos_ < s_.size()) fail(std::string("unexpected '") + s_[pos_] + "' after the expression");
  }

 private:
  // Nesting: parentheses, function calls and chains of unary signs or powers (the parser
  // recurses at each). Size: terms (numbers and names) and all nodes; evaluation recurses once
  // per level of the tree, which is at most the terms plus the nesting, so no accepted input can
  // overflow the stack.
  static constexpr int kMaxDepth = 200;
  static constexpr int kMaxTerms = 10000;
  static constexpr size_t kMaxNodes = 50000;

  [[noreturn]] void fail(const std::string& what) const {
    throw ExpressionError(what, static_cast<int>(pos_) + 1);
  }
  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool accept(char c) {
    skip();
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  int add(Expression::Op op, int a = -1, int b = -1, int column = 0) {
    if (op == Expression::Op::number || op == Expression::Op::name) {
      if (terms_ == kMaxTerms)
        fail("expression too long (more than " + std::to_string(kMaxTerms) +
             " terms: numbers and names)");
      ++terms_;
    }
    if (e_.nodes_.size() >= kMaxNodes)
      fail("expression too long (more than " + std::to_string(kMaxNodes) +
           " operations and terms)");
    Expression::Node n;
    n.op = op;
    n.a = a;
    n.b = b;
    n.column = column;
    e_.nodes_.push_back(std::move(n));
    return static_cast<int>(e_.nodes_.size()) - 1;
  }
  int column() const { return static_cast<int>(pos_) + 1; }
  // one level deeper: a '(' , a function's argument, a unary sign or an exponent
  int deeper(int depth) const {
    if (depth >= kMaxDepth)
      fail("expression nested too deeply (more than " + std::to_string(kMaxDepth) +
           " levels of parentheses, function calls, signs and powers)");
    return depth + 1;
  }

  // A comparison operator at pos_ (consumed), or -1.
  int comparison() {
    skip();
    if (pos_ >= s_.size()) return -1;
    const char c = s_[pos_];
    const bool eq = pos_ + 1 < s_.size() && s_[pos_ + 1] == '=';
    int kind = -1;
    if (c == '<') kind = eq ? kLessEqual : kLess;
    if (c == '>') kind = eq ? kGreaterEqual : kGreater;
    if (c == '=') {
      if (!eq) fail("'=' is not an operator: compare with '=='");
      kind = kEqual;
    }
    if (c == '!') {
      if (!eq) fail("'!' is not an operator: compare with '!=', negate a condition c with 1 - c");
      kind = kNotEqual;
    }
    if (kind >= 0) pos_ += eq ? 2 : 1;
    return kind;
  }
  int expr(int depth) {
    const int left = sum(depth);
    skip();
    const int col = column();
    const int kind = comparison();
    if (kind < 0) return left;
    const int n = add(Expression::Op::compare, left, sum(depth), col);
    e_.nodes_[n].function = kind;
    skip();
    const size_t at = pos_;
    if (comparison() >= 0) {
      pos_ = at;
      fail("comparisons do not chain: write a < b < c as (a < b) * (b < c)");
    }
    return n;
  }
  int sum(int depth) {
    int left = term(depth);
    for (;;) {
      skip();
      const int col = column();
      if (accept('+'))
        left = add(Expression::Op::add, left, term(depth), col);
      else if (accept('-'))
        left = add(Expression::Op::sub, left, term(depth), col);
      else
        return left;
    }
  }
  int term(int depth) {
    int left = unary(depth);
    for (;;) {
      skip();
      const int col = column();
      if (accept('*'))
        left = add(Expression::Op::mul, left, unary(depth), col);
      else if (accept('/'))
        left = add(Expression::Op::div, left, unary(depth), col);
      else
        return left;
    }
  }
  int unary(int depth) {
    skip();
    const int col = column();
    if (accept('-')) return add(Expression::Op::neg, unary(deeper(depth)), -1, col);
    if (accept('+')) return unary(deeper(depth));
    return power(depth);
  }
  int power(int depth) {
    const int base = primary(depth);
    skip();
    const int col = column();
    if (accept('^')) return add(Expression::Op::pow, base, unary(deeper(depth)), col);
    return base;
  }
  int primary(int depth) {
    skip();
    if (pos_ >= s_.size()) fail("expected a number, a name or '(' but the expression ended");
    const char c = s_[pos_];
    const int col = column();
    if (c == '(') {
      ++pos_;
      const int inner = expr(deeper(depth));
      if (!accept(')')) fail("expected ')'");
      return inner;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (name_start(c)) {
      const size_t start = pos_;
      while (pos_ < s_.size() && name_char(s_[pos_])) ++pos_;
      std::string name(s_.substr(start, pos_ - start));
      if (name.back() == '.') {
        pos_ = start + name.size() - 1;
        fail("a name may not end with '.'");
      }
      skip();
      if (pos_ < s_.size() && s_[pos_] == '(') return call(name, col, depth);
      if (name == "pi") {
        const int n = add(Expression::Op::number, -1, -1, col);
        e_.nodes_[n].value = std::numbers::pi;
        return n;
      }
      const int n = add(Expression::Op::name, -1, -1, col);
      e_.nodes_[n].name = std::move(name);
      return n;
    }
    fail(std::string("expected a number, a name or '(' but got '") + c + "'");
  }
  int select(int condition, int then, int otherwise, int col) {
    const int n = add(Expression::Op::select, condition, then, col);
    e_.nodes_[n].c = otherwise;
    return n;
  }
  int call(const std::string& name, int col, int depth) {
    ++pos_;  // '('
    std::vector<int> args{expr(deeper(depth))};
    while (accept(',')) args.push_back(expr(deeper(depth)));
    if (!accept(')')) fail("expected ',' or ')' in the arguments of " + name + "()");
    const size_t count = args.size();
    auto arity = [&](size_t expected) {
      if (count != expected)
        throw ExpressionError(
            name + "() takes " + arguments(expected) + ", got " + std::to_string(count), col);
    };
    if (name == "if") {
      arity(3);
      return select(args[0], args[1], args[2], col);
    }
    if (name == "piecewise") {
      if (count < 3 || count % 2 == 0)
        throw ExpressionError(
            "piecewise() takes pairs of a condition and its value, then the default value: an "
            "odd number of arguments (3, 5, ...), got " +
                std::to_string(count),
            col);
      int out = args.back();  // piecewise(c1, v1, c2, v2, d) = if(c1, v1, if(c2, v2, d))
      for (size_t k = count - 1; k >= 2; k -= 2) out = select(args[k - 2], args[k - 1], out, col);
      return out;
    }
    if (const int k = find(kFunctions1, name); k >= 0) {
      arity(1);
      return function(Expression::Op::call1, k, args, col);
    }
    if (const int k = find(kFunctions2, name); k >= 0) {
      arity(2);
      return function(Expression::Op::call2, k, args, col);
    }
    if (const int k = find(kFunctions3, name); k >= 0) {
      arity(3);
      return function(Expression::Op::call3, k, args, col);
    }
    for (const auto& f : user_)
      if (f.name == name) {
        arity(1);
        return function(Expression::Op::user, user_function(f), args, col);
      }
    std::vector<std::string> known = Expression::function_names();
    for (const auto& f : user_) known.push_back(f.name);
    throw ExpressionError("unknown function '" + name + "'" + did_you_mean(name, known), col);
  }
  template <class Functions>
  static int find(const Functions& table, const std::string& name) {
    for (int k = 0; k < static_cast<int>(std::size(table)); ++k)
      if (name == table[k].name) return k;
    return -1;
  }
  int function(Expression::Op op, int k, const std::vector<int>& args, int col) {
    const int n = add(op, args[0], args.size() > 1 ? args[1] : -1, col);
    e_.nodes_[n].c = args.size() > 2 ? args[2] : -1;
    e_.nodes_[n].function = k;
    return n;
  }
  // index of `f` in the expression's own copies of the caller's functions
  int user_function(const NamedFunction& f) {
    auto& own = e_.functions_;
    for (size_t k = 0; k < own.size(); ++k)
      if (own[k].name == f.name) return static_cast<int>(k);
    own.push_back(f);
    return static_cast<int>(own.size()) - 1;
  }
  int number() {
    const size_t start = pos_;
    while (pos_ < s_.size() &&
           (std::isdigit(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '.'))
      ++pos_;
    if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
      size_t p = pos_ + 1;
      if (p < s_.size() && (s_[p] == '+' || s_[p] == '-')) ++p;
      if (p < s_.size() && std::isdigit(static_cast<unsigned char>(s_[p]))) {
        pos_ = p;
        while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
      }
    }
    const std::string text(s_.substr(start, pos_ - start));
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || std::count(text.begin(), text.end(), '.') > 1) {
      pos_ = start;
      fail("malformed number '" + text + "'");
    }
    if (pos_ < s_.size() && name_start(s_[pos_])) fail("expected an operator after the number");
    const int n = add(Expression::Op::number, -1, -1, static_cast<int>(start) + 1);
    e_.nodes_[n].value = v;
    return n;
  }

  Expression& e_;
  std::string_view s_;
  std::span<const NamedFunction> user_;
  size_t pos_ = 0;
  int terms_ = 0;  // numbers and names so far
};

Expression Expression::parse(std::string_view text, std::span<const NamedFunction> functions) {
  Expression e;
  e.text_ = std::string(text);
  ExpressionParser p(e, e.text_, functions);
  p.run();
  return e;
}

std::vector<std::string> Expression::function_names() {
  std::vector<std::string> out;
  for (const auto& f : kFunctions1) out.emplace_back(f.name);
  for (const auto& f : kFunctions2) out.emplace_back(f.name);
  for (const auto& f : kFunctions3) out.emplace_back(f.name);
  for (const char* f : kSpecialForms) out.emplace_back(f);
  return out;
}

bool Expression::is_function(std::string_view name) {
  const auto names = function_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::vector<std::string> Expression::names() const {
  std::vector<std::string> out;
  for (const auto& n : nodes_)
    if (n.op == Op::name && std::find(out.begin(), out.end(), n.name) == out.end())
      out.push_back(n.name);
  return out;
}

int Expression::column(std::string_view name) const {
  int best = 0;
  for (const auto& n : nodes_)
    if (n.op == Op::name && n.name == name && (best == 0 || n.column < best)) best = n.column;
  return best;
}

void Expression::bind(const std::function<Binding(const std::string&)>& resolve,
                      std::span<const std::string> candidates) {
  for (auto& n : nodes_) {
    if (n.op != Op::name) continue;
    n.binding = resolve(n.name);
    if (n.binding.kind == Binding::Kind::unbound)
      throw ExpressionError("undefined name '" + n.name + "'" + did_you_mean(n.name, candidates),
                            n.column);
  }
}

bool Expression::depends_on_time() const {
  return std::any_of(nodes_.begin(), nodes_.end(), [](const Node& n) {
    return n.op == Op::name && n.binding.kind != Binding::Kind::constant;
  });
}

Jet Expression::evaluate(std::span<const Jet> variables, Jet t) const {
  return eval(root_, variables, t);
}

Jet Expression::eval(int i, std::span<const Jet> x, Jet t) const {
  const Node& n = nodes_[static_cast<size_t>(i)];
  switch (n.op) {
    case Op::number:
      return Jet(n.value);
    case Op::name:
      switch (n.binding.kind) {
        case Binding::Kind::constant:
          return Jet(n.binding.value);
        case Binding::Kind::time:
          return t;
        case Binding::Kind::variable:
          if (n.binding.index < 0 || static_cast<size_t>(n.binding.index) >= x.size())
            throw Error("expression '" + text_ + "': variable '" + n.name + "' has no value");
          return x[static_cast<size_t>(n.binding.index)];
        case Binding::Kind::unbound:
          break;
      }
      throw Error("expression '" + text_ + "': name '" + n.name + "' is not bound");
    case Op::neg:
      return -eval(n.a, x, t);
    case Op::add:
      return eval(n.a, x, t) + eval(n.b, x, t);
    case Op::sub:
      return eval(n.a, x, t) - eval(n.b, x, t);
    case Op::mul:
      return eval(n.a, x, t) * eval(n.b, x, t);
    case Op::div:
      return eval(n.a, x, t) / eval(n.b, x, t);
    case Op::pow: {
      const Jet a = eval(n.a, x, t), b = eval(n.b, x, t);
      // constant exponent: a^p through the power rule (defined for a < 0 and integer p)
      if (b.d == 0 && b.dd == 0) return pow(a, b.v);
      return pow(a, b);
    }
    case Op::compare:
      return compare(n.function, eval(n.a, x, t).v, eval(n.b, x, t).v);
    case Op::select: {
      const double c = eval(n.a, x, t).v;
      if (std::isnan(c)) return Jet(c);
      return eval(c != 0 ? n.b : n.c, x, t);
    }
    case Op::call1:
      return kFunctions1[n.function].f(eval(n.a, x, t));
    case Op::call2:
      return kFunctions2[n.function].f(eval(n.a, x, t), eval(n.b, x, t));
    case Op::call3:
      return kFunctions3[n.function].f(eval(n.a, x, t), eval(n.b, x, t), eval(n.c, x, t));
    case Op::user:
      return functions_[static_cast<size_t>(n.function)].f(eval(n.a, x, t));
  }
  return {};
}

}  // namespace mo2d
