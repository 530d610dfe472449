#pragma once
// Bodies given by their lengths and a sketch, as scene files write them (docs/scene-format.md,
// "Bodies given by their shape"): `length:` (a bar) and `shape:` with `at:` (an approximate
// placement). Each returns a BodyDef whose shape is exact and whose node positions are a sketch;
// build_model (mo2d/model.hpp) places the body rigidly where every joint closes, nearest to the
// sketch (the sketch picks the assembly branch), and Model::sketch reports how far each node
// moved. No circle intersections by hand:
//
//   s.add_body(bar_body("coupler", 0.35, {"A", {0, 0.1}}, {"B", {0.3, 0.3}}));  // B: elbow up
//   BodyDef rocker = placed_body("rocker", {{"O", {0, 0}}, {"B", {0.3, 0}}}, {{0.4, 0}, 1.8});
//   rocker.mass = 0.4;
//   s.add_body(rocker);
//
// The scene loader makes its bodies with these (src/scene/load_system.cpp).
#include <string>
#include <vector>

#include "mo2d/system.hpp"

namespace mo2d {

// A bar of length `length` (m) between its nodes a and b: a at (0, 0) and b at (length, 0) in the
// bar's own frame (its shape, exact), a.position and b.position the sketch (approximate, in the
// System's frame). Mass, inertia and centre of mass are left to set on the result. Throws Error
// naming the body if the length is not finite and > 0.
BodyDef bar_body(std::string name, double length, NodeDef a, NodeDef b);

// A body given by its shape, the nodes' coordinates in its own frame (exact; at least one node),
// and an approximate placement `at` (rotation, then shift): each node sketched at
// at.apply(its shape coordinates). Throws Error naming the body for an empty shape.
BodyDef placed_body(std::string name, std::vector<NodeDef> shape, Placement at);

}  // namespace mo2d
