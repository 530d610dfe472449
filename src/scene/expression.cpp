// Recursive-descent parser and Jet evaluator of scene expressions (grammar: mo2d/expression.hpp).
#include "mo2d/expression.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
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
const Function1 kFunctions1[] = {
    {"sin", [](Jet a) { return sin(a); }}, {"cos", [](Jet a) { return cos(a); }},
    {"tan", [](Jet a) { return tan(a); }}, {"exp", [](Jet a) { return exp(a); }},
    {"log", [](Jet a) { return log(a); }}, {"sqrt", [](Jet a) { return sqrt(a); }},
    {"abs", [](Jet a) { return abs(a); }}};
const Function2 kFunctions2[] = {{"min", [](Jet a, Jet b) { return min(a, b); }},
                                 {"max", [](Jet a, Jet b) { return max(a, b); }},
                                 {"atan2", [](Jet a, Jet b) { return atan2(a, b); }}};

bool name_start(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
}

}  // namespace

class ExpressionParser {
 public:
  ExpressionParser(Expression& e, std::string_view text) : e_(e), s_(text) {}

  void run() {
    skip();
    if (pos_ >= s_.size()) fail("expected an expression, got nothing");
    e_.root_ = expr(0);
    skip();
    if (pos_ < s_.size()) fail(std::string("unexpected '") + s_[pos_] + "' after the expression");
  }

 private:
  static constexpr int kMaxDepth = 200;
  static constexpr size_t kMaxNodes =
      10000;  // nesting limit: deep input must not overflow the stack

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
    // evaluation recurses once per node: bound the size so no input can overflow the stack
    if (e_.nodes_.size() >= kMaxNodes) fail("expression too long (more than 10000 terms)");
    Expression::Node n;
    n.op = op;
    n.a = a;
    n.b = b;
    n.column = column;
    e_.nodes_.push_back(std::move(n));
    return static_cast<int>(e_.nodes_.size()) - 1;
  }
  int column() const { return static_cast<int>(pos_) + 1; }
  void enter(int depth) const {
    if (depth > kMaxDepth) fail("expression nested too deeply");
  }

  int expr(int depth) {
    enter(depth);
    int left = term(depth + 1);
    for (;;) {
      skip();
      const int col = column();
      if (accept('+'))
        left = add(Expression::Op::add, left, term(depth + 1), col);
      else if (accept('-'))
        left = add(Expression::Op::sub, left, term(depth + 1), col);
      else
        return left;
    }
  }
  int term(int depth) {
    enter(depth);
    int left = unary(depth + 1);
    for (;;) {
      skip();
      const int col = column();
      if (accept('*'))
        left = add(Expression::Op::mul, left, unary(depth + 1), col);
      else if (accept('/'))
        left = add(Expression::Op::div, left, unary(depth + 1), col);
      else
        return left;
    }
  }
  int unary(int depth) {
    enter(depth);
    skip();
    const int col = column();
    if (accept('-')) return add(Expression::Op::neg, unary(depth + 1), -1, col);
    if (accept('+')) return unary(depth + 1);
    return power(depth + 1);
  }
  int power(int depth) {
    enter(depth);
    const int base = primary(depth + 1);
    skip();
    const int col = column();
    if (accept('^')) return add(Expression::Op::pow, base, unary(depth + 1), col);
    return base;
  }
  int primary(int depth) {
    enter(depth);
    skip();
    if (pos_ >= s_.size()) fail("expected a number, a name or '(' but the expression ended");
    const char c = s_[pos_];
    const int col = column();
    if (c == '(') {
      ++pos_;
      const int inner = expr(depth + 1);
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
  int call(const std::string& name, int col, int depth) {
    ++pos_;  // '('
    std::vector<int> args{expr(depth + 1)};
    while (accept(',')) args.push_back(expr(depth + 1));
    if (!accept(')')) fail("expected ',' or ')' in the arguments of " + name + "()");
    for (int k = 0; k < static_cast<int>(std::size(kFunctions1)); ++k)
      if (name == kFunctions1[k].name) {
        if (args.size() != 1) throw ExpressionError(name + "() takes 1 argument", col);
        const int n = add(Expression::Op::call1, args[0], -1, col);
        e_.nodes_[n].function = k;
        return n;
      }
    for (int k = 0; k < static_cast<int>(std::size(kFunctions2)); ++k)
      if (name == kFunctions2[k].name) {
        if (args.size() != 2) throw ExpressionError(name + "() takes 2 arguments", col);
        const int n = add(Expression::Op::call2, args[0], args[1], col);
        e_.nodes_[n].function = k;
        return n;
      }
    std::vector<std::string> known;
    for (const auto& f : kFunctions1) known.emplace_back(f.name);
    for (const auto& f : kFunctions2) known.emplace_back(f.name);
    throw ExpressionError("unknown function '" + name + "'" + did_you_mean(name, known), col);
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
  size_t pos_ = 0;
};

Expression Expression::parse(std::string_view text) {
  Expression e;
  e.text_ = std::string(text);
  ExpressionParser p(e, e.text_);
  p.run();
  return e;
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
    case Op::call1:
      return kFunctions1[n.function].f(eval(n.a, x, t));
    case Op::call2:
      return kFunctions2[n.function].f(eval(n.a, x, t), eval(n.b, x, t));
  }
  return {};
}

}  // namespace mo2d
