// libFuzzer target: arbitrary bytes as a scene file through TOML parsing, key/type/range
// checks and validate_scene(). Invariants (any violation aborts, i.e. is a crash):
//   - the loader returns a valid scene or throws SceneError; no other exception escapes;
//   - a SceneError lists at least one problem and every line of its message names the file;
//   - a valid scene stays within the documented size limit and survives a round trip
//     through scene_to_toml() (the written text loads again with the same contents).
// An input starting with "#!repeat N" stands for a much longer one (fuzz/expand_repeats.hpp):
// that is how the fuzzer reaches nesting 40,000 deep and 100,000 struts.
// Build and run: scripts/fuzz.sh [SECONDS]

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

#include "fuzz/expand_repeats.hpp"
#include "scenes/load_scene.hpp"
#include "scenes/write_scene.hpp"

namespace {

const std::string kPath = "fuzz-input.toml";

[[noreturn]] void violated(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_scene: invariant violated: %s\n%s\n", what, detail.c_str());
  std::abort();
}

void check_error(const fetic::scenes::SceneError& error) {
  const std::string message = error.what();
  if (error.problems().empty()) violated("SceneError without problems", message);
  if (error.path() != kPath) violated("SceneError names another file", error.path());
  std::size_t start = 0;
  while (start <= message.size()) {
    const std::size_t end = std::min(message.find('\n', start), message.size());
    if (message.compare(start, kPath.size() + 1, kPath + ":") != 0)
      violated("a message line does not start with the file name", message);
    start = end + 1;
  }
}

void check_scene(const fetic::scenes::Scene& scene) {
  if (scene.path != kPath) violated("scene.path is not the file name", scene.path);
  if (scene.struts.empty()) violated("a valid scene without struts", "");
  if (fetic::scenes::unknowns(scene) > fetic::scenes::kMaxUnknowns)
    violated("a valid scene beyond kMaxUnknowns", std::to_string(fetic::scenes::unknowns(scene)));
  const std::string text = fetic::scenes::scene_to_toml(scene);
  try {
    const fetic::scenes::Scene again = fetic::scenes::parse_scene(text, kPath);
    if (again.struts.size() != scene.struts.size() || again.loads.size() != scene.loads.size() ||
        again.contacts.size() != scene.contacts.size() || again.model != scene.model)
      violated("the round trip changed the scene", text);
  } catch (const fetic::scenes::SceneError& error) {
    violated("a valid scene written by scene_to_toml() does not load again",
             std::string(error.what()) + "\n--- written text ---\n" + text);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text =
      fetic::fuzz::expand_repeats(std::string_view(reinterpret_cast<const char*>(data), size));
  try {
    check_scene(fetic::scenes::parse_scene(text, kPath));
  } catch (const fetic::scenes::SceneError& error) {
    check_error(error);
  } catch (const std::exception& error) {
    violated("an exception other than SceneError escaped the loader", error.what());
  } catch (...) {
    violated("a non-standard exception escaped the loader", "");
  }
  return 0;
}
