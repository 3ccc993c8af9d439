#pragma once
// The version of fetic (CMakeLists.txt's project version), as written into every output
// that says what made it: --version, the result file, the VTU files, the monitor stream.

namespace fetic::app {

// "0.1.0"
const char* fetic_version();

}  // namespace fetic::app
