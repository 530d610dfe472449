#pragma once
// Assertions shared by the error tests (tests/model/build_model_errors_test.cpp,
// tests/kinematics/assembly_errors_test.cpp, tests/inverse/inverse_errors_test.cpp): bad input must
// give a clear mo2d::Error naming the offending element (and the time, for a run), and the small
// mechanisms those tests break one thing of.
//
// Set MO2D_SHOW_ERRORS=1 to print every caught message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <limits>
#include <string>
#include <typeinfo>
#include <vector>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

namespace mo2d::test {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline std::string describe_error(const Error& e) {
  return std::string("\"") + e.what() + "\" (element '" + e.element() + "', time " +
         std::to_string(e.time()) + ")";
}

// Passes if f throws mo2d::Error whose what() contains every string of `parts`; the caught
// Error is copied to *out. Any other outcome (no exception, another exception type) fails.
inline ::testing::AssertionResult ThrowsError(const std::function<void()>& f,
                                              const std::vector<std::string>& parts,
                                              Error* out = nullptr) {
  try {
    f();
  } catch (const Error& e) {
    if (out) *out = e;
    if (std::getenv("MO2D_SHOW_ERRORS"))
      std::cout << "  [mo2d::Error] " << describe_error(e) << "\n";
    const std::string what = e.what();
    for (const auto& p : parts)
      if (what.find(p) == std::string::npos)
        return ::testing::AssertionFailure()
               << "the mo2d::Error message lacks \"" << p << "\": " << describe_error(e);
    return ::testing::AssertionSuccess() << describe_error(e);
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure()
           << "threw " << typeid(e).name() << ", not mo2d::Error: " << e.what();
  } catch (...) {
    return ::testing::AssertionFailure() << "threw something that is not a std::exception";
  }
  return ::testing::AssertionFailure() << "no exception was thrown";
}

inline bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// what() names element() (the element a caller would highlight is spelled in the message).
inline ::testing::AssertionResult NamesItsElement(const Error& e) {
  if (e.element().empty())
    return ::testing::AssertionFailure() << "element() is empty: " << describe_error(e);
  if (!contains(e.what(), e.element()))
    return ::testing::AssertionFailure()
           << "what() does not contain element() '" << e.element() << "': " << describe_error(e);
  return ::testing::AssertionSuccess();
}

// what() contains at least one of the names.
inline ::testing::AssertionResult NamesOneOf(const Error& e,
                                             const std::vector<std::string>& names) {
  for (const auto& n : names)
    if (contains(e.what(), n)) return ::testing::AssertionSuccess();
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  return ::testing::AssertionFailure()
         << "the message names none of {" << list << "}: " << describe_error(e);
}

inline std::function<void()> building(const System& s, BuildOptions o = {}) {
  return [s, o] { (void)build_model(s, o); };
}

inline std::function<void()> running(const System& s, std::vector<Prescribed> motion,
                                     InverseOptions run = {}, BuildOptions build = {}) {
  return [s, motion, run, build] {
    const Model m = build_model(s, build);
    (void)inverse_dynamics(m, motion, run);
  };
}

inline Prescribed constant(std::string label, double value) {
  return {std::move(label), [value](Jet) { return Jet(value); }};
}

// A valid crank O-A hinged to the ground at O: the base most tests break one thing of.
inline System crank_only() {
  System s("crank_only");
  s.add_ground_node("O", {0, 0});
  s.add_body(
      {.name = "crank", .nodes = {{"O", {0, 0}}, {"A", {0.1, 0}}}, .mass = 1, .inertia = 0.01});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "crank.O", .actuated = true});
  return s;
}

// Crank-rocker four-bar of mechanisms::fourbar() (ground 0.4, crank 0.1, coupler 0.35, rocker
// 0.3; crank vertical at t = 0), with the angles of crank and rocker as coordinates and a choice
// of actuated pivots.
struct FourBarGeometry {
  Vec2 A0{0, 0}, B0{0.4, 0}, A{0, 0.1}, B{0, 0};
  double rocker_angle = 0;
  FourBarGeometry() {
    const double b = 0.35, c = 0.3;
    const Vec2 AB0 = B0 - A;
    const double l = AB0.norm();
    const double x = (b * b - c * c + l * l) / (2 * l);
    const Vec2 ex = AB0 / l, ey(-ex.y(), ex.x());
    B = A + x * ex + std::sqrt(b * b - x * x) * ey;
    rocker_angle = std::atan2(B.y() - B0.y(), B.x() - B0.x());
  }
};

inline System fourbar_system(bool crank_actuated, bool rocker_actuated) {
  const FourBarGeometry g;
  System s("fourbar");
  s.add_ground_node("A0", g.A0).add_ground_node("B0", g.B0);
  s.add_body({.name = "crank", .nodes = {{"O", g.A0}, {"A", g.A}}, .mass = 0.2, .inertia = 2e-4});
  s.add_body({.name = "coupler", .nodes = {{"A", g.A}, {"B", g.B}}, .mass = 0.5, .inertia = 5e-3});
  s.add_body({.name = "rocker", .nodes = {{"O", g.B0}, {"B", g.B}}, .mass = 0.4, .inertia = 3e-3});
  s.add_revolute({.name = "crank_pivot",
                  .node_a = "ground.A0",
                  .node_b = "crank.O",
                  .actuated = crank_actuated});
  s.add_revolute({.name = "crank_pin", .node_a = "crank.A", .node_b = "coupler.A"});
  s.add_revolute({.name = "rocker_pin", .node_a = "coupler.B", .node_b = "rocker.B"});
  s.add_revolute({.name = "rocker_pivot",
                  .node_a = "ground.B0",
                  .node_b = "rocker.O",
                  .actuated = rocker_actuated});
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}});
  s.add_coordinate({.name = "rocker.angle", .rate = {{"rocker.w", 1.0}}});
  s.set_gravity({0, -9.81});
  return s;
}

// The slider-crank of mechanisms::slider_crank() with its default parameters.
inline const mechanisms::SliderCrankParams kSC{};

}  // namespace mo2d::test
