// Gear pairs as Box2D 2.4.1 gear joints; see box2d_world.hpp.
//
// Box2D's gear joint couples two revolute joints, joint1 (body C -> body A) and joint2
// (body D -> body B), by coordinate1 + ratio coordinate2 = constant, each coordinate the angle of
// the joint's second body relative to its first. A mo2d gear pair on carrier c (driven body j,
// driver k, ratio rho) is
//     (theta_j - theta_c) - rho (theta_k - theta_c) = constant,
// so joint1 = c -> j, joint2 = c -> k and ratio = -rho. Its impulse P acts on the carrier with
// -(1 - rho) P: the share -P through C and +rho P through D.
//
// A defect of Box2D 2.4.1 (b2_gear_joint.cpp): the solver reads the velocities of C and D into
// copies, updates both and writes them back one after the other, so when C and D are the same
// body the write of D overwrites that of C: the carrier receives +rho P only, and the effective
// mass counts I_c (1 + rho^2) instead of I_c (1 - rho)^2. On a moving carrier Box2D then
// integrates a machine whose gear is not workless (tests/crosscheck/gear_crosscheck_test.cpp:
// 0.17 rad after 1 s on a swinging housing, whatever the step or the iterations, and the same
// 0.17 rad from the Lagrangian with the carrier's share -P left out).
//
// The translation therefore never hands Box2D a gear whose two joints start on the same moving
// body: each moving carrier gets a proxy, a second Box2D body at the same pose, rigidly welded to
// it, the carrier's mass and inertia split equally between the two (same centre of mass: the
// pair is the carrier). The shafts of a carrier are coloured in two classes along the gear
// pairs (the pairs of one carrier must form a bipartite graph: a train or a tree of pairs); the
// revolute joints of the second class start on the proxy.
#include <box2d/box2d.h>

#include <map>
#include <queue>

#include "box2d_world.hpp"
#include "mo2d/error.hpp"

