// set_parameter_values (mo2d/scene.hpp): a scene file's text with some parameters given new
// numbers in place, the rest of the text (comments, layout, the other parameters' expressions)
// kept; the result read back to check it.
#include <algorithm>
#include <charconv>
#include <cmath>

#include "scene/reader.hpp"

namespace mo2d {

namespace {

// The end (0-based, exclusive) of the scalar that starts at `pos` in `text`: a quoted scalar to
// its closing quote, a plain one to the end of its line, a comment (" #") or, in a flow map, the
// next ',' or '}'.
std::size_t scalar_end(const std::string& text, std::size_t pos, bool flow) {
  const char q = text[pos];
  if (q == '"' || q == '\'') {
    for (std::size_t k = pos + 1; k < text.size(); ++k) {
      if (q == '"' && text[k] == '\\') {
        ++k;
        continue;
      }
      if (text[k] != q) continue;
      if (q == '\'' && k + 1 < text.size() && text[k + 1] == '\'') {
        ++k;
        continue;
      }
      return k + 1;
    }
    return text.size();
  }
  std::size_t k = pos;
  for (; k < text.size(); ++k) {
    const char ch = text[k];
    if (ch == '\n' || ch == '\r') break;
    if (ch == '#' && k > pos && (text[k - 1] == ' ' || text[k - 1] == '\t')) break;
    if (flow && (ch == ',' || ch == '}')) break;
  }
  while (k > pos && (text[k - 1] == ' ' || text[k - 1] == '\t')) --k;
  return k;
}

std::string number_text(double v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, end);
}

}  // namespace

std::string set_parameter_values(std::string_view yaml, const std::string& file,
                                 std::span<const std::pair<std::string, double>> values) {
  std::string text(yaml);
  const Location where{file, 0, 0};
  YAML::Node doc;
  try {
    doc = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw SceneError(where, std::string("cannot read the scene: ") + e.what());
  }
  const YAML::Node params = doc["parameters"];
  if (!params.IsMap()) throw SceneError(where, "the scene has no parameters: block");
  const bool flow = params.Style() == YAML::EmitterStyle::Flow;
  struct Edit {
    std::size_t begin, end;
    std::string text;
  };
  std::vector<Edit> edits;
  for (const auto& [name, v] : values) {
    if (!std::isfinite(v)) throw Error("parameter '" + name + "': the value is not finite", name);
    const YAML::Node node = params[name];
    if (!node.IsDefined() || !node.IsScalar())
      throw SceneError(where,
                       "'" + name + "' is not a parameter given by a number or an expression");
    const auto pos = static_cast<std::size_t>(node.Mark().pos);
    if (pos >= text.size())
      throw SceneError(where, "parameter '" + name + "': cannot locate its value");
    edits.push_back({pos, scalar_end(text, pos, flow), number_text(v)});
  }
  std::sort(edits.begin(), edits.end(),
            [](const Edit& a, const Edit& b) { return a.begin > b.begin; });
  for (const Edit& e : edits) text.replace(e.begin, e.end - e.begin, e.text);
  // read back: every replaced parameter has exactly its new value
  const Scene back = parse_scene(text, file);
  for (const auto& value : values) {
    const std::string& name = value.first;
    const double v = value.second;
    const auto it = std::find_if(back.parameters.begin(), back.parameters.end(),
                                 [&](const auto& p) { return p.first == name; });
    if (it == back.parameters.end() || it->second != v)
      throw SceneError(
          where,
          "parameter '" + name + "': the rewritten scene reads " +
              (it == back.parameters.end() ? std::string("no value") : number_text(it->second)) +
              ", not " + number_text(v) + " (a value written over several lines?)");
  }
  return text;
}

}  // namespace mo2d
