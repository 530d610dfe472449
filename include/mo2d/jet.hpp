#pragma once
// Jet: a value with its first and second derivative along one direction (truncated Taylor series
// of order 2). Evaluating f(Jet{t, 1, 0}) gives f(t), f'(t), f''(t) exactly; evaluating
// f(x + s v, t + s) gives the directional derivatives used for Jacobians and acceleration biases.
#include <cmath>

namespace mo2d {

struct Jet {
  double v = 0;   // value
  double d = 0;   // first derivative
  double dd = 0;  // second derivative
  constexpr Jet() = default;
  constexpr Jet(double value) : v(value) {}  // NOLINT: implicit on purpose (constants)
  constexpr Jet(double value, double d1, double d2) : v(value), d(d1), dd(d2) {}
  static constexpr Jet variable(double value) { return {value, 1.0, 0.0}; }
};

inline Jet operator+(Jet a, Jet b) {
  return {a.v + b.v, a.d + b.d, a.dd + b.dd};
}
inline Jet operator-(Jet a, Jet b) {
  return {a.v - b.v, a.d - b.d, a.dd - b.dd};
}
inline Jet operator-(Jet a) {
  return {-a.v, -a.d, -a.dd};
}
inline Jet operator*(Jet a, Jet b) {
  return {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + 2 * a.d * b.d + a.v * b.dd};
}
// Chain rule for a scalar function with value f0, derivative f1, second derivative f2 at a.v.
inline Jet chain(Jet a, double f0, double f1, double f2) {
  return {f0, f1 * a.d, f2 * a.d * a.d + f1 * a.dd};
}
inline Jet operator/(Jet a, Jet b) {
  const double inv = 1.0 / b.v;
  return a * chain(b, inv, -inv * inv, 2 * inv * inv * inv);
}
inline Jet& operator+=(Jet& a, Jet b) {
  return a = a + b;
}
inline Jet& operator-=(Jet& a, Jet b) {
  return a = a - b;
}
inline Jet& operator*=(Jet& a, Jet b) {
  return a = a * b;
}
inline Jet& operator/=(Jet& a, Jet b) {
  return a = a / b;
}

inline Jet sin(Jet a) {
  const double s = std::sin(a.v), c = std::cos(a.v);
  return chain(a, s, c, -s);
}
inline Jet cos(Jet a) {
  const double s = std::sin(a.v), c = std::cos(a.v);
  return chain(a, c, -s, -c);
}
inline Jet tan(Jet a) {
  const double t = std::tan(a.v), s2 = 1 + t * t;
  return chain(a, t, s2, 2 * t * s2);
}
inline Jet exp(Jet a) {
  const double e = std::exp(a.v);
  return chain(a, e, e, e);
}
inline Jet log(Jet a) {
  return chain(a, std::log(a.v), 1 / a.v, -1 / (a.v * a.v));
}
inline Jet sqrt(Jet a) {
  const double r = std::sqrt(a.v);
  return chain(a, r, 0.5 / r, -0.25 / (r * a.v));
}
inline Jet pow(Jet a, double p) {
  const double f0 = std::pow(a.v, p);
  const double f1 = p * std::pow(a.v, p - 1);
  const double f2 = p * (p - 1) * std::pow(a.v, p - 2);
  return chain(a, f0, f1, f2);
}
inline Jet pow(Jet a, Jet b) {
  return exp(b * log(a));
}
inline Jet abs(Jet a) {
  return a.v < 0 ? -a : a;
}
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
inline Jet min(Jet a, Jet b) {
  return a.v <= b.v ? a : b;
}
inline Jet max(Jet a, Jet b) {
  return a.v >= b.v ? a : b;
}

}  // namespace mo2d