namespace mo2d::crosscheck_detail {

namespace {

[[noreturn]] void refuse_gear(const std::string& what, const std::string& element) {
  throw Error("Box2D cross-check: " + what, element);
}

// The carrier's revolute joint to `shaft` (node_a on the carrier), as a constraint index; -1 if
// none.
int revolute_index(const Model& m, int carrier, int shaft) {
  for (size_t i = 0; i < m.constraints.size(); ++i)
    if (const auto* r = std::get_if<Constraint::Revolute>(&m.constraints[i].def))
      if (r->body1 == carrier && r->body2 == shaft) return static_cast<int>(i);
  return -1;
}

// Two-colour the shafts of one carrier along its gear pairs (edges j - k); the shafts of colour 1
// are returned. Refuses an odd cycle.
std::vector<int> second_class(const std::string& carrier_name,
                              const std::vector<std::pair<int, int>>& edges) {
  std::map<int, std::vector<int>> adjacent;
  for (auto [a, b] : edges) {
    adjacent[a].push_back(b);
    adjacent[b].push_back(a);
  }
  std::map<int, int> colour;
  std::vector<int> ones;
  for (const auto& [start, unused] : adjacent) {
    if (colour.contains(start)) continue;
    colour[start] = 0;
    std::queue<int> open;
    open.push(start);
    while (!open.empty()) {
      const int s = open.front();
      open.pop();
      if (colour[s] == 1) ones.push_back(s);
      for (int t : adjacent[s]) {
        if (!colour.contains(t)) {
          colour[t] = 1 - colour[s];
          open.push(t);
        } else if (colour[t] == colour[s]) {
          refuse_gear("the gear pairs on carrier '" + carrier_name +
                          "' form an odd cycle: Box2D's gear joint needs the two joints of a "
                          "pair on distinct bodies, and the carrier split in two cannot give that",
                      carrier_name);
        }
      }
    }
  }
  return ones;
}

// A rack (q - r phi = constant: the slide coordinate q of a prismatic joint, phi the pinion's
// angle relative to the carrier) as a b2GearJoint between the b2PrismaticJoint (coordinate:
// the translation along the same axis i -> j, q + constant) and the carrier -> pinion
// b2RevoluteJoint (phi + constant), ratio -r.
void add_rack_joint(const Model& m, Box2DWorld& w, const Constraint& c) {
  const auto& g = c.as<Constraint::Gear>();
  const int pinion = gear_driver(m, g);
  b2Joint* slide = nullptr;
  b2Joint* axle = nullptr;
  for (const JointMap& j : w.joints) {
    const Constraint::Slider* s = m.constraints[j.constraint].slider();
    if (s && s->q == g.coord) {
      if (j.kind != JointKind::prismatic)
        refuse_gear("rack '" + c.name + "': its slide '" + j.name +
                        "' is a b2WheelJoint here (its rotation is free), which Box2D's gear "
                        "joint cannot couple",
                    c.name);
      slide = j.joint;
    }
    if (j.kind == JointKind::revolute && j.body1 == g.carrier && pinion >= 0 && j.body2 == pinion)
      axle = j.joint;
  }
  if (!slide || !axle)
    refuse_gear("rack '" + c.name +
                    "': Box2D's gear joint needs the slide as a prismatic joint and a revolute "
                    "joint from the carrier to the pinion",
                c.name);
  if (slide->GetBodyA() == axle->GetBodyA() && slide->GetBodyA()->GetType() != b2_staticBody)
    refuse_gear("rack '" + c.name +
                    "': the slide and the pinion's axle start on the same moving "
                    "body (Box2D 2.4.1's gear joint loses that body's share)",
                c.name);
  b2GearJointDef def;
  def.joint1 = slide;
  def.joint2 = axle;
  def.bodyA = slide->GetBodyB();
  def.bodyB = axle->GetBodyB();
  def.ratio = static_cast<float>(-g.ratio);
  w.world->CreateJoint(&def);
}

}  // namespace

int gear_driver(const Model& m, const Constraint::Gear& g) {
  for (const Constraint& k : m.constraints)
    if (const auto* cd = std::get_if<Constraint::Coordinate>(&k.def); cd && cd->coord == g.phi)
      for (auto [body, weight] : cd->angle_terms)
        if (weight > 0) return body;
  return -1;
}

std::vector<char> revolutes_on_proxy(const Model& m) {
  std::map<int, std::vector<std::pair<int, int>>> pairs;  // moving carrier -> gear edges
  for (const Constraint& c : m.constraints)
    if (const auto* g = std::get_if<Constraint::Gear>(&c.def); g && g->coord < 0 && g->carrier >= 0)
      pairs[g->carrier].emplace_back(g->body, gear_driver(m, *g));
  std::vector<char> on_proxy(m.constraints.size(), 0);
  for (const auto& [carrier, edges] : pairs)
    for (int shaft : second_class(m.bodies[carrier].name, edges))
      if (const int r = revolute_index(m, carrier, shaft); r >= 0) on_proxy[r] = 1;
  return on_proxy;
}

void add_carrier_proxy(Box2DWorld& w, int carrier) {
  BodyMap& map = w.bodies[carrier];
  if (map.proxy) return;
  b2Body* body = map.body;
  b2BodyDef def;
  def.type = b2_dynamicBody;
  def.position = body->GetPosition();
  def.angle = body->GetAngle();
  def.linearVelocity = body->GetLinearVelocity();
  def.angularVelocity = body->GetAngularVelocity();
  def.fixedRotation = body->IsFixedRotation();
  def.allowSleep = false;
  map.proxy = w.world->CreateBody(&def);
  b2MassData half;
  body->GetMassData(&half);
  half.mass *= 0.5f;
  half.I *= 0.5f;  // about the origin, the common centre of mass
  body->SetMassData(&half);
  map.proxy->SetMassData(&half);
  b2WeldJointDef weld;  // stiffness 0: a rigid weld
  weld.Initialize(body, map.proxy, body->GetPosition());
  w.world->CreateJoint(&weld);
}

void add_gear_joint(const Model& m, Box2DWorld& w, const Constraint& c) {
  const auto& g = c.as<Constraint::Gear>();
  if (g.coord >= 0) {
    add_rack_joint(m, w, c);
    return;
  }
  const int driver = gear_driver(m, g);
  b2Joint* j1 = nullptr;
  b2Joint* j2 = nullptr;
  for (const JointMap& j : w.joints) {
    if (j.kind != JointKind::revolute || j.body1 != g.carrier) continue;
    if (j.body2 == g.body) j1 = j.joint;
    if (driver >= 0 && j.body2 == driver) j2 = j.joint;
  }
  if (!j1 || !j2)
    refuse_gear("gear '" + c.name +
                    "': Box2D's gear joint needs a revolute joint from the carrier (node_a) to "
                    "the body and one to the driver",
                c.name);
  if (g.carrier >= 0 && j1->GetBodyA() == j2->GetBodyA())
    refuse_gear("gear '" + c.name + "': both revolute joints start on the same moving carrier",
                c.name);  // the Box2D defect described at the top; revolutes_on_proxy prevents it
  b2GearJointDef def;
  def.joint1 = j1;
  def.joint2 = j2;
  def.bodyA = j1->GetBodyB();
  def.bodyB = j2->GetBodyB();
  def.ratio = static_cast<float>(-g.ratio);
  w.world->CreateJoint(&def);
}

}  // namespace mo2d::crosscheck_detail
