// The scene reader's YAML look-ups (src/scene/reader.hpp): a const look-up that finds nothing gives
// an invalid node that names its key, as yaml-cpp's own std::stringstream text did, for every key
// type the reader uses (its key text is written without a stream since docs/performance.md, "CLI
// start-up").
#include <gtest/gtest.h>

#include <string>

#include "scene/reader.hpp"

namespace reader_lookup_test {

// The message of the InvalidNode thrown by reading `missing` (an invalid node) as a number.
std::string invalid_node_message(const YAML::Node& missing) {
  try {
    (void)missing.as<double>();
  } catch (const YAML::InvalidNode& e) {
    return e.what();
  }
  return "(no InvalidNode)";
}

TEST(SceneReader, MissedLookUpNamesItsKey) {
  const YAML::Node map = YAML::Load("{mass: 1, inertia: 2}");
  const std::string expected = "invalid node; first invalid key: \"length\"";
  const char* pointer = "length";
  const std::string text = "length";
  EXPECT_EQ(invalid_node_message(map["length"]), expected);  // a string literal (char[7])
  EXPECT_EQ(invalid_node_message(map[pointer]), expected);
  EXPECT_EQ(invalid_node_message(map[text]), expected);
  EXPECT_FALSE(map["length"].IsDefined());
  EXPECT_EQ(map["inertia"].as<double>(), 2.0);  // a key that is there: its value
  EXPECT_EQ(map[text.substr(0, 0) + "mass"].as<double>(), 1.0);
}

}  // namespace reader_lookup_test
