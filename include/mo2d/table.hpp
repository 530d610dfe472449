#pragma once
// Tables: y(x) given at points (a cam lift against the cam angle, a gas pressure against the crank
// angle, a motion against time), interpolated by a cubic spline or linearly and evaluated on a
// Jet: the first and second derivatives returned are those of the interpolant, exactly (chain
// rule on the piece's polynomial), so a table can drive a motion, a load or a constraint.
//
// Cubic: the C² interpolating spline (value, slope and curvature continuous at every knot),
// with not-a-knot end conditions (the third derivative is also continuous at the second and the
// second-to-last knot): it reproduces any cubic polynomial exactly and puts no artificial
// S'' = 0 at the ends (a natural spline would, wrong for a motion that accelerates there).
// Three points give the parabola through them, two the straight line.
// Periodic (extrapolation periodic): the data cover one period, the last point is the first one a
// period later (same y), the spline is C² across the wrap, x is wrapped into [x0, x0 + period).
// Linear: a polyline; its slope jumps at the knots (second derivative 0 on each piece).
#include <span>
#include <string>
#include <vector>

#include "mo2d/error.hpp"
#include "mo2d/jet.hpp"

namespace mo2d {

// How a table interpolates between its points (see the file's description).
enum class Interpolation { cubic, linear };

// Beyond the ends: an Error naming the table, x and the range (error); the end value with zero
// derivatives (clamp); the data repeated with period x_max - x_min (periodic).
enum class Extrapolation { error, clamp, periodic };

// How a LookupTable interpolates and extrapolates.
struct TableOptions {
  // cubic spline (default) or polyline
  Interpolation interpolation = Interpolation::cubic;
  // what happens beyond the first and last x
  Extrapolation extrapolation = Extrapolation::error;
};

// A table y(x) interpolated between its points and evaluated on a Jet (exact derivatives of the
// interpolant); x and y in the units of what it tabulates.
class LookupTable {
 public:
  // At least 2 points, x strictly increasing, every value finite; periodic: y.back() == y.front()
  // to 1e-9 of the largest |y| (the first value is used for both). Throws Error naming the
  // table and the offending point (0-based index).
  LookupTable(std::string name, std::vector<double> x, std::vector<double> y,
              TableOptions options = {});

  // The interpolant at x.v with its first and second derivative along x's direction:
  // {S(x), S'(x) x', S''(x) x'^2 + S'(x) x''}. x beyond the range by more than round-off
  // (1e-12 of the range's scale) with extrapolation error, or a non-finite x, throws Error.
  Jet operator()(Jet x) const;
  // The interpolated value at x.
  double operator()(double x) const { return (*this)(Jet(x)).v; }

  // The table's name (in its error messages).
  const std::string& name() const { return name_; }
  // The points' x values (increasing) and y values.
  std::span<const double> x() const { return x_; }
  std::span<const double> y() const { return y_; }
  // The range of x covered by the points.
  double x_min() const { return x_.front(); }
  double x_max() const { return x_.back(); }
  // The interpolation and extrapolation.
  const TableOptions& options() const { return options_; }

 private:
  struct Piece {  // y = a + b s + c s^2 + d s^3, s = x - x_i on [x_i, x_i+1]
    double a = 0, b = 0, c = 0, d = 0;
  };
  void fit();
  double wrap(double x) const;
  std::string name_{};
  std::vector<double> x_{}, y_{};
  TableOptions options_{};
  std::vector<Piece> pieces_{};
};

// Columns of a CSV file for read_table_csv: header names (empty: the first, the second column),
// and factors applied to the values read (x_table = scale_x * x_file; scale_x > 0).
struct CsvColumns {
  // header name of the x column
  std::string x{};
  // header name of the y column
  std::string y{};
  // factors applied to the x and y values read
  double scale_x = 1, scale_y = 1;
};

// A table from a CSV file: a header row of column names, then one row of numbers per point,
// separated by commas (spaces around a value ignored; blank lines and lines starting with '#'
// skipped). Errors name the file and line ("cam.csv:7: ..."): a missing or unknown column (with a
// "did you mean"), a cell that is not a finite number, a short row, x not increasing, fewer than
// 2 points.
LookupTable read_table_csv(const std::string& path, std::string name,
                           const CsvColumns& columns = {}, TableOptions options = {});

}  // namespace mo2d
