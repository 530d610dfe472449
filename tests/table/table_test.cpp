// Tables (mo2d/table.hpp): the not-a-knot spline reproduces cubics and passes through the data,
// is C² at the knots, converges at fourth order, its Jet derivatives agree with finite
// differences; the periodic spline is C² across the wrap; out-of-range and bad data are errors;
// CSV files are read by column name with errors at file:line.
#include "mo2d/table.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

namespace mo2d {
namespace {

using std::numbers::pi;

// p(x) = 1 - 2x + 0.5x^2 + 0.3x^3 on unevenly spaced knots
double p(double x) {
  return 1 - 2 * x + 0.5 * x * x + 0.3 * x * x * x;
}
double p1(double x) {
  return -2 + x + 0.9 * x * x;
}
double p2(double x) {
  return 1 + 1.8 * x;
}
const std::vector<double> kKnots = {-1, -0.4, 0.3, 0.7, 1.2, 2.0, 2.1, 3};

LookupTable sampled(double (*f)(double), const std::vector<double>& x, TableOptions o = {}) {
  std::vector<double> y;
  for (double v : x) y.push_back(f(v));
  return LookupTable("f", x, y, o);
}

std::vector<double> grid(double a, double b, int n) {
  std::vector<double> x;
  for (int i = 0; i <= n; ++i) x.push_back(a + (b - a) * i / n);
  return x;
}

// An irregular, non-polynomial data set.
double wiggle(double x) {
  return std::sin(3 * x) + 0.2 * x * x - std::exp(-x);
}

TEST(LookupTable, NotAKnotReproducesACubic) {
  const LookupTable t = sampled(p, kKnots);
  for (double x : grid(-1, 3, 97)) {
    // along a direction: x(s) with x' = 2, x'' = -0.5 (chain rule)
    const Jet j = t(Jet(x, 2, -0.5));
    EXPECT_NEAR(j.v, p(x), 1e-13) << x;
    EXPECT_NEAR(j.d, 2 * p1(x), 1e-12) << x;
    EXPECT_NEAR(j.dd, 4 * p2(x) - 0.5 * p1(x), 1e-11) << x;
  }
}

TEST(LookupTable, TwoAndThreePointsGiveTheLineAndTheParabola) {
  const LookupTable line("l", {1, 3}, {2, 6});
  EXPECT_NEAR(line(2.5), 5, 1e-15);
  EXPECT_NEAR(line(Jet::variable(2.5)).d, 2, 1e-15);
  const LookupTable parabola = sampled([](double x) { return 3 * x * x - x + 1; }, {0, 0.5, 2});
  for (double x : grid(0, 2, 8)) {
    const Jet j = parabola(Jet::variable(x));
    EXPECT_NEAR(j.v, 3 * x * x - x + 1, 1e-13);
    EXPECT_NEAR(j.d, 6 * x - 1, 1e-13);
    EXPECT_NEAR(j.dd, 6, 1e-13);
  }
}

TEST(LookupTable, PassesThroughTheDataAndIsC2AtTheKnots) {
  for (auto options : {TableOptions{}, TableOptions{Interpolation::linear, Extrapolation::error}}) {
    const bool cubic = options.interpolation == Interpolation::cubic;
    const LookupTable t = sampled(wiggle, kKnots, options);
    for (size_t i = 0; i < kKnots.size(); ++i) {
      const double x = kKnots[i];
      EXPECT_NEAR(t(x), wiggle(x), 1e-14) << i;
      if (i == 0 || i + 1 == kKnots.size()) continue;
      // left limit: the previous piece at its right end
      const Jet left = t(Jet::variable(std::nextafter(x, -INFINITY)));
      const Jet right = t(Jet::variable(x));
      EXPECT_NEAR(left.v, right.v, 1e-14) << i;
      if (!cubic) continue;
      EXPECT_NEAR(left.d, right.d, 1e-13) << i;
      EXPECT_NEAR(left.dd, right.dd, 1e-12) << i;
    }
  }
}

TEST(LookupTable, JetDerivativesMatchFiniteDifferences) {
  const LookupTable t = sampled(wiggle, kKnots);
  const double h = 1e-5;
  for (double x : {-0.9, -0.1, 0.5, 1.0, 1.9, 2.05, 2.6}) {
    const Jet j = t(Jet::variable(x));
    EXPECT_NEAR(j.d, (t(x + h) - t(x - h)) / (2 * h), 1e-8) << x;
    EXPECT_NEAR(j.dd, (t(Jet::variable(x + h)).d - t(Jet::variable(x - h)).d) / (2 * h), 1e-7) << x;
  }
}

// Error of the spline of f on n intervals against f, f', f'' on a fine grid.
double spline_error(double (*f)(double), double (*f2)(double), int n, TableOptions o) {
  const double b = o.extrapolation == Extrapolation::periodic ? 2 * pi : 2.0;
  const LookupTable t = sampled(f, grid(0, b, n), o);
  double e = 0;
  for (double x : grid(0, b, 1000)) e = std::max(e, std::abs(t(Jet::variable(x)).dd - f2(x)));
  return e;
}

TEST(LookupTable, ConvergesAtTheSplinesOrder) {
  // second derivative error O(h^2) for both end conditions: a wrong end row loses an order
  auto e = [](double x) { return std::exp(x); };
  auto s = [](double x) { return std::sin(x) + 0.3 * std::cos(2 * x); };
  auto s2 = [](double x) { return -std::sin(x) - 1.2 * std::cos(2 * x); };
  const TableOptions periodic{Interpolation::cubic, Extrapolation::periodic};
  for (int n : {16, 32}) {
    const double ratio_e = spline_error(e, e, n, {}) / spline_error(e, e, 2 * n, {});
    const double ratio_s = spline_error(s, s2, n, periodic) / spline_error(s, s2, 2 * n, periodic);
    EXPECT_GT(ratio_e, 3.5) << n;
    EXPECT_LT(ratio_e, 4.5) << n;
    EXPECT_GT(ratio_s, 3.5) << n;
    EXPECT_LT(ratio_s, 4.5) << n;
  }
  // and the values at fourth order
  const LookupTable t16 = sampled(e, grid(0, 2, 16)), t32 = sampled(e, grid(0, 2, 32));
  double e16 = 0, e32 = 0;
  for (double x : grid(0, 2, 1000)) {
    e16 = std::max(e16, std::abs(t16(x) - std::exp(x)));
    e32 = std::max(e32, std::abs(t32(x) - std::exp(x)));
  }
  EXPECT_GT(e16 / e32, 12);
  EXPECT_LT(e16 / e32, 20);
}

TEST(LookupTable, PeriodicIsC2AcrossTheWrap) {
  auto f = [](double x) { return std::sin(x) + 0.3 * std::cos(2 * x) + 0.1 * std::sin(5 * x); };
  std::vector<double> x = {0, 0.4, 1.1, 1.5, 2.6, 3.0, 4.1, 5.0, 5.5, 2 * pi};
  const LookupTable t = sampled(f, x, TableOptions{Interpolation::cubic, Extrapolation::periodic});
  const Jet start = t(Jet::variable(0.0));
  const Jet end = t(Jet::variable(std::nextafter(2 * pi, 0.0)));
  EXPECT_NEAR(start.v, end.v, 1e-14);
  EXPECT_NEAR(start.d, end.d, 1e-13);
  EXPECT_NEAR(start.dd, end.dd, 1e-12);
  EXPECT_GT(std::abs(start.dd), 0.1);  // a real check: the curvature is not zero there
  // repeated with the period, in both directions, derivatives included
  for (double u : {0.3, 1.7, 4.4, 6.1}) {
    for (int k : {-3, -1, 1, 2, 10}) {
      const Jet a = t(Jet(u, 1.5, 0.2)), b = t(Jet(u + k * 2 * pi, 1.5, 0.2));
      EXPECT_NEAR(a.v, b.v, 1e-13);
      EXPECT_NEAR(a.d, b.d, 1e-12);
      EXPECT_NEAR(a.dd, b.dd, 1e-11);
    }
  }
  // a periodic table must end where it starts
  EXPECT_THROW(
      LookupTable("p", {0, 1, 2}, {0, 1, 0.5}, {Interpolation::cubic, Extrapolation::periodic}),
      Error);
}

TEST(LookupTable, OutOfRange) {
  const LookupTable t("cam", {0, 1, 2, 3}, {0, 1, 4, 2});
  try {
    t(3.5);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "table 'cam': x = 3.5 is outside the table's range [0, 3] (extrapolation error; "
              "clamp or periodic evaluate beyond the ends)");
    EXPECT_EQ(e.element(), "cam");
  }
  EXPECT_THROW(t(-1e-6), Error);
  EXPECT_THROW(t(NAN), Error);
  EXPECT_NEAR(t(3 + 1e-15), 2, 1e-13);  // round-off beyond the end: the end piece
  const LookupTable c("cam", {0, 1, 2, 3}, {0, 1, 4, 2},
                      {Interpolation::cubic, Extrapolation::clamp});
  const Jet below = c(Jet(-2, 1, 1)), above = c(Jet(7, 1, 1));
  EXPECT_EQ(below.v, 0);
  EXPECT_EQ(above.v, 2);
  EXPECT_EQ(below.d, 0);
  EXPECT_EQ(above.dd, 0);
}

std::string error_of(auto f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(LookupTable, BadPoints) {
  EXPECT_EQ(error_of([] { LookupTable("a", {1}, {2}); }),
            "table 'a': at least 2 points are needed, got 1");
  EXPECT_EQ(error_of([] {
              LookupTable("a", {0, 1, 1}, {2, 3, 4});
            }),
            "table 'a': x must increase: x = 1 at point 2 after x = 1");
  EXPECT_EQ(error_of([] {
              LookupTable("a", {0, 1, 2}, {2, NAN, 4});
            }),
            "table 'a': point 1 (1, nan) is not finite");
  EXPECT_EQ(error_of([] {
              LookupTable("a", {0, 1}, {2, 3, 4});
            }),
            "table 'a': 2 x values but 3 y values");
}

class CsvTable : public ::testing::Test {
 protected:
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mo2d_table_test_" + std::to_string(::getpid()));
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir / name).string();
    std::ofstream(path) << text;
    return path;
  }
  std::string error(const std::string& text, const CsvColumns& c = {}, TableOptions o = {}) {
    const std::string path = write("t.csv", text);
    const std::string e = error_of([&] { read_table_csv(path, "cam", c, o); });
    return e.starts_with(path) ? "t.csv" + e.substr(path.size()) : e;
  }
};

