// System: collecting definitions. Validation happens in build_model, where names can be resolved.
#include "mo2d/system.hpp"

#include <cmath>

#include "mo2d/law.hpp"

namespace mo2d {

Law::Law(Signal fn) {
  if (!fn) return;
  f = [fn = std::move(fn)](std::span<const Jet> /*x*/, Jet t) { return Jet(fn(t.v)); };
}

Law Law::constant(double value) {
  return Law({}, [value](std::span<const Jet> /*x*/, Jet /*t*/) { return Jet(value); });
}

Vec2 Placement::apply(const Vec2& p) const {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * p.x() - s * p.y() + offset.x(), s * p.x() + c * p.y() + offset.y()};
}

System& System::add_ground_node(std::string name, Vec2 position) {
  ground_.push_back({std::move(name), position});
  return *this;
}
System& System::add_body(BodyDef body) {
  bodies_.push_back(std::move(body));
  return *this;
}
BodyDef* System::find_body(const std::string& name) {
  for (BodyDef& b : bodies_)
    if (b.name == name) return &b;
  return nullptr;
}
System& System::add_revolute(RevoluteDef joint) {
  revolutes_.push_back(std::move(joint));
  return *this;
}
System& System::add_prismatic(PrismaticDef joint) {
  prismatics_.push_back(std::move(joint));
  return *this;
}
System& System::add_pin_in_slot(PinInSlotDef joint) {
  slots_.push_back(std::move(joint));
  return *this;
}
System& System::add_coordinate(CoordinateDef coordinate) {
  coordinates_.push_back(std::move(coordinate));
  return *this;
}
System& System::add_gear(GearDef gear) {
  gears_.push_back(std::move(gear));
  return *this;
}
System& System::add_rack(RackDef rack) {
  racks_.push_back(std::move(rack));
  return *this;
}
System& System::add_constraint(PositionConstraintDef constraint) {
  pos_.push_back(std::move(constraint));
  return *this;
}
System& System::add_constraint(VelocityConstraintDef constraint) {
  vel_.push_back(std::move(constraint));
  return *this;
}
System& System::add_force(ForceDef force) {
  forces_.push_back(std::move(force));
  return *this;
}
System& System::add_torque(TorqueDef torque) {
  torques_.push_back(std::move(torque));
  return *this;
}
System& System::add_spring(SpringDef spring) {
  springs_.push_back(std::move(spring));
  return *this;
}
System& System::add_torsional_spring(TorsionalSpringDef spring) {
  torsional_.push_back(std::move(spring));
  return *this;
}
System& System::add_chain(ChainDef chain) {
  chains_.push_back(std::move(chain));
  return *this;
}
System& System::add_friction(FrictionDef friction) {
  frictions_.push_back(std::move(friction));
  return *this;
}
System& System::add_instance(std::string name, const System& sub, Placement placement) {
  instances_.push_back({std::move(name), std::make_shared<const System>(sub), placement});
  return *this;
}
System& System::add_point(PointDef point) {
  points_.push_back(std::move(point));
  return *this;
}
System& System::set_gravity(Vec2 g) {
  gravity_ = g;
  return *this;
}

}  // namespace mo2d
