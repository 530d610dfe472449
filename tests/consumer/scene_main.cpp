// A user of the installed mo2d::scene: load a scene from text, build it, print its DOF. Links
// yaml-cpp only through mo2d::scene (find_dependency in mo2dConfig.cmake).
#include <cstdio>
#include <mo2d/scene.hpp>

int main() {
  const char* text = R"yaml(
name: pendulum
ground: {O: [0, 0]}
bodies:
  link: {nodes: {O: [0, 0], P: [1, 0]}, mass: 1, com: P}
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: link.O, actuated: true}
)yaml";
  const mo2d::Model m = mo2d::build_scene_model(mo2d::parse_scene(text, "pendulum.yaml"));
  std::printf("scene %s: DOF %d\n", m.name.c_str(), m.dof);
  return m.dof == 1 ? 0 : 1;
}
