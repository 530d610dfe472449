#pragma once
// Generator of random valid mechanisms for the metamorphic tests
// (tests/metamorphic/metamorphic_test.cpp, docs/testing.md). A mechanism is first generated as
// plain data (Mechanism: positions, masses, load amplitudes, motion parameters), so that each
// metamorphic transformation (translate, rotate, mirror, scale, reorder) is applied exactly to the
// data; to_system() then writes the mo2d::System a user would write.
//
// Geometry is consistent by construction: the nodes are placed first, then the bodies are defined
// from those positions (a node shared by two bodies has the same coordinates in both).
// Reproducible: one seed gives the same mechanism with any standard library (std::mt19937_64 is
// specified exactly; the distributions are written here because std:: distributions are not).
#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "mo2d/inverse.hpp"
#include "mo2d/model.hpp"
#include "mo2d/system.hpp"

namespace mo2d::meta {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : g_(seed) {}
  double uniform();                        // [0, 1), 53 random bits
  double uniform(double a, double b);      // [a, b)
  double log_uniform(double a, double b);  // log-uniform on [a, b), 0 < a < b
  int integer(int lo, int hi);             // lo..hi inclusive
  bool chance(double p);
  double sign() { return chance(0.5) ? 1.0 : -1.0; }
  Vec2 direction(double angle_lo = -3.14159265358979, double angle_hi = 3.14159265358979);

 private:
  std::mt19937_64 g_;
};

// a0 + a1 sin(omega t + phase): the signal of every load (scalar or vector amplitudes).
struct Wave {
  double a0 = 0, a1 = 0, omega = 0, phase = 0;
  double operator()(double t) const;
};
struct VecWave {
  Vec2 a0{0, 0}, a1{0, 0};
  double omega = 0, phase = 0;
  Vec2 operator()(double t) const;
};

struct CenterSpec {
  CenterOfMass::Kind kind = CenterOfMass::Kind::node;
  std::string ni{}, nj{};
  double gamma = 0, rho = 0;
  Vec2 point{0, 0};
};
struct BodySpec {
  std::string name{};
  std::vector<NodeDef> nodes{};
  double mass = 0, inertia = 0;
  CenterSpec com{};
  bool rotates() const { return nodes.size() >= 2 || inertia > 0; }
};
struct ForceSpec {
  std::string name{}, body{};
  Vec2 point{0, 0};
  VecWave f{};
};
struct TorqueSpec {
  std::string name{}, body{};
  Wave tau{};
};
struct SpringSpec {
  std::string name{}, body_a{};
  Vec2 point_a{0, 0};
  std::string body_b{};
  Vec2 point_b{0, 0};
  double rest = 0, k = 0, c = 0;
};
struct TorsionSpec {
  std::string name{}, joint{};
  double k = 0, c = 0;
};
struct CoordSpec {  // an extra coordinate (always an angle here), initial value 0
  std::string name{};
  std::vector<std::pair<std::string, double>> rate{};
};
struct InstanceSpec {
  std::string name{};
  int sub = 0;  // index in Mechanism::subs
  Placement placement{};
};

struct SystemSpec {
  std::string name{};
  std::vector<NodeDef> ground{};
  std::vector<BodySpec> bodies{};
  std::vector<RevoluteDef> revolutes{};
  std::vector<PrismaticDef> prismatics{};
  std::vector<PinInSlotDef> slots{};
  std::vector<CoordSpec> coords{};
  std::vector<ForceSpec> forces{};
  std::vector<TorqueSpec> torques{};
  std::vector<SpringSpec> springs{};
  std::vector<TorsionSpec> torsionals{};
  std::vector<InstanceSpec> instances{};
  Vec2 gravity{0, 0};
};

// Prescribed motion s(t) = s0 + amp (sin(omega t + phase) - sin(phase)) + drift t of an angle
// (an extra coordinate) or a length (a slider coordinate "joint.q").
struct MotionSpec {
  std::string coordinate{};
  bool angle = true;
  double s0 = 0, amp = 0, omega = 0, phase = 0, drift = 0;
  Jet operator()(Jet t) const;
};

