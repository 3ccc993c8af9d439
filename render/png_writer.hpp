#pragma once
// PNG encoding with stb_image_write, and a small pool of worker threads that encodes
// frames while the next ones render: encoding (60-100 ms a frame at 1280x720) costs far
// more than rendering (about 4 ms), so the frame rate of a movie is set by it. The pool
// hands each encoded PNG to a sink (which writes the file, atomically, in the app layer).

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "render/image.hpp"

namespace fetic::render {

using PngBytes = std::vector<std::uint8_t>;

// The PNG file of `image` (deterministic: same pixels, same bytes).
PngBytes encode_png(const Image& image);

class PngEncoderPool {
 public:
  using Sink = std::function<void(PngBytes)>;

  // `threads` workers; 0 encodes on the calling thread inside submit(). At most
  // `queue_limit` frames wait (memory: 3.7 MB each at 1280x720); submit() blocks beyond.
  explicit PngEncoderPool(int threads, int queue_limit = 0);
  ~PngEncoderPool();  // finishes the queued frames, ignoring their errors
  PngEncoderPool(const PngEncoderPool&) = delete;
  PngEncoderPool& operator=(const PngEncoderPool&) = delete;

  // Encodes `image` and passes the bytes to `sink`, on some worker. Rethrows the first
  // exception a sink has thrown so far (later frames are then dropped).
  void submit(Image image, Sink sink);
  // Waits until every submitted frame is through its sink; rethrows the first exception.
  void finish();
  int threads() const { return static_cast<int>(workers_.size()); }

 private:
  struct Job {
    Image image;
    Sink sink;
  };
  void work();
  void rethrow_failure();

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> queue_;
  std::size_t queue_limit_ = 1;
  int busy_ = 0;
  bool stopping_ = false;
  std::exception_ptr failure_;
};

}  // namespace fetic::render
