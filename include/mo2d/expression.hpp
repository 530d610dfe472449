#pragma once
// Expressions of scene files: a small recursive-descent parser and an evaluator over Jet, so a
// motion s(t) written as text gives s, s_dot and s_ddot exactly (no finite differences).
//
// Grammar (usual precedence, '^' binds tighter than unary minus and is right-associative):
//   expr    := sum (('<' | '<=' | '>' | '>=' | '==' | '!=') sum)?   (comparisons do not chain)
//   sum     := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power
//   power   := primary ('^' unary)?
//   primary := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'
// Functions: sin cos tan exp log sqrt abs floor ceil round sign (one argument), min max atan2
// hypot mod (two), clamp(x, lo, hi), if(c, a, b) and piecewise(c1, v1, c2, v2, ..., default),
// plus the caller's own functions of one argument (tables). Constant: pi. A comparison is 1 or 0;
// a condition holds when it is not 0 (NaN gives NaN); if() and piecewise() evaluate only the
// branch they select.
// Names may contain dots after the first character ("crank.angle"); they are bound by the caller
// to constants (parameters), the time t or variables (coordinates of a user constraint).
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mo2d/error.hpp"
#include "mo2d/jet.hpp"

namespace mo2d {

// A parse or binding error; column() is 1-based in the expression text.
class ExpressionError : public Error {
 public:
  // `what`: the message; `column`: 1-based column in the expression text.
  ExpressionError(const std::string& what, int column) : Error(what), column_(column) {}
  // 1-based column of the offending character in the expression text.
  int column() const { return column_; }

 private:
  int column_ = 0;
};

// A function of one argument the caller adds to expressions by name (a Table, ...): Jet in, Jet
// out, so it must apply the chain rule (value, first and second derivative along the argument's
// direction). Built-in names take precedence: give it a name that is not one.
struct NamedFunction {
  // the name expressions call it by
  std::string name{};
  // the function, applying the chain rule to its Jet argument
  std::function<Jet(Jet)> f{};
};

// What a name stands for.
struct Binding {
  // what the name is: not yet bound, a constant (value), the time t, a variable (index)
  enum class Kind { unbound, constant, time, variable } kind = Kind::unbound;
  double value = 0;  // constant
  int index = -1;    // variable: index into the span passed to evaluate()
};

// An arithmetic expression of a scene (docs/scene-format.md, expressions) over named constants, the
// time t and variables, evaluated with its first two derivatives (Jet): parse() it, bind() its
// names, then evaluate().
class Expression {
 public:
  // Throws ExpressionError with the column of the offending character (an unknown function or
  // a wrong number of arguments: the column of the function's name). `functions`: the caller's
  // functions of one argument, copied into the expression where it calls them.
  static Expression parse(std::string_view text, std::span<const NamedFunction> functions = {});
  // The built-in function names (sin ... piecewise), and whether `name` is one of them.
  static std::vector<std::string> function_names();
  static bool is_function(std::string_view name);

  // The text it was parsed from.
  const std::string& text() const { return text_; }
  // Names the expression uses (not functions, not pi), unique, in order of first use.
  std::vector<std::string> names() const;
  // 1-based column of the first use of `name` in the text (0 if unused).
  int column(std::string_view name) const;
  // Resolve every name; an unbound one throws ExpressionError at its column, with a
  // "did you mean" suggestion taken from `candidates`.
  void bind(const std::function<Binding(const std::string& name)>& resolve,
            std::span<const std::string> candidates = {});
  // Value and first two derivatives (along t and the variables' own derivatives). All names must
  // be bound. No allocation.
  Jet evaluate(std::span<const Jet> variables = {}, Jet t = {}) const;
  // Whether the value depends on the time t (a name bound to Kind::time).
  bool depends_on_time() const;

 private:
  enum class Op {
    number,
    name,
    neg,
    add,
    sub,
    mul,
    div,
    pow,
    compare,
    select,
    call1,
    call2,
    call3,
    user
  };
  struct Node {
    Op op = Op::number;
    double value = 0;
    int a = -1, b = -1, c = -1;  // children (select: condition, then, else)
    int function = -1;   // callN: index in the function tables; user: in functions_; compare: kind
    int column = 0;      // 1-based
    std::string name{};  // name
    Binding binding{};   // name
  };
  Jet eval(int node, std::span<const Jet> variables, Jet t) const;
  friend class ExpressionParser;
  std::string text_{};
  std::vector<Node> nodes_{};
  std::vector<NamedFunction> functions_{};  // the caller's functions this expression calls
  int root_ = -1;
};

}  // namespace mo2d