struct Mechanism {
  std::uint64_t seed = 0;
  int attempt = 0;       // candidates rejected before this one (same seed)
  std::string family{};  // modules, e.g. "fourbar+chain2+legs3"
  std::vector<SystemSpec> subs{};
  SystemSpec root{};
  std::vector<MotionSpec> motion{};
  double t1 = 1;      // run [0, t1] (s)
  double length = 1;  // characteristic length (m): tolerances on positions are relative to it
  double time = 1;    // characteristic time sqrt(length / 9.81 m/s^2) (s) of motions and loads
  bool has_springs() const;         // linear or torsional, at any level
  bool has_external_loads() const;  // point forces or torques, at any level
  bool has_subsystems() const { return !root.instances.empty(); }
};

System to_system(const Mechanism& m);
std::vector<Prescribed> prescribed(const Mechanism& m);

// Exact transformations of the data.
Mechanism translated(const Mechanism& m, Vec2 d);     // ground included
Mechanism rotated(const Mechanism& m, double angle);  // about the origin, gravity and loads too
Mechanism mirrored(const Mechanism& m);               // x -> -x
Mechanism scaled(const Mechanism& m, double L, double M, double T);  // lengths, masses, time
Mechanism reordered(const Mechanism& m, std::uint64_t seed);         // nodes, bodies, joints, loads

// Flattened, world-frame description at the initial configuration, written from the data (not
// from mo2d's Model): used by the independent energy and power functions of the tests.
struct FlatBody {
  std::string name{};                      // full label, "leg1.p"
  std::vector<std::string> node_labels{};  // full labels, "leg1.p.E"
  std::vector<Vec2> nodes{};               // initial world positions
  double mass = 0, inertia = 0;
  Vec2 com{0, 0};  // initial world position of the centre of mass
};
struct FlatPoint {
  int body = -1;  // -1: ground
  Vec2 p{0, 0};   // initial world position
};
struct FlatSpring {
  FlatPoint a, b;
  double rest = 0, k = 0, c = 0;
};
struct FlatTorsion {
  int body1 = -1, body2 = -1;
  double k = 0, c = 0;
};
struct FlatForce {
  FlatPoint at;
  VecWave f;  // world frame
};
struct FlatTorque {
  int body = -1;
  Wave tau;
};
struct FlatActuator {
  std::string input{};         // "j3.torque", "leg1.j1.torque", "j5.force"
  bool revolute = true;        // torque u: power u (w2 - w1); else force u: power u dq/dt
  int body1 = -1, body2 = -1;  // revolute
  std::string rate{};          // prismatic: "j5.v"
};
struct Flat {
  std::vector<FlatBody> bodies;
  std::vector<FlatSpring> springs;
  std::vector<FlatTorsion> torsionals;
  std::vector<FlatForce> forces;
  std::vector<FlatTorque> torques;
  std::vector<FlatActuator> actuators;
  Vec2 gravity{0, 0};
};
Flat flatten(const Mechanism& m);

// Conditioning of a configuration for the prescribed coordinates: smallest singular value over the
// largest of [Psi; E] (position Jacobian with rows normalised to unit length and length columns
// multiplied by Model::scale, so dimensionless; E selects the prescribed coordinates).
double prescribed_conditioning(const Model& model, const Eigen::VectorXd& q0,
                               const std::vector<std::string>& prescribed_labels);

struct GeneratorOptions {
  int samples = 41;               // inverse-dynamics samples on which a candidate is checked
  double min_sigma_ratio = 1e-2;  // reject a candidate whose conditioning falls below this
  int max_attempts = 50;
};
struct GeneratorStats {
  long candidates = 0, accepted = 0;
  std::map<std::string, long> rejected;  // reason -> count
  std::map<std::string, long> families;  // module -> accepted mechanisms containing it
};

// A random valid mechanism for this seed (rejected candidates are counted in stats by reason).
Mechanism generate(std::uint64_t seed, GeneratorStats& stats, const GeneratorOptions& o = {});

}  // namespace mo2d::meta
