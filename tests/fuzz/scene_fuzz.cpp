// libFuzzer target for the scene loader: any byte string must either load (and build a model) or
// be rejected with mo2d::Error (SceneError); a crash, a sanitizer report, a hang or any other
// exception is a bug. Built and run by scripts/fuzz.sh (clang,
// -fsanitize=fuzzer,address,undefined).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "mo2d/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const mo2d::Scene scene = mo2d::parse_scene(text, "fuzz.yaml");
    mo2d::BuildOptions options;
    const mo2d::Model model = mo2d::build_scene_model(scene, options);
    (void)model;
  } catch (const mo2d::Error&) {
    // rejected with a message: the expected outcome for most inputs
  }
  return 0;
}
