#include "render/png_writer.hpp"

#include <stb_image_write.h>

namespace fetic::render {

PngBytes encode_png(const Image& image) {
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

PngEncoderPool::PngEncoderPool(int threads, int queue_limit) {
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
    sink(encode_png(image));
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
        job.sink(encode_png(job.image));
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
