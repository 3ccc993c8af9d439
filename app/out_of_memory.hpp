#pragma once
// std::bad_alloc anywhere ends a command with "out of memory while ACTIVITY" and status 7
// (kExitOutOfMemory), never an abort: the main thread catches it (main.cpp); on any other
// thread (OpenMP regions, the gui's solver, PNG encoders) it would reach std::terminate,
// whose handler installed here says the same, removes temporary outputs and exits.

namespace fetic::app {

// What the command is doing now, for the message; scoped: the previous one comes back at
// the end of the scope, unless an exception leaves it (the message names where it arose).
class Activity {
 public:
  explicit Activity(const char* what);
  ~Activity();
  Activity(const Activity&) = delete;
  Activity& operator=(const Activity&) = delete;

 private:
  const char* previous_;
  int exceptions_;
};

// "reading the scene", "assembling the model", ... ("working" before any is set).
const char* current_activity();

// Installs the std::terminate handler described above.
void install_out_of_memory_handler();

// Prints "fetic: out of memory while ACTIVITY (...)" and returns kExitOutOfMemory.
int report_out_of_memory();

}  // namespace fetic::app
