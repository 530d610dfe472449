#pragma once
// Law: a load value (a force component, a torque, a spring tension, an input effort) as a
// function of time and of named quantities of the state, Orsino's active forces f_A(t, q0, q1)
// of eq. 4.13. The quantities are named by labels that build_model resolves:
//  - every coordinate and quasi-velocity label `mo2d info` prints ("crank.A.x", "slide.q",
//    "crank.angle", "crank.w", "slide.v"), including the aliases of merged nodes and nodes
//    joined to the ground (whose coordinates are constants and rates zero);
//  - derived quantities: "B.theta" (direction of the line from body B's first to its second node,
//    rad, in (-pi, pi]), "B.com.x|y|vx|vy" (centre of mass), "J.angle" and "J.rate" (revolute
//    joint J: rotation of its body 2 relative to its body 1 since the initial configuration, in
//    (-pi, pi], and its rate), "S.length", "S.extension" and "S.rate" (spring S), and
//    "P.x|y|vx|vy" for every named point P (System::add_point);
//  - inside a spring's tension law also "length", "extension", "rate" (that spring's own), inside a
//    torsional spring's torque law "angle" and "rate" (that joint's, relative to the rest angle).
// Labels are local to the System that owns the load (a load in instance "leg" reading
// "thigh.theta" reads "leg.thigh.theta"); the values are in the world frame, SI units.
// A coordinate or quasi-velocity label wins over a derived quantity of the same name.
#include <concepts>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "mo2d/jet.hpp"

namespace mo2d {

// A function of time t (s), in the unit of the quantity it gives.
using Signal = std::function<double(double t)>;

// A load, effort or spring law: a function f(x, t) of some quantities x of the state (named by
// args, e.g. "crank.angle", "crank.w") and of the time t (s), in the unit of what it drives (N, N
// m).
struct Law {
  // Labels of the quantities f reads, in the order of its argument x.
  std::vector<std::string> args{};
  // The value from the quantities and the time. Jet arguments: the value, and derivatives along a
  // direction where a caller asks for them (a law written with Jet arithmetic gives exact ones).
  std::function<Jet(std::span<const Jet> x, Jet t)> f{};

  Law() = default;
  // A law of the quantities `labels` given by fn(x, t).
  Law(std::vector<std::string> labels, std::function<Jet(std::span<const Jet>, Jet)> fn)
      : args(std::move(labels)), f(std::move(fn)) {}
  // A function of time only (the loads of earlier versions: any double(double) callable).
  template <class F>
  requires std::is_invocable_r_v<double, F, double> &&(!std::same_as<std::decay_t<F>, Law>)
      Law(F fn)  // NOLINT(google-explicit-constructor): a time function is a law
      : Law(Signal(std::move(fn))) {}
  Law(Signal fn);  // NOLINT(google-explicit-constructor)
  // The law of constant value `value`.
  static Law constant(double value);

  // Whether the law is set (an empty law: zero).
  explicit operator bool() const { return static_cast<bool>(f); }
  // Whether it reads the state (a feedback law), not only the time.
  bool depends_on_state() const { return !args.empty(); }
};

}  // namespace mo2d