TEST_F(CsvTable, ColumnsByNameScalesAndComments) {
  const std::string path = write("lift.csv",
                                 "# cam lift\n"
                                 "time, angle_deg , \"lift\"\n"
                                 "0, 0, 0\n"
                                 "\n"
                                 "1, 90, 2.5\r\n"
                                 "2, 180, 4\n"
                                 "3, 270, 1.5\n"
                                 "4, 360, 0\n");
  const LookupTable t = read_table_csv(
      path, "lift", {.x = "angle_deg", .y = "lift", .scale_x = pi / 180, .scale_y = 1e-3},
      {Interpolation::cubic, Extrapolation::periodic});
  EXPECT_EQ(t.x().size(), 5u);
  EXPECT_NEAR(t.x_max(), 2 * pi, 1e-15);
  EXPECT_NEAR(t(pi / 2), 2.5e-3, 1e-18);
  EXPECT_NEAR(t(2 * pi + pi), 4e-3, 1e-17);
  // default columns: the first two
  const LookupTable d = read_table_csv(path, "d");
  EXPECT_EQ(d.x_max(), 4);
  EXPECT_EQ(d(2.0), 180);
}

TEST_F(CsvTable, ErrorsGiveFileAndLine) {
  EXPECT_EQ(error("a,b\n0,1\n1,x2\n"), "t.csv:3: table 'cam': column 'b': 'x2' is not a number");
  EXPECT_EQ(error("a,b\n0,1\n1,\n"), "t.csv:3: table 'cam': column 'b' is empty");
  EXPECT_EQ(error("a,b\n0,1\n1,inf\n"), "t.csv:3: table 'cam': column 'b': inf is not finite");
  EXPECT_EQ(error("a,b\n0,1\n2,1\n# c\n2,3\n"),
            "t.csv:5: table 'cam': x must increase: a = 2 after 2 on line 3");
  EXPECT_EQ(error("a,b,c\n0,1,2\n1,2\n", {.x = "a", .y = "c"}),
            "t.csv:3: table 'cam': the row has 2 value(s), the column 'c' is number 3");
  EXPECT_EQ(error("angle,lift\n0,1\n1,2\n", {.x = "angel"}),
            "t.csv:1: table 'cam': no column 'angel' (did you mean 'angle'?); the header has "
            "'angle', 'lift'");
  // a value finite as written but not once scaled: at its own line, not at the last one
  EXPECT_EQ(error("a,b\n0,1\n1,1e10\n2,3\n", {.scale_y = 1e300}),
            "t.csv:3: table 'cam': column 'b': 1e10 times scale_y = 1e+300 is out of range (inf)");
  EXPECT_EQ(error("a,b\n0,1\n-1e10,2\n2,3\n", {.scale_x = 1e300}),
            "t.csv:3: table 'cam': column 'a': -1e10 times scale_x = 1e+300 is out of range "
            "(-inf)");
  EXPECT_EQ(error("a,b\n0,1\n"), "t.csv:2: table 'cam': at least 2 points are needed, got 1");
  EXPECT_EQ(error("0,1\n1,2\n"),
            "t.csv:1: table 'cam': the first row holds numbers: a header row of column names is "
            "expected before the data (e.g. 'angle, lift')");
  EXPECT_EQ(error("# only a comment\n"),
            "t.csv: table 'cam': the file is empty (a header row of column names is expected)");
  EXPECT_EQ(error("a,b\n0,1\n1,2\n2,1.5\n", {}, {Interpolation::cubic, Extrapolation::periodic}),
            "t.csv:4: table 'cam': a periodic table ends where it starts, one period later: y = "
            "1.5 at x = 2 but y = 1 at x = 0");
  EXPECT_EQ(error_of([&] { read_table_csv((dir / "none.csv").string(), "cam"); }),
            (dir / "none.csv").string() + ": table 'cam': cannot open the file");
}

}  // namespace
}  // namespace mo2d
