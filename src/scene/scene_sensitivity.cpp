// The parameter models of a scene's parameters (mo2d/scene_sensitivity.hpp).
#include "mo2d/scene_sensitivity.hpp"

#include <charconv>
#include <cmath>

#include "model/suggest.hpp"
#include "run/format.hpp"
#include "run/time_grid.hpp"

namespace mo2d {

namespace {

std::string number_text(double v) {  // shortest text that reads back to v
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, end);
}

// The prescribed motions of `s` against the run's at every sample time: equal values, rates and
// accelerations (the positions of the run depend on them).
void check_motion(const Scene& base, const Scene& s, const std::string& name,
                  const InverseOptions& o) {
  if (s.motion.size() != base.motion.size())
    throw Error("sensitivity to '" + name + "': it changes the prescribed motion", name);
  for (std::size_t i = 0; i < base.motion.size(); ++i)
    for (int k = 0; k < o.samples; ++k) {
      const double t = detail::sample_time(o.t0, o.t1, o.samples, k);
      const Jet a = base.motion[i].motion(Jet(t, 1, 0)), b = s.motion[i].motion(Jet(t, 1, 0));
      if (base.motion[i].coordinate != s.motion[i].coordinate || !(a.v == b.v) || !(a.d == b.d) ||
          !(a.dd == b.dd))
        throw Error("sensitivity to '" + name + "': it changes the prescribed motion of '" +
                        base.motion[i].coordinate + "' (at t = " + detail::fmt(t) +
                        " s); parameters of the motion are not supported yet",
                    name);
    }
}

}  // namespace

std::vector<ParameterModels> scene_parameter_models(std::string_view yaml, const Scene& scene,
                                                    std::span<const ParameterOverride> overrides,
                                                    std::span<const RunOverride> run,
                                                    std::span<const std::string> names,
                                                    const Model& m, const BuildOptions& build,
                                                    const InverseOptions& options) {
  std::vector<std::string> known;
  for (const auto& p : scene.parameters) known.push_back(p.first);
  std::vector<ParameterModels> out;
  for (const std::string& name : names) {
    std::size_t index = known.size();
    for (std::size_t k = 0; k < known.size(); ++k)
      if (known[k] == name) index = k;
    if (index == known.size())
      throw Error(
          "sensitivity to '" + name + "': not a parameter of " + scene.file +
              (known.empty() ? " (it has no parameters: block)" : did_you_mean(name, known)),
          name);
    for (const ParameterModels& p : out)
      if (p.name == name) throw Error("sensitivity to '" + name + "': asked twice", name);
    if (!scene.contacts.empty())
      throw Error("sensitivity to '" + name +
                      "': the scene has contacts; sensitivities of runs with contacts are not "
                      "supported yet",
                  name);
    ParameterModels p;
    p.name = name;
    p.value = scene.parameters[index].second;
    p.step = sensitivity_step(p.value);
    for (int k = 1; k <= 3; ++k) {
      std::vector<ParameterOverride> set;
      for (const ParameterOverride& o : overrides)
        if (o.name != name) set.push_back(o);
      const double value = p.value + k * p.step;
      set.push_back({name, number_text(value)});
      try {
        const Scene s = parse_scene(yaml, scene.file, set, run);
        check_motion(scene, s, name, options);
        p.at.push_back(build_scene_model(s, build));
      } catch (const Error& e) {
        if (e.element() == name && std::string(e.what()).starts_with("sensitivity")) throw;
        throw Error("sensitivity to '" + name + "': the scene with " + name + " = " +
                        number_text(value) + " (the step " + number_text(p.step) +
                        " of the exact difference formula) fails: " + e.what(),
                    name);
      }
    }
    check_parameter_models(m, p);
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace mo2d
