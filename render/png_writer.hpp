#pragma once
// PNG encoding with libspng, and a small pool of worker threads that encodes frames while
// the next ones render; the pool hands each encoded PNG to a sink (which writes the file,
// atomically, in the app layer). Frames are opaque, so they are written as RGB; zlib at
// level 3 without row filters: on these flat pictures (large areas of one colour) the
// filters buy little and cost most of the time (docs/RENDERING.md, "Frame rate").

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

// The PNG file of `image` (deterministic: same pixels, same bytes). RGB when every pixel
// is opaque, RGBA otherwise, so that it is always lossless. Empty when encoding failed.
PngBytes encode_png(const Image& image);
// The encoder fetic used before libspng (stb_image_write, its default zlib level 8 and
// all row filters): `fetic bench-render` measures the two in the same run.
PngBytes encode_png_stb(const Image& image);

class PngEncoderPool {
 public:
  using Sink = std::function<void(PngBytes)>;

  using Encoder = PngBytes (*)(const Image&);

  // `threads` workers; 0 encodes on the calling thread inside submit(). At most
  // `queue_limit` frames wait (memory: 3.7 MB each at 1280x720); submit() blocks beyond.
  explicit PngEncoderPool(int threads, int queue_limit = 0, Encoder encoder = &encode_png);
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

  Encoder encoder_ = &encode_png;
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
