#pragma once
// Where fetic finds its data - the bundled scenes and the fonts of rendered text -
// wherever it is run from:
//   1. $FETIC_DATA_DIR, when set;
//   2. the installed layout: <directory of the executable>/../share/fetic
//      (`cmake --install build --prefix P`, the Debian package: /usr/share/fetic);
//   3. the source tree the executable was built from (running from the build tree).
// A scene path the user types is taken as given (relative to the current directory).

#include <filesystem>
#include <string>

namespace fetic::app {

// The data directory (holds scenes/ and fonts/), or empty when none of the above exists.
std::filesystem::path data_directory();

// <data directory>/scenes/NAME; "scenes/NAME" (relative) when there is no data directory.
std::string bundled_scene(const std::string& name);

// A DejaVu font file: <data directory>/fonts/NAME when there, else fonts-dejavu-core's.
std::string font_file(const std::string& name);

}  // namespace fetic::app
