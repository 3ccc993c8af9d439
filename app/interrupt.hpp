#pragma once
// SIGINT and SIGTERM only raise a flag; long loops (iterations, frames, load steps) ask
// for it between steps and stop cleanly. Output files are written atomically, so an
// interrupted run leaves complete files only.

namespace fetic::app {

void install_interrupt_handlers();
bool interrupted();
// "SIGINT" or "SIGTERM" (empty when not interrupted).
const char* interrupt_name();
// The same for a signal number (another process' signal, under MPI).
const char* signal_name(int signal);
// The signal received, or 0.
int interrupt_signal();

}  // namespace fetic::app
