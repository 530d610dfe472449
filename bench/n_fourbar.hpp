#pragma once
// The IFToMM N-four-bar of the benchmarks (N + 1 cranks pivoted at x = 0 .. N, N couplers,
// 1 kg / 1 m uniform bars, gravity): bench/forward_bench.cpp and bench/peers_bench.cpp.
#include <string>

#include "mo2d/system.hpp"

namespace mo2d::bench {

inline System n_fourbar(int n) {
  System s("fourbar_chain_" + std::to_string(n));
  const double m = 1.0, L = 1.0, I = m * L * L / 12;
  for (int k = 0; k <= n; ++k) {
    const std::string c = "crank" + std::to_string(k), o = "O" + std::to_string(k);
    s.add_ground_node(o, {double(k), 0.0});
    s.add_body({.name = c,
                .nodes = {{"O", {double(k), 0.0}}, {"B", {double(k), L}}},
                .mass = m,
                .inertia = I,
                .com = CenterOfMass::between("O", "B", 0.5)});
    s.add_revolute({.name = c + "_pivot", .node_a = "ground." + o, .node_b = c + ".O"});
  }
  for (int k = 0; k < n; ++k) {
    const std::string cp = "coupler" + std::to_string(k + 1);
    const std::string left = "crank" + std::to_string(k), right = "crank" + std::to_string(k + 1);
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
