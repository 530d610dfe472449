#pragma once
// "Did you mean" suggestions for unknown names (labels, keys, parameters), shared by the model
// builder, the scene loader and the expression parser.
#include <cstddef>
#include <span>
#include <string>
#include <string_view>

namespace mo2d {

// Levenshtein distance (insertions, deletions, substitutions).
std::size_t edit_distance(std::string_view a, std::string_view b);

// " (did you mean 'x'?)" for the closest candidate within max(3, |name| / 3) edits, else "".
std::string did_you_mean(std::string_view name, std::span<const std::string> candidates);

// Index of `label` in `labels`; throws Error("unknown <what> 'label'" + did_you_mean) if absent.
int label_index(std::span<const std::string> labels, const std::string& label, const char* what);

}  // namespace mo2d
