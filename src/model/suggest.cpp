// "Did you mean" suggestions: the candidate at the smallest edit distance, if close enough.
#include "model/suggest.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

#include "mo2d/error.hpp"

namespace mo2d {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  std::iota(prev.begin(), prev.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1,
                         prev[j - 1] + static_cast<std::size_t>(a[i - 1] != b[j - 1])});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string did_you_mean(std::string_view name, std::span<const std::string> candidates) {
  std::string best;
  std::size_t best_d = std::string::npos;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(name, c);
    if (d < best_d) best_d = d, best = c;
  }
  if (best.empty() || best_d > std::max<std::size_t>(3, name.size() / 3)) return "";
  return " (did you mean '" + best + "'?)";
}

int label_index(std::span<const std::string> labels, const std::string& label, const char* what) {
  const auto it = std::find(labels.begin(), labels.end(), label);
  if (it == labels.end())
    throw Error(std::string("unknown ") + what + " '" + label + "'" + did_you_mean(label, labels),
                label);
  return static_cast<int>(it - labels.begin());
}

}  // namespace mo2d
