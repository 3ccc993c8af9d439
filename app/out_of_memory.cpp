#include "app/out_of_memory.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>

#include "app/exit_codes.hpp"
#include "app/output_file.hpp"

namespace fetic::app {
namespace {

std::atomic<const char*> activity{"working"};

const char* const kAdvice =
    " (the scene needs more memory than this process may have: see docs/RELIABILITY.md, "
    "\"Memory\")\n";

void write_error(const char* text) {
  const size_t length = std::strlen(text);
  for (size_t written = 0; written < length;) {
    const ssize_t n = ::write(2, text + written, length - written);
    if (n <= 0) return;
    written += static_cast<size_t>(n);
  }
}

[[noreturn]] void on_terminate() {
  if (const std::exception_ptr error = std::current_exception()) {
    try {
      std::rethrow_exception(error);
    } catch (const std::bad_alloc&) {
      write_error("fetic: out of memory while ");
      write_error(current_activity());
      write_error(kAdvice);
      remove_temporary_outputs();
      ::_exit(kExitOutOfMemory);
    } catch (...) {
    }
  }
  std::abort();  // anything else is a bug: keep the core dump
}

}  // namespace

Activity::Activity(const char* what)
    : previous_(activity.exchange(what)), exceptions_(std::uncaught_exceptions()) {}
Activity::~Activity() {
  if (std::uncaught_exceptions() == exceptions_) activity.store(previous_);
}

const char* current_activity() {
  return activity.load();
}

void install_out_of_memory_handler() {
  std::set_terminate(on_terminate);
}

int report_out_of_memory() {
  remove_temporary_outputs();
  write_error("fetic: out of memory while ");
  write_error(current_activity());
  write_error(kAdvice);
  return kExitOutOfMemory;
}

}  // namespace fetic::app
