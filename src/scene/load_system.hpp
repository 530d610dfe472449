#pragma once
// Reading one system block (ground, bodies, joints, coordinates, constraints, loads, instances) of
// a scene: the root document and each entry of `subsystems` use the same keys.
#include <map>
#include <memory>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "reader.hpp"

namespace mo2d::scene_detail {

// What a parent may refer to in a system: node labels ("body.node", "ground.node",
// "instance.body.node"), body names, revolute joints, and where each element was defined.
struct SystemInfo {
  std::vector<std::string> nodes{};
  std::vector<std::string> bodies{};
  std::vector<std::string> points{};  // named points ("instance.point")
  std::vector<std::pair<std::string, Location>> elements{};
  // where each argument of a load's law is written: "element/label" (element: full name)
  std::vector<std::pair<std::string, Location>> law_labels{};
  // labels read by constraint expressions, where each is written (Scene::expression_labels)
  std::vector<ExpressionLabel> labels{};
};

struct BuiltSubsystem {
  std::shared_ptr<const System> system{};
  SystemInfo info{};
};

// The `subsystems` map, built on first use (an instance may use a subsystem defined anywhere in
// the map; a subsystem that contains itself is an error).
struct Subsystems {
  YAML::Node definitions{};
  std::map<std::string, BuiltSubsystem> built{};
  std::set<std::string> building{};
};

inline constexpr std::initializer_list<const char*> kSystemKeys = {
    "ground",      "bodies", "joints",    "coordinates", "gears",        "racks",
    "constraints", "loads",  "instances", "points",      "transmissions"};

// A law from an expression of t, the parameters and quantities of the state (its other names,
// resolved by build_model); a function of time only when it names none. `uses` (if given)
// receives where each argument is written, as "element/label".
Law state_law(const Reader& r, const YAML::Node& node, const std::string& what,
              const std::string& element, std::vector<std::pair<std::string, Location>>* uses);

// points: {name: {body, point}} -> System::add_point (load_outputs.cpp).
void read_points(const Reader& r, const YAML::Node& node, System& out, SystemInfo& info);
// outputs: {loads, com, points} -> Scene::outputs (load_outputs.cpp).
void read_outputs(const Reader& r, const YAML::Node& node, const SystemInfo& info, Scene& scene);
// design: {four_bars, frame, bearings, speed_fluctuation} -> Scene::design (load_design.cpp).
void read_design(const Reader& r, const YAML::Node& node, const SystemInfo& info, Scene& scene);
// The `friction` entry of joint `name` (load_friction.cpp), if any, added to `out`.
void read_joint_friction(const Reader& r, const YAML::Node& joint, const std::string& name,
                         bool revolute, System& out);

// gears: and racks: (load_gears.cpp), added to `out`.
// run.accuracy in a run: block (and what it replaces), and the command-line flags that cannot go
// with it (load_accuracy.cpp)
void read_accuracy(const Reader& r, const YAML::Node& node, RunSettings& run);
void check_accuracy_overrides(std::span<const RunOverride> overrides, bool scene_accuracy);
void read_gears(const Reader& r, const YAML::Node& gears, const YAML::Node& racks, System& out,
                SystemInfo& info);

// transmissions: (load_transmissions.cpp), added to `out` at the fidelity each names.
void read_transmissions(const Reader& r, const YAML::Node& node, System& out, SystemInfo& info);

// An element's name at `key` (a gear's, rack's, chain's, transmission's, shaft's, point's): an
// error at the key's line if it holds '.', ',', ':' or spaces, or is "ground" (load_gears.cpp).
void check_element_name(const Reader& r, const YAML::Node& key, const std::string& what);
// loads: chains: (load_chains.cpp), added to `out`.
// The body named at map[key] (a gear's, a rack's or a chain's): a body of the system, or
// "ground" where ground_allowed; an error at the key's line otherwise, with a suggestion.
std::string body_of(const Reader& r, const YAML::Node& map, const char* key,
                    const std::string& what, const SystemInfo& info, bool ground_allowed);
void read_chains(const Reader& r, const YAML::Node& chains, System& out, SystemInfo& info);

// contacts: (load_contacts.cpp) -> scene.contacts, each named in info.elements; and the contact
// run's keys of run: (max_events, zeno_time, zeno_speed, baumgarte_rate) -> scene.contact.
void read_contacts(const Reader& r, const YAML::Node& node, SystemInfo& info, Scene& scene);
void read_contact_run(const Reader& r, const YAML::Node& run, Scene& scene);

// Fill `out` from `block`; root: gravity is allowed in loads.
SystemInfo read_system(const Reader& r, const YAML::Node& block, System& out, bool root,
                       Subsystems& library);

}  // namespace mo2d::scene_detail
