#pragma once
// Standard output is an output like any other: a lost byte there (a full disk, /dev/full,
// a closed descriptor, a reader that went away) must not end in status 0.

namespace fetic::app {

// At start-up: a closed descriptor 0, 1 or 2 is taken by a read-only descriptor, so that
// no file the command opens later becomes "stdout" by accident and every write to it
// fails visibly (EBADF). SIGPIPE is ignored: a write to a pipe without a reader fails
// with EPIPE and is reported like any other lost write.
void guard_standard_streams();

// At the end: flushes stdout (C++ and C streams); when any byte written to it was lost,
// says so on stderr and returns kExitOutput in place of a status of success (0) or
// non-convergence (4). Other statuses are kept.
int finish_standard_output(int status);

}  // namespace fetic::app
