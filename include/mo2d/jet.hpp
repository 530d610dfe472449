#pragma once
// Jet: a value with its first and second derivative along one direction (truncated Taylor series
// of order 2). Evaluating f(Jet{t, 1, 0}) gives f(t), f'(t), f''(t) exactly; evaluating
// f(x + s v, t + s) gives the directional derivatives used for Jacobians and acceleration biases.
#include <cmath>

namespace mo2d {

// A value with its first and second derivative along one direction (see the file's description); in
// the unit of what it carries, per unit of the direction's parameter.
struct Jet {
  double v = 0;   // value
  double d = 0;   // first derivative
  double dd = 0;  // second derivative
  constexpr Jet() = default;
  constexpr Jet(double value) : v(value) {}  // NOLINT: implicit on purpose (constants)
  // A Jet with its value and first and second derivatives.
  constexpr Jet(double value, double d1, double d2) : v(value), d(d1), dd(d2) {}
  // The independent variable at `value`: derivative 1, second derivative 0.
  static constexpr Jet variable(double value) { return {value, 1.0, 0.0}; }
};

// Sum (value and derivatives add).
inline Jet operator+(Jet a, Jet b) {
  return {a.v + b.v, a.d + b.d, a.dd + b.dd};
}
// Difference.
inline Jet operator-(Jet a, Jet b) {
  return {a.v - b.v, a.d - b.d, a.dd - b.dd};
}
// Negation.
inline Jet operator-(Jet a) {
  return {-a.v, -a.d, -a.dd};
}
// Product (Leibniz rule: (ab)'' = a'' b + 2 a' b' + a b'').
inline Jet operator*(Jet a, Jet b) {
  return {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + 2 * a.d * b.d + a.v * b.dd};
}
// Chain rule for a scalar function with value f0, derivative f1, second derivative f2 at a.v.
inline Jet chain(Jet a, double f0, double f1, double f2) {
  return {f0, f1 * a.d, f2 * a.d * a.d + f1 * a.dd};
}
// Quotient a * (1/b), 1/b by the chain rule.
inline Jet operator/(Jet a, Jet b) {
  const double inv = 1.0 / b.v;
  return a * chain(b, inv, -inv * inv, 2 * inv * inv * inv);
}
// a = a + b.
inline Jet& operator+=(Jet& a, Jet b) {
  return a = a + b;
}
// a = a - b.
inline Jet& operator-=(Jet& a, Jet b) {
  return a = a - b;
}
// a = a * b.
inline Jet& operator*=(Jet& a, Jet b) {
  return a = a * b;
}
// a = a / b.
inline Jet& operator/=(Jet& a, Jet b) {
  return a = a / b;
}

// sin, by the chain rule (a in rad).
inline Jet sin(Jet a) {
  const double s = std::sin(a.v), c = std::cos(a.v);
  return chain(a, s, c, -s);
}
// cos, by the chain rule (a in rad).
inline Jet cos(Jet a) {
  const double s = std::sin(a.v), c = std::cos(a.v);
  return chain(a, c, -s, -c);
}
// tan, by the chain rule (a in rad).
inline Jet tan(Jet a) {
  const double t = std::tan(a.v), s2 = 1 + t * t;
  return chain(a, t, s2, 2 * t * s2);
}
// exp, by the chain rule.
inline Jet exp(Jet a) {
  const double e = std::exp(a.v);
  return chain(a, e, e, e);
}
// Natural logarithm, by the chain rule.
inline Jet log(Jet a) {
  return chain(a, std::log(a.v), 1 / a.v, -1 / (a.v * a.v));
}
// Square root, by the chain rule.
inline Jet sqrt(Jet a) {
  const double r = std::sqrt(a.v);
  return chain(a, r, 0.5 / r, -0.25 / (r * a.v));
}
// a to a constant power p, by the chain rule.
inline Jet pow(Jet a, double p) {
  const double f0 = std::pow(a.v, p);
  const double f1 = p * std::pow(a.v, p - 1);
  const double f2 = p * (p - 1) * std::pow(a.v, p - 2);
  return chain(a, f0, f1, f2);
}
// a to the power b, exp(b log a) (a > 0).
inline Jet pow(Jet a, Jet b) {
  return exp(b * log(a));
}
// |a|: the derivatives of the branch taken (not differentiable at 0).
inline Jet abs(Jet a) {
  return a.v < 0 ? -a : a;
}
// The angle of (x, y) in (-pi, pi] (rad), with its derivatives.
inline Jet atan2(Jet y, Jet x) {
  // d atan2 = (x dy - y dx) / r2, computed through the quotient rule on components.
  const Jet r2 = x * x + y * y;
  const Jet num = Jet{0, x.v * y.d - y.v * x.d, x.v * y.dd - y.v * x.dd};
  const double v = std::atan2(y.v, x.v);
  const double d = num.d / r2.v;
  // second derivative: d/ds [(x y' - y x')/r2] = (x y'' - y x'')/r2 - (x y' - y x') r2'/r2^2
  const double dd = num.dd / r2.v - num.d * r2.d / (r2.v * r2.v);
  return {v, d, dd};
}
// The smaller of a and b (by value), with its derivatives.
inline Jet min(Jet a, Jet b) {
  return a.v <= b.v ? a : b;
}
// The larger of a and b (by value), with its derivatives.
inline Jet max(Jet a, Jet b) {
  return a.v >= b.v ? a : b;
}

// Piecewise-constant functions: derivatives 0 (between the jumps; there they do not exist).
inline Jet floor(Jet a) {
  return Jet(std::floor(a.v));
}
// The smallest integer >= a (derivatives 0).
inline Jet ceil(Jet a) {
  return Jet(std::ceil(a.v));
}
inline Jet round(Jet a) {  // half away from zero (std::round)
  return Jet(std::round(a.v));
}
inline Jet sign(Jet a) {  // -1, 0 or 1; NaN stays NaN
  return Jet(a.v > 0 ? 1.0 : a.v < 0 ? -1.0 : a.v == 0 ? 0.0 : a.v);
}
// Floored modulo x - y floor(x/y), like Python's %: the result has the sign of y (in [0, y) for
// y > 0). The value comes from std::fmod (exact); between the jumps k = floor(x/y) is constant,
// so the derivatives are x' - k y' and x'' - k y''. mod(x, 0) is NaN.
inline Jet mod(Jet x, Jet y) {
  double r = std::fmod(x.v, y.v);
  if (r != 0 && ((r < 0) != (y.v < 0))) r += y.v;
  if (r == y.v) r = 0;  // r + y rounded to y (x a tiny negative multiple of y): stay in [0, y)
  const double k = std::round((x.v - r) / y.v);
  return {r, x.d - k * y.d, x.dd - k * y.dd};
}
// min(max(x, lo), hi): the derivatives of the selected branch.
inline Jet clamp(Jet x, Jet lo, Jet hi) {
  return min(max(x, lo), hi);
}
// sqrt(x^2 + y^2) without overflow. At the origin (not differentiable) the one-sided derivatives
// along the direction: |(x', y')| and (x' x'' + y' y'') / |(x', y')|, or |(x'', y'')| when the
// first derivatives vanish.
inline Jet hypot(Jet x, Jet y) {
  const double h = std::hypot(x.v, y.v);
  if (h == 0) {
    const double n = std::hypot(x.d, y.d);
    return {0, n, n == 0 ? std::hypot(x.dd, y.dd) : (x.d * x.dd + y.d * y.dd) / n};
  }
  // h h' = x x' + y y'; differentiated: h'^2 + h h'' = x'^2 + y'^2 + x x'' + y y''
  const double d = (x.v * x.d + y.v * y.d) / h;
  const double dd = (x.d * x.d + y.d * y.d + x.v * x.dd + y.v * y.dd - d * d) / h;
  return {h, d, dd};
}

}  // namespace mo2d
