#pragma once
// Ending a child process (ffmpeg) when fetic is interrupted.

#include <sys/types.h>

#include <chrono>

namespace fetic::app {

// Sends SIGTERM, waits up to `grace` for the child to end, then sends SIGKILL; reaps it
// either way. SIGTERM alone is not enough: ffmpeg's handler only counts the signal and
// restarts the call it interrupted, so an ffmpeg blocked opening a FIFO without a reader
// would never end (and fetic, waiting for it, neither).
void stop_child(pid_t child, std::chrono::milliseconds grace = std::chrono::seconds(1));

}  // namespace fetic::app
