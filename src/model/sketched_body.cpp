// Bodies given by their lengths and a sketch (mo2d/sketched_body.hpp): the BodyDef of a bar and
// of a shape with an approximate placement; build_model's sketch assembly does the rest.
#include "mo2d/sketched_body.hpp"

#include <cmath>
#include <utility>

#include "mo2d/error.hpp"

namespace mo2d {

BodyDef bar_body(std::string name, double length, NodeDef a, NodeDef b) {
  if (!std::isfinite(length) || !(length > 0))
    throw Error("body '" + name + "': a bar's length must be finite and > 0 m, not " +
                    std::to_string(length),
                name);
  BodyDef body;
  body.name = std::move(name);
  body.nodes = {std::move(a), std::move(b)};
  body.shape = {Vec2(0, 0), Vec2(length, 0)};
  return body;
}

BodyDef placed_body(std::string name, std::vector<NodeDef> shape, Placement at) {
  if (shape.empty()) throw Error("body '" + name + "': a shape needs at least one node", name);
  BodyDef body;
  body.name = std::move(name);
  for (NodeDef& n : shape) {
    body.shape.push_back(n.position);
    body.nodes.push_back({std::move(n.name), at.apply(n.position)});
  }
  return body;
}

}  // namespace mo2d
