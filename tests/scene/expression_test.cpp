// Scene expressions: parsing, precedence, exact first and second derivatives against hand
// derivatives, and errors with the column of the offending character.
#include "mo2d/expression.hpp"

#include <gtest/gtest.h>
#include <pthread.h>

#include <cmath>
#include <numbers>

#include "model/suggest.hpp"

namespace mo2d {
namespace {

constexpr double kTol = 1e-13;  // hand derivatives and Jet agree to rounding

// Expression of t with parameters a = 2, b = 0.5.
Jet at(const std::string& text, double t) {
  Expression e = Expression::parse(text);
  e.bind([](const std::string& n) {
    if (n == "t") return Binding{Binding::Kind::time, 0, -1};
    if (n == "a") return Binding{Binding::Kind::constant, 2.0, -1};
    if (n == "b") return Binding{Binding::Kind::constant, 0.5, -1};
    return Binding{};
  });
  return e.evaluate({}, Jet::variable(t));
}

void expect_jet(Jet j, double v, double d, double dd) {
  EXPECT_NEAR(j.v, v, kTol * (1 + std::abs(v)));
  EXPECT_NEAR(j.d, d, kTol * (1 + std::abs(d)));
  EXPECT_NEAR(j.dd, dd, kTol * (1 + std::abs(dd)));
}

TEST(Expression, PrecedenceAndAssociativity) {
  EXPECT_DOUBLE_EQ(at("1 + 2 * 3", 0).v, 7);
  EXPECT_DOUBLE_EQ(at("(1 + 2) * 3", 0).v, 9);
  EXPECT_DOUBLE_EQ(at("2 ^ 3 ^ 2", 0).v, 512);  // right-associative
  EXPECT_DOUBLE_EQ(at("-2 ^ 2", 0).v, -4);      // unary minus below ^
  EXPECT_DOUBLE_EQ(at("2 ^ -1", 0).v, 0.5);
  EXPECT_DOUBLE_EQ(at("8 / 4 / 2", 0).v, 1);  // left-associative
  EXPECT_DOUBLE_EQ(at("10 - 4 - 3", 0).v, 3);
  EXPECT_DOUBLE_EQ(at("--3", 0).v, 3);
  EXPECT_DOUBLE_EQ(at("1.5e2 + .5 + 2E-1", 0).v, 150.7);
  EXPECT_DOUBLE_EQ(at("pi", 0).v, std::numbers::pi);
  EXPECT_DOUBLE_EQ(at("a * b", 0).v, 1.0);
  EXPECT_DOUBLE_EQ(at("min(a, b) + max(a, b)", 0).v, 2.5);
  EXPECT_DOUBLE_EQ(at("abs(-a)", 0).v, 2);
}

TEST(Expression, DerivativesMatchHandDerivatives) {
  const double t = 0.7;
  // a sin(3t): 3a cos(3t), -9a sin(3t)
  expect_jet(at("a*sin(3*t)", t), 2 * std::sin(3 * t), 6 * std::cos(3 * t), -18 * std::sin(3 * t));
  // t^2 cos(t)
  expect_jet(at("t^2*cos(t)", t), t * t * std::cos(t), 2 * t * std::cos(t) - t * t * std::sin(t),
             2 * std::cos(t) - 4 * t * std::sin(t) - t * t * std::cos(t));
  // exp(-b t)
  expect_jet(at("exp(-b*t)", t), std::exp(-0.5 * t), -0.5 * std::exp(-0.5 * t),
             0.25 * std::exp(-0.5 * t));
  // log(1 + t^2): 2t/(1+t^2), (2 - 2t^2)/(1+t^2)^2
  const double u = 1 + t * t;
  expect_jet(at("log(1 + t^2)", t), std::log(u), 2 * t / u, (2 - 2 * t * t) / (u * u));
  // sqrt(t): 1/(2 sqrt t), -1/(4 t^1.5)
  expect_jet(at("sqrt(t)", t), std::sqrt(t), 0.5 / std::sqrt(t), -0.25 / std::pow(t, 1.5));
  // tan(t): sec^2, 2 sec^2 tan
  const double sec2 = 1 / (std::cos(t) * std::cos(t));
  expect_jet(at("tan(t)", t), std::tan(t), sec2, 2 * sec2 * std::tan(t));
  // 1/t: -1/t^2, 2/t^3
  expect_jet(at("1/t", t), 1 / t, -1 / (t * t), 2 / (t * t * t));
  // (pi/6) sin^4(pi t/4) (3RRR platform angle), with a negative base: sin < 0 at t = 5
  const double T = 5, w = std::numbers::pi / 4, s = std::sin(w * T), c = std::cos(w * T);
  expect_jet(at("(pi/6) * sin(pi/4*t)^4", T), std::numbers::pi / 6 * std::pow(s, 4),
             std::numbers::pi / 6 * 4 * w * s * s * s * c,
             std::numbers::pi / 6 * (12 * w * w * s * s * c * c - 4 * w * w * std::pow(s, 4)));
  // t^t = exp(t log t): variable exponent
  expect_jet(at("t^t", t), std::pow(t, t), std::pow(t, t) * (std::log(t) + 1),
             std::pow(t, t) * ((std::log(t) + 1) * (std::log(t) + 1) + 1 / t));
  // unary minus and subtraction
  expect_jet(at("-(t - 3*t^2)", t), -(t - 3 * t * t), -(1 - 6 * t), 6);
}

TEST(Expression, VariablesAndNamesWithDots) {
  Expression e = Expression::parse("crank.A.x - 0.5*cos(crank.angle) + t");
  EXPECT_EQ(e.names(), (std::vector<std::string>{"crank.A.x", "crank.angle", "t"}));
  e.bind([](const std::string& n) {
    if (n == "t") return Binding{Binding::Kind::time, 0, -1};
    return Binding{Binding::Kind::variable, 0, n == "crank.A.x" ? 0 : 1};
  });
  const Jet x[2] = {Jet(1.0, 2.0, 0.0), Jet(0.3, 1.0, 0.0)};
  const Jet r = e.evaluate(x, Jet(0.1, 1, 0));
  EXPECT_NEAR(r.v, 1.0 - 0.5 * std::cos(0.3) + 0.1, kTol);
  EXPECT_NEAR(r.d, 2.0 + 0.5 * std::sin(0.3) + 1, kTol);
  EXPECT_NEAR(r.dd, 0.5 * std::cos(0.3), kTol);
  EXPECT_TRUE(e.depends_on_time());
}

int error_column(const std::string& text) {
  try {
    Expression::parse(text);
  } catch (const ExpressionError& e) {
    return e.column();
  }
  return -1;
}

TEST(Expression, ParseErrorsGiveTheColumn) {
  EXPECT_EQ(error_column("1 + * 2"), 5);
  EXPECT_EQ(error_column("(1 + 2"), 7);
  EXPECT_EQ(error_column("1 + 2)"), 6);
  EXPECT_EQ(error_column(""), 1);
  EXPECT_EQ(error_column("2 $ 3"), 3);
  EXPECT_EQ(error_column("sinn(t)"), 1);
  EXPECT_EQ(error_column("min(1)"), 1);
  EXPECT_EQ(error_column("1.2.3"), 1);
  EXPECT_EQ(error_column("2t"), 2);
  EXPECT_EQ(error_column("a."), 2);
  EXPECT_GT(error_column(std::string(300, '(') + "1" + std::string(300, ')')), 0);
  try {
    Expression::parse("sinn(t)");
  } catch (const ExpressionError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'sin'"), std::string::npos) << e.what();
  }
}

std::string parse_error(const std::string& text) {
  try {
    Expression::parse(text);
  } catch (const ExpressionError& e) {
    return e.what();
  }
  return "";
}

std::string repeated(const std::string& s, int n) {
  std::string out;
  for (int k = 0; k < n; ++k) out += s;
  return out;
}

// The limits docs/fuzzing.md states: 200 levels of nesting (each a parenthesis, a function call,
// a unary sign or an exponent, not each rule of the grammar on the way) and 10 000 terms.
// Under AddressSanitizer (the debug-asan preset) a frame of the recursive parser is many times
// larger than in a release build: 200 levels overflowed the 8 MB main stack there (not in
// release). The limits are checked on a thread with a 256 MB stack in that build.
void with_large_stack(void (*body)()) {
#ifdef MO2D_SANITIZE
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, std::size_t{256} << 20);
  pthread_t thread;
  ASSERT_EQ(pthread_create(
                &thread, &attr,
                [](void* f) -> void* {
                  reinterpret_cast<void (*)()>(f)();
                  return nullptr;
                },
                reinterpret_cast<void*>(body)),
            0);
  pthread_join(thread, nullptr);
  pthread_attr_destroy(&attr);
#else
  body();
#endif
}

void nesting_and_size_limits() {
  EXPECT_DOUBLE_EQ(at(repeated("(", 200) + "t" + repeated(")", 200), 0.25).v, 0.25);
  EXPECT_DOUBLE_EQ(at(repeated("abs(", 200) + "t" + repeated(")", 200), -0.5).v, 0.5);
  EXPECT_DOUBLE_EQ(at(repeated("-", 200) + "t", 0.5).v, 0.5);
  EXPECT_DOUBLE_EQ(at(repeated("(1 + ", 200) + "t" + repeated(")", 200), 0).v, 200);
  const std::string deep = parse_error(repeated("(", 201) + "t" + repeated(")", 201));
  EXPECT_NE(deep.find("expression nested too deeply (more than 200 levels"), std::string::npos)
      << deep;
  EXPECT_NE(parse_error(repeated("-", 201) + "t").find("more than 200 levels"), std::string::npos);
  // 10 000 terms (9 999 additions): accepted and evaluated; one more is refused
  EXPECT_DOUBLE_EQ(at("1" + repeated(" + 1", 9999), 0).v, 10000);
  const std::string longer = parse_error("1" + repeated(" + 1", 10000));
  EXPECT_NE(longer.find("expression too long (more than 10000 terms"), std::string::npos) << longer;
}

TEST(Expression, NestingAndSizeLimitsAreTheDocumentedOnes) {
  with_large_stack(nesting_and_size_limits);
}

TEST(Expression, UnboundNameGivesColumnAndSuggestion) {
  Expression e = Expression::parse("2 * omgea * t");
  const std::vector<std::string> params = {"omega", "L"};
  try {
    e.bind(
        [](const std::string& n) {
          return n == "t" ? Binding{Binding::Kind::time, 0, -1} : Binding{};
        },
        params);
    FAIL() << "expected an error";
  } catch (const ExpressionError& err) {
    EXPECT_EQ(err.column(), 5);
    EXPECT_NE(std::string(err.what()).find("did you mean 'omega'"), std::string::npos);
  }
}

TEST(Expression, EditDistance) {
  EXPECT_EQ(edit_distance("mass", "masss"), 1u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
}

}  // namespace
}  // namespace mo2d
