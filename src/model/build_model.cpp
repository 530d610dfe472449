// build_model: System tree -> flat, constant Model. The driver of the stages declared, with the
// data passed between them, in model/build_stages.hpp (one file per stage in src/model/).
#include <set>

#include "dynamics/chain.hpp"
#include "mo2d/budget.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/model.hpp"
#include "model/build_stages.hpp"

namespace mo2d {
namespace {

void check_input_labels(const Model& m) {
  std::set<std::string> input_labels;
  for (const auto& in : m.inputs)
    if (!input_labels.insert(in.label).second)
      throw Error("input '" + in.label + "' is defined twice", in.label);
}

// Stage 8: holonomy and DOF; then (BuildOptions::assemble) the consistent initial configuration
// from the given one `q0` and the check that no constraint is redundant.
// chain_modes (stage 8b): the inextensible chains' rows only of the spans at their length (a chain
// with slack in both spans stays slack: detail::chain_start); m's ranks are checked either way.
void assemble_model(Model& m, const Eigen::VectorXd& q0, const BuildOptions& options,
                    bool chain_modes = false) {
  m.q0 = q0;
  m.holonomic = true;
  for (const auto& c : m.constraints) {
    const auto* coordinate = std::get_if<Constraint::Coordinate>(&c.def);
    if ((coordinate && !coordinate->holonomic) || c.kind() == ConstraintKind::user_velocity)
      m.holonomic = false;
  }
  m.dof = m.n1 - m.m1;
  if (!options.assemble) return;
  check_memory("building '" + m.name + "' (assembly and rank checks)",
               build_memory_bytes(m.n0, m.m0, m.n1, m.m1), options.max_memory, model_sizes(m),
               "max_memory");
  try {
    if (chain_modes)
      m.q0 = detail::chain_start(m, q0, 0.0, {}, options.assembly_tolerance).q0;
    else
      m.q0 = assemble(m, q0, 0.0, {}, options.assembly_tolerance);
    check_constraint_ranks(m, m.q0, 0.0);
  } catch (const Error& e) {  // a build-time error: no run time
    throw Error(e.what(), e.element());
  }
}

}  // namespace

Model build_model(const System& system, const BuildOptions& options) {
  using namespace build;
  // 1. flatten the tree of subsystems; 1b. place the bodies given by their shape
  Flat flat = flatten(system);
  SketchReport sketch = resolve_sketches(flat, options);
  Model m;
  m.name = system.name();
  m.reduction = options.reduction;
  m.gravity = system.gravity();
  m.tree = flat.tree;
  m.ground_names = flat.ground_names;
  m.ground_positions = flat.ground_pos;

  // 2. validate: nodes, bodies (with their mass data), names, the topology of revolute joints
  check_gravity(m.gravity);
  const Elements elements = collect_elements(flat, options, m);
  add_bodies(flat, m);
  check_names(flat);
  check_revolute_topology(flat, elements);

  // 3. variable reduction, each joint validated where it is met
  const Reduced reduced = reduce(flat, elements, options, m);

  // 4. variables and labels; 5. constraint rows, reactions, inputs
  Numbering numbering = number_variables(flat, elements, reduced, m);
  const JointReactions joint_reactions = add_rows(flat, elements, reduced, numbering, m);

  // 6. loads; 7. merge edges of the eliminated joints
  add_loads(flat, elements, reduced, m);
  add_chains(flat, m);
  add_frictions(flat, elements, reduced, m);
  add_merge_edges(elements, reduced, joint_reactions, m);

  // 8. assemble
  check_input_labels(m);
  assemble_model(m, numbering.q0, options);
  init_chains(m);
  if (add_inextensible_chains(m)) assemble_model(m, m.q0, options, true);  // 8b. the spans' rows
  m.sketch = std::move(sketch);
  complete_sketch_report(m);
  return m;
}

}  // namespace mo2d
