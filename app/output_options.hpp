#pragma once
// The command-line check every option that names an output shares: an empty name would
// write nothing, so it is refused (status 1) instead of being taken as "not given".

#include <CLI/CLI.hpp>

namespace fetic::app {

enum class OutputKind { File, Folder };

// Refuses an empty name: "an empty name writes nothing; give a file name (- for standard
// output)" or "... give a folder name".
CLI::Validator output_name(OutputKind kind = OutputKind::File);

}  // namespace fetic::app
