// The expression functions of issue 12 (mod floor ceil round sign hypot clamp, comparisons, if,
// piecewise, the caller's functions): values against closed forms, Jet derivatives against hand
// derivatives and finite differences, errors at the column of the function's name.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mo2d/expression.hpp"

namespace mo2d {
namespace {

using std::numbers::pi;

// e(t) with a = 3, b = 0.5 and the caller's function sq(x) = x^2 (its own chain rule).
const NamedFunction kSquare{"sq", [](Jet x) { return x * x; }};

Expression bound(const std::string& text) {
  Expression e = Expression::parse(text, std::span(&kSquare, 1));
  e.bind([](const std::string& n) {
    if (n == "t") return Binding{Binding::Kind::time, 0, -1};
    if (n == "a") return Binding{Binding::Kind::constant, 3.0, -1};
    if (n == "b") return Binding{Binding::Kind::constant, 0.5, -1};
    return Binding{};
  });
  return e;
}

Jet at(const std::string& text, double t) {
  return bound(text).evaluate({}, Jet::variable(t));
}

double value(const std::string& text, double t = 0) {
  return at(text, t).v;
}

// The Jet derivatives of `text` at t against central differences of the value and of d.
void expect_fd(const std::string& text, double t) {
  SCOPED_TRACE(text + " at t = " + std::to_string(t));
  const Expression e = bound(text);
  const double h = 1e-5;
  auto f = [&](double s) { return e.evaluate({}, Jet::variable(s)); };
  const Jet j = f(t);
  EXPECT_NEAR(j.d, (f(t + h).v - f(t - h).v) / (2 * h), 1e-7 * (1 + std::abs(j.d)));
  EXPECT_NEAR(j.dd, (f(t + h).d - f(t - h).d) / (2 * h), 1e-6 * (1 + std::abs(j.dd)));
}

TEST(ExpressionFunctions, ModIsFlooredLikePython) {
  EXPECT_EQ(value("mod(7, 3)"), 1);
  EXPECT_EQ(value("mod(-1, 3)"), 2);
  EXPECT_EQ(value("mod(-7, 3)"), 2);
  EXPECT_EQ(value("mod(7, -3)"), -2);
  EXPECT_EQ(value("mod(5.5, 2)"), 1.5);
  EXPECT_EQ(value("mod(6, 3)"), 0);
  EXPECT_EQ(value("mod(-1e-20, 1)"), 0);  // r + y rounds to y: stays in [0, y)
  EXPECT_NEAR(value("mod(13*pi + 0.25, 2*pi)"), pi + 0.25, 1e-14);
  EXPECT_TRUE(std::isnan(value("mod(1, 0)")));
  // d/dt mod(a t^2, 2 pi) = 2 a t, second 2 a; with a moving modulus mod(t, b t + 1):
  // x - k y with k = floor(t / (b t + 1)) = 1 at t = 7 (7 / 4.5): d = 1 - k b
  const Jet m = at("mod(a*t^2, 2*pi)", 2.0);
  EXPECT_NEAR(m.v, std::fmod(12.0, 2 * pi), 1e-14);
  EXPECT_NEAR(m.d, 12, 1e-14);
  EXPECT_NEAR(m.dd, 6, 1e-14);
  const Jet v = at("mod(t, b*t + 1)", 7.0);
  EXPECT_NEAR(v.v, 7 - 4.5, 1e-14);
  EXPECT_NEAR(v.d, 1 - 1 * 0.5, 1e-14);
  expect_fd("mod(a*t^2, 2*pi)", 2.0);
  expect_fd("mod(t^2, b*t + 1)", 7.0);
}

TEST(ExpressionFunctions, PiecewiseConstantsHaveZeroDerivatives) {
  EXPECT_EQ(value("floor(-2.5)"), -3);
  EXPECT_EQ(value("ceil(-2.5)"), -2);
  EXPECT_EQ(value("round(2.5)"), 3);
  EXPECT_EQ(value("round(-2.5)"), -3);
  EXPECT_EQ(value("sign(-0.1)") + 2 * value("sign(0)") + 4 * value("sign(3)"), 3);
  for (const char* f : {"floor(a*t)", "ceil(a*t)", "round(a*t)", "sign(t - 1)"}) {
    const Jet j = at(f, 0.7);
    EXPECT_EQ(j.d, 0) << f;
    EXPECT_EQ(j.dd, 0) << f;
  }
  EXPECT_EQ(value("floor(a*t)", 0.7), 2);
}

TEST(ExpressionFunctions, ClampAndHypot) {
  EXPECT_EQ(value("clamp(t, 0, 1)", -2), 0);
  EXPECT_EQ(value("clamp(t, 0, 1)", 0.3), 0.3);
  EXPECT_EQ(value("clamp(t, 0, 1)", 4), 1);
  // the selected branch's derivatives: x, lo(t) = t^2 / 10 or hi(t) = 1 + t^3
  const Jet in = at("clamp(a*t, t^2/10, 1 + t^3)", 0.2);
  EXPECT_NEAR(in.d, 3, 1e-15);
  const Jet lo = at("clamp(-t, t^2/10, 1 + t^3)", 0.5);
  EXPECT_NEAR(lo.d, 0.1, 1e-15);
  EXPECT_NEAR(lo.dd, 0.2, 1e-15);
  const Jet hi = at("clamp(a*t, t^2/10, 1 + t^3)", 0.8);
  EXPECT_NEAR(hi.d, 3 * 0.64, 1e-14);
  EXPECT_NEAR(hi.dd, 6 * 0.8, 1e-14);

  EXPECT_EQ(value("hypot(3, 4)"), 5);
  EXPECT_DOUBLE_EQ(value("hypot(3e200, 4e200)"), 5e200);  // no overflow
  // |(cos t, 2 sin t)|: closed form sqrt(1 + 3 sin^2 t)
  const double t = 0.8, s = std::sin(t), c = std::cos(t), r = std::sqrt(1 + 3 * s * s);
  const Jet h = at("hypot(cos(t), 2*sin(t))", t);
  EXPECT_NEAR(h.v, r, 1e-15);
  EXPECT_NEAR(h.d, 3 * s * c / r, 1e-14);
  EXPECT_NEAR(h.dd, 3 * (c * c - s * s) / r - 9 * s * s * c * c / (r * r * r), 1e-14);
  expect_fd("hypot(cos(t), 2*sin(t))", t);
  expect_fd("hypot(t^2 - 1, a*t)", 1.3);
  // at the origin: the one-sided derivative along the direction, |(3, 4)| = 5
  const Jet o = at("hypot(3*t, 4*t)", 0);
  EXPECT_EQ(o.v, 0);
  EXPECT_NEAR(o.d, 5, 1e-15);
  EXPECT_NEAR(o.dd, 0, 1e-15);
  EXPECT_NEAR(at("hypot(3*t^2, 4*t^2)", 0).dd, 10, 1e-15);  // 5 t^2
}

TEST(ExpressionFunctions, Atan2DerivativesMatchFiniteDifferences) {
  // atan2(sin t, cos t) = t (away from the cut)
  const Jet j = at("atan2(a*sin(t), a*cos(t))", 1.2);
  EXPECT_NEAR(j.v, 1.2, 1e-15);
  EXPECT_NEAR(j.d, 1, 1e-15);
  EXPECT_NEAR(j.dd, 0, 1e-15);
  expect_fd("atan2(t^2 + 0.1, 1 - a*t)", 0.4);
  expect_fd("atan2(t^2 + 0.1, 1 - a*t)", 2.0);  // second quadrant
}

TEST(ExpressionFunctions, ComparisonsIfAndPiecewise) {
  EXPECT_EQ(value("1 < 2") + 2 * value("2 < 2") + 4 * value("2 <= 2") + 8 * value("3 > 2") +
                16 * value("2 >= 3") + 32 * value("2 == 2") + 64 * value("2 != 2"),
            1 + 4 + 8 + 32);
  EXPECT_EQ(value("1 + 2 < 2 * 2"), 1);  // below + and *
  EXPECT_TRUE(std::isnan(value("log(-1) < 1")));
  EXPECT_EQ(value("if(t < 1, 10, 20)", 0.5), 10);
  EXPECT_EQ(value("if(t < 1, 10, 20)", 1), 20);
  EXPECT_TRUE(std::isnan(value("if(log(-1), 1, 2)")));
  // only the selected branch is evaluated: sqrt(t) of a negative t is not
  EXPECT_EQ(value("if(t > 0, sqrt(t), 0)", -1), 0);
  // a rise, a dwell and a fall: derivatives of the selected piece
  const std::string s = "piecewise(t < 1, t^3, t < 2, 1, 3 - t)";
  EXPECT_EQ(value(s, 0.5), 0.125);
  EXPECT_EQ(value(s, 1.5), 1);
  EXPECT_EQ(value(s, 2.5), 0.5);
  const Jet rise = at(s, 0.5);
  EXPECT_NEAR(rise.d, 0.75, 1e-15);
  EXPECT_NEAR(rise.dd, 3, 1e-15);
  EXPECT_EQ(at(s, 1.5).d, 0);
  EXPECT_EQ(at(s, 2.5).d, -1);
  expect_fd(s, 0.5);
  EXPECT_EQ(value("piecewise(t < 0, -1, 1)", -3), -1);
}

TEST(ExpressionFunctions, CallersFunctions) {
  const Jet j = at("sq(sin(t)) + sq(2)", 0.3);
  EXPECT_NEAR(j.v, std::sin(0.3) * std::sin(0.3) + 4, 1e-15);
  EXPECT_NEAR(j.d, std::sin(0.6), 1e-15);
  EXPECT_NEAR(j.dd, 2 * std::cos(0.6), 1e-15);
  // a copy of the expression keeps its functions
  const Expression e = bound("sq(t)");
  const Expression copy = e;
  EXPECT_EQ(copy.evaluate({}, Jet(3)).v, 9);
}

struct Failure {
  int column = -1;
  std::string what;
};
Failure parse_error(const std::string& text) {
  try {
    Expression::parse(text, std::span(&kSquare, 1));
  } catch (const ExpressionError& e) {
    return {e.column(), e.what()};
  }
  return {};
}

TEST(ExpressionFunctions, ErrorsAtTheColumn) {
  auto expect = [](const std::string& text, int column, const std::string& what) {
    const Failure f = parse_error(text);
    EXPECT_EQ(f.column, column) << text;
    EXPECT_EQ(f.what, what) << text;
  };
  expect("1 + clmap(t, 0, 1)", 5, "unknown function 'clmap' (did you mean 'clamp'?)");
  expect("2 * sqq(t)", 5, "unknown function 'sqq' (did you mean 'sq'?)");
  expect("mod(t)", 1, "mod() takes 2 arguments, got 1");
  expect("t + clamp(t, 1)", 5, "clamp() takes 3 arguments, got 2");
  expect("floor(1, 2)", 1, "floor() takes 1 argument, got 2");
  expect("sq(1, 2)", 1, "sq() takes 1 argument, got 2");
  expect("if(t, 1)", 1, "if() takes 3 arguments, got 2");
  expect("3 * piecewise(t < 1, 2, t < 2, 3)", 5,
         "piecewise() takes pairs of a condition and its value, then the default value: an odd "
         "number of arguments (3, 5, ...), got 4");
  expect("0 < t < 1", 7, "comparisons do not chain: write a < b < c as (a < b) * (b < c)");
  expect("t = 1", 3, "'=' is not an operator: compare with '=='");
  expect("!t", 1, "expected a number, a name or '(' but got '!'");
  expect("t ! 1", 3, "'!' is not an operator: compare with '!=', negate a condition c with 1 - c");
  EXPECT_TRUE(Expression::is_function("piecewise"));
  EXPECT_TRUE(Expression::is_function("hypot"));
  EXPECT_FALSE(Expression::is_function("sq"));
}

}  // namespace
}  // namespace mo2d
