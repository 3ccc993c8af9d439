#pragma once
// Where fetic finds its data - the bundled scenes and the fonts of rendered text -
// wherever it is run from:
//   1. $FETIC_DATA_DIR, when set;
//   2. the installed layout: <directory of the executable>/../share/fetic
//      (`cmake --install build --prefix P`, the Debian package: /usr/share/fetic);
//   3. the source tree the executable was built from (running from the build tree).
// A scene the user names is taken as a path relative to the current directory first; when
// no such file exists, it is looked up among the bundled scenes by name (find_scene).

#include <filesystem>
#include <string>
#include <vector>

namespace fetic::app {

// The data directory (holds scenes/ and fonts/), or empty when none of the above exists.
std::filesystem::path data_directory();

// <data directory>/scenes/NAME; "scenes/NAME" (relative) when there is no data directory.
std::string bundled_scene(const std::string& name);

// Where a scene argument was found: `path` is the file to open (the argument itself when
// nothing matched), `looked_in` every place tried, in order.
struct SceneLookup {
  std::string path;
  std::vector<std::string> looked_in;
  bool found = false;
};

// `thesis`, `thesis.toml` and `scenes/thesis.toml` all name <data directory>/scenes/
// thesis.toml when no such path exists relative to the working directory. An existing
// path (file, FIFO, directory) is always taken as given; so is an absolute path.
SceneLookup find_scene(const std::string& argument);

// The argument's path after find_scene (for the command line's scene arguments).
std::string resolve_scene(const std::string& argument);

// The bundled scenes (*.toml in <data directory>/scenes), sorted by name.
std::vector<std::filesystem::path> bundled_scenes();

// A DejaVu font file: <data directory>/fonts/NAME when there, else fonts-dejavu-core's.
std::string font_file(const std::string& name);

}  // namespace fetic::app
