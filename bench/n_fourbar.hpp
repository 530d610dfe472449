#pragma once
// The IFToMM N-four-bar of the benchmarks (N + 1 cranks pivoted at x = 0 .. N, N couplers,
// 1 kg / 1 m uniform bars, gravity): bench/forward_bench.cpp and bench/peers_bench.cpp.
#include <string>

#include "mo2d/system.hpp"

namespace mo2d::bench {

// prefix followed by k ("crank3"), by appends: GCC 12 warns falsely (-Wrestrict, its bug 105329)
// on "crank" + std::to_string(k) once inlined into a unity batch.
inline std::string numbered(const char* prefix, int k) {
  std::string name = prefix;
  name += std::to_string(k);
  return name;
}

inline System n_fourbar(int n) {
  System s(numbered("fourbar_chain_", n));
  const double m = 1.0, L = 1.0, I = m * L * L / 12;
  for (int k = 0; k <= n; ++k) {
    const std::string c = numbered("crank", k), o = numbered("O", k);
    s.add_ground_node(o, {double(k), 0.0});
    s.add_body({.name = c,
                .nodes = {{"O", {double(k), 0.0}}, {"B", {double(k), L}}},
                .mass = m,
                .inertia = I,
                .com = CenterOfMass::between("O", "B", 0.5)});
    s.add_revolute({.name = c + "_pivot", .node_a = "ground." + o, .node_b = c + ".O"});
  }
  for (int k = 0; k < n; ++k) {
    const std::string cp = numbered("coupler", k + 1);
    const std::string left = numbered("crank", k), right = numbered("crank", k + 1);
    s.add_body({.name = cp,
                .nodes = {{"A", {double(k), L}}, {"B", {double(k + 1), L}}},
                .mass = m,
                .inertia = I,
                .com = CenterOfMass::between("A", "B", 0.5)});
    s.add_revolute({.name = cp + "_left", .node_a = left + ".B", .node_b = cp + ".A"});
    s.add_revolute({.name = cp + "_right", .node_a = right + ".B", .node_b = cp + ".B"});
  }
  s.set_gravity({0, -9.81});
  return s;
}

}  // namespace mo2d::bench
