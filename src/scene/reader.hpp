#pragma once
// Typed, located reading of YAML nodes for the scene loader: every accessor either returns the
// value or throws SceneError at the node's line and column with what was expected.
#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mo2d/expression.hpp"
#include "mo2d/scene.hpp"
#include "mo2d/table.hpp"

// A const look-up `node[key]` that finds nothing returns an invalid node carrying the key's text
// (for the message of a later YAML::InvalidNode), which yaml-cpp 0.7 writes through a
// std::stringstream (YAML::key_to_string): about 3,500 instructions a look-up, 83 look-ups of
// optional keys and 0.3 M of `mo2d info mechanisms/double_fourbar.yaml` (docs/performance.md,
// "CLI start-up"). For the key types the scene reader uses (string literals, const char*,
// std::string) the same text without a stream. Declared here, before any look-up: every file that
// reads YAML includes this header. (yaml-cpp 0.7 declares the template in the global namespace.)
template <std::size_t N>
struct streamable_to_string<char[N], true> {
  static std::string impl(const char (&key)[N]) { return std::string(key); }
};
template <>
struct streamable_to_string<const char*, true> {
  static std::string impl(const char* key) { return key ? std::string(key) : std::string(); }
};
template <>
struct streamable_to_string<std::string, true> {
  static std::string impl(const std::string& key) { return key; }
};

namespace mo2d::scene_detail {

using Entries = std::vector<std::pair<YAML::Node, YAML::Node>>;  // (key, value) in file order

struct Reader {
  std::string file{};
  std::string_view source{};                             // the YAML text (it outlives the reader)
  std::unordered_map<std::string, double> parameters{};  // evaluated
  std::vector<std::string> parameter_names{};
  // The scene's tables as functions of one argument, callable in every expression read after
  // them (Reader::expression passes them to Expression::parse).
  std::vector<NamedFunction> functions{};
  // The same tables by name (a contact's cam profile names one).
  std::vector<std::pair<std::string, std::shared_ptr<const LookupTable>>> tables{};

  Location at(const YAML::Node& node) const;
  [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const;

  // `node` must be a map whose keys are all in `allowed` (else "unknown key ... did you mean").
  void check_keys(const YAML::Node& node, std::initializer_list<const char*> allowed,
                  const std::string& what) const;
  // The entries of a map (null = empty), keys checked to be unique scalars.
  Entries entries(const YAML::Node& node, const std::string& what) const;
  // map[key], which must exist.
  YAML::Node required(const YAML::Node& map, const char* key, const std::string& what) const;

  std::string string(const YAML::Node& node, const std::string& what) const;
  bool boolean(const YAML::Node& node, const std::string& what) const;
  int integer(const YAML::Node& node, const std::string& what) const;
  // A number: a constant expression of the parameters.
  double number(const YAML::Node& node, const std::string& what) const;
  double number_or(const YAML::Node& map, const char* key, double fallback,
                   const std::string& what) const;
  Vec2 vec2(const YAML::Node& node, const std::string& what) const;
  std::vector<std::string> strings(const YAML::Node& node, const std::string& what) const;
  // An expression of t (and the parameters), shared by the closures that evaluate it.
  std::shared_ptr<const Expression> time_function(const YAML::Node& node,
                                                  const std::string& what) const;
  // Parse a scalar as an expression (the built-in functions and `functions`); errors point at the
  // offending column of the file.
  Expression expression(const YAML::Node& node, const std::string& what) const;
  // The file position of column `column` (1-based) of the expression text of `node`; of the
  // indicator for a block scalar (| or >, whose text is not the file's).
  Location at_column(const YAML::Node& node, int column) const;
  // Rethrow an ExpressionError from the text of `node` at its file position.
  [[noreturn]] void fail_expression(const YAML::Node& node, const ExpressionError& e,
                                    const std::string& what) const;
  Binding parameter_binding(const std::string& name) const;
};

const char* type_name(const YAML::Node& node);

}  // namespace mo2d::scene_detail
