#include "render/png_writer.hpp"

#include <spng.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

namespace fetic::render {

PngBytes encode_png(const Image& image) {
  const std::size_t pixels =
      static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  if (image.width <= 0 || image.height <= 0 || image.rgba.size() < 4 * pixels) return {};
  bool opaque = true;
  for (std::size_t i = 3; i < 4 * pixels && opaque; i += 4)
    opaque = image.rgba[i] == 255;
  std::vector<std::uint8_t> rgb;
  if (opaque) {
    rgb.resize(3 * pixels);
    for (std::size_t i = 0; i < pixels; ++i)
      std::copy_n(image.rgba.data() + 4 * i, 3, rgb.data() + 3 * i);
  }
  const std::unique_ptr<spng_ctx, decltype(&spng_ctx_free)> context(spng_ctx_new(SPNG_CTX_ENCODER),
                                                                    &spng_ctx_free);
  if (!context) return {};
  spng_ctx* ctx = context.get();
  spng_set_option(ctx, SPNG_ENCODE_TO_BUFFER, 1);
  spng_set_option(ctx, SPNG_IMG_COMPRESSION_LEVEL, 3);
  spng_set_option(ctx, SPNG_FILTER_CHOICE, SPNG_FILTER_CHOICE_NONE);
  spng_ihdr header{};
  header.width = static_cast<std::uint32_t>(image.width);
  header.height = static_cast<std::uint32_t>(image.height);
  header.bit_depth = 8;
  header.color_type = opaque ? SPNG_COLOR_TYPE_TRUECOLOR : SPNG_COLOR_TYPE_TRUECOLOR_ALPHA;
  if (spng_set_ihdr(ctx, &header) != 0) return {};
  const void* data = opaque ? static_cast<const void*>(rgb.data()) : image.rgba.data();
  const std::size_t size = opaque ? rgb.size() : 4 * pixels;
  if (spng_encode_image(ctx, data, size, SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE) != 0) return {};
  std::size_t length = 0;
  int error = 0;
  void* buffer = spng_get_png_buffer(ctx, &length, &error);
  if (!buffer || error != 0) {
    std::free(buffer);
    return {};
  }
  const auto* bytes = static_cast<const std::uint8_t*>(buffer);
  PngBytes png(bytes, bytes + length);
  std::free(buffer);
  return png;
}

PngBytes encode_png_stb(const Image& image) {
  PngBytes bytes;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<PngBytes*>(context);
    const auto* begin = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), begin, begin + size);
  };
  if (!stbi_write_png_to_func(append, &bytes, image.width, image.height, 4, image.rgba.data(),
                              image.width * 4))
    bytes.clear();
  return bytes;
}

PngEncoderPool::PngEncoderPool(int threads, int queue_limit, Encoder encoder) : encoder_(encoder) {
  queue_limit_ = static_cast<std::size_t>(queue_limit > 0 ? queue_limit : std::max(1, threads));
  for (int i = 0; i < threads; ++i)
    workers_.emplace_back([this] { work(); });
}

PngEncoderPool::~PngEncoderPool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  for (std::thread& worker : workers_)
    worker.join();
}

void PngEncoderPool::rethrow_failure() {
  if (failure_) std::rethrow_exception(failure_);
}

void PngEncoderPool::submit(Image image, Sink sink) {
  if (workers_.empty()) {
    sink(encoder_(image));
    return;
  }
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return failure_ || queue_.size() < queue_limit_; });
  rethrow_failure();
  queue_.push_back({std::move(image), std::move(sink)});
  changed_.notify_all();
}

void PngEncoderPool::finish() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.empty() && busy_ == 0; });
  rethrow_failure();
}

void PngEncoderPool::work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stopping, nothing left
    Job job = std::move(queue_.front());
    queue_.pop_front();
    ++busy_;
    const bool skip = static_cast<bool>(failure_);
    lock.unlock();
    changed_.notify_all();  // room in the queue
    std::exception_ptr error;
    if (!skip) {
      try {
        job.sink(encoder_(job.image));
      } catch (...) {
        error = std::current_exception();
      }
    }
    lock.lock();
    --busy_;
    if (error && !failure_) failure_ = error;
    changed_.notify_all();
  }
}

}  // namespace fetic::render
