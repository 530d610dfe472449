#pragma once
// The parameter models of a scene's parameters for exact sensitivities (mo2d/sensitivity.hpp):
// the scene read again with the parameter at p + h, p + 2h, p + 3h (its dependent parameters and
// every expression that reads it evaluated again), the models built, and the refusals of what the
// run's kinematics would depend on.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mo2d/inverse.hpp"
#include "mo2d/model.hpp"
#include "mo2d/scene.hpp"
#include "mo2d/sensitivity.hpp"

namespace mo2d {

// For each name of `names` (a parameter of the scene's parameters: block), its ParameterModels:
// the scene text `yaml` (of `scene`, read with `overrides` and `run`) parsed again with the
// parameter at p + k h (k = 1, 2, 3; h = sensitivity_step(p)), each built with `build` (the
// options `m`, the run's model, was built with). Throws Error (element: the name) for a name that
// is not a parameter (with a suggestion), a scene with contacts, a scene that fails at p + k h,
// a prescribed motion that changes at a sample time of `options`, and everything
// check_parameter_models refuses.
std::vector<ParameterModels> scene_parameter_models(std::string_view yaml, const Scene& scene,
                                                    std::span<const ParameterOverride> overrides,
                                                    std::span<const RunOverride> run,
                                                    std::span<const std::string> names,
                                                    const Model& m, const BuildOptions& build,
                                                    const InverseOptions& options);

}  // namespace mo2d
