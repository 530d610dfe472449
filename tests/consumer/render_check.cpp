// Links mo2d::render from an installed mo2d: Cairo, a private dependency of the static library,
// must be found by find_package(mo2d). Draws one frame of a pendulum in memory.
#include <mo2d/mo2d.hpp>
#include <mo2d/render.hpp>

int main() {
  using namespace mo2d;
  System s("pendulum");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "link", .nodes = {{"O", {0, 0}}, {"P", {1, 0}}}, .mass = 1});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "link.O"});
  const Model model = build_model(s);
  FrameOptions o;
  o.width = 64;
  o.height = 48;
  const Image im = render_frame(model, single_configuration(model.q0), 0, o);
  return im.width == 64 && im.height == 48 ? 0 : 1;
}
