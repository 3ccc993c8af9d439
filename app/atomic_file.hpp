#pragma once
// Output files appear whole or not at all: written to a temporary file beside the
// target, then renamed over it.

#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>

namespace fetic::app {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Calls write(stream) on a temporary file, then renames it to `path`. Throws OutputError
// (naming the file) when anything fails; the temporary file is removed.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

// Same for a writer that produces the file itself at a given path (e.g. a PNG encoder).
void write_via_temporary(const std::string& path,
                         const std::function<bool(const std::string&)>& write);

}  // namespace fetic::app
