#pragma once
// A movie made while the frames render: raw RGBA frames go through a pipe into ffmpeg
// (H.264), with no PNG files in between. A writer thread feeds the pipe, so the next frame
// renders while ffmpeg takes the last one. Used inside write_output_by
// (app/output_file.hpp), so a movie file appears whole or not at all, and a FIFO, a device
// or standard output gets a fragmented mp4 (it cannot be rewound for the index).

#include <sys/types.h>

#include <condition_variable>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "app/output_file.hpp"
#include "render/image.hpp"

namespace fetic::app {

// Starts ffmpeg reading `input` (its input options and -i) and writing an H.264 mp4 (with
// the `encoding` options, e.g. a preset) to the target: the file itself, standard output
// when target.file is "", a fragmented mp4 onto a stream. `stdin_fd` >= 0 becomes its
// standard input. SIGPIPE, which fetic ignores, is back at its default there. Returns 0,
// or the error of posix_spawnp.
int spawn_ffmpeg(const std::vector<std::string>& input, const std::vector<std::string>& encoding,
                 const ExternalTarget& target, int stdin_fd, pid_t& child);

class MovieStream {
 public:
  // Starts ffmpeg writing an mp4 of width x height at `fps` frames per second to the
  // target. Throws OutputError when ffmpeg cannot be started.
  MovieStream(const ExternalTarget& target, int width, int height, int fps);
  // Stops ffmpeg if finish() was not called (its output is then incomplete).
  ~MovieStream();
  MovieStream(const MovieStream&) = delete;
  MovieStream& operator=(const MovieStream&) = delete;

  // Queues a frame (of the size given above); blocks while two frames wait. Throws
  // OutputError when ffmpeg has stopped taking frames.
  void submit(render::Image image);
  // Closes the pipe and waits for ffmpeg. True when every frame went in and ffmpeg
  // finished the file; false when it failed or the run was interrupted meanwhile (then
  // ffmpeg is stopped).
  bool finish();
  int frames() const { return written_; }

 private:
  void write_frames();
  void stop_ffmpeg();

  int width_ = 0, height_ = 0;
  int pipe_ = -1;  // write end, ffmpeg's standard input
  pid_t child_ = 0;
  std::thread writer_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<render::Image> queue_;
  bool closing_ = false;
  bool broken_ = false;  // ffmpeg stopped reading
  int written_ = 0;
};

}  // namespace fetic::app
