#pragma once
// The scene file as text, read within a size limit checked before reading (what toml++
// may then see is checked by scenes/toml_guard.hpp).

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

#include "scenes/scene_error.hpp"

namespace fetic::scenes {

// Largest scene file read, in bytes. Parsing takes about 30 times the file's size in
// memory (toml++'s tree; docs/RELIABILITY.md), and a scene of the size limit in unknowns
// fits in far less text.
inline constexpr std::size_t kMaxSceneFileBytes = std::size_t{64} << 20;

// Reads the file: a regular file's size is checked first, any other stream (a FIFO,
// /dev/stdin, a device) is read up to the limit. Refuses a directory. Throws SceneError
// naming the path. `stop` is asked whenever a signal interrupts a wait (opening a FIFO
// without a writer, reading from it); when it returns true the reading ends with a
// SceneError saying so.
std::string read_scene_text(const std::string& path, const std::function<bool()>& stop = {});

// The same for any text file read whole (`what`, for messages: "scene file", "script"),
// up to `max_bytes`.
std::string read_text_file(const std::string& path, std::size_t max_bytes, const std::string& what,
                           const std::function<bool()>& stop = {});

}  // namespace fetic::scenes
