#pragma once
// Exit statuses of every fetic command (documented in docs/COMMANDS.md).

namespace fetic::app {

enum ExitCode : int {
  kExitOk = 0,
  kExitUsage = 1,          // bad command line
  kExitInvalidScene = 2,   // the scene file is missing or not valid
  kExitSolverSetup = 3,    // the method cannot solve this scene (singular, unsupported)
  kExitNotConverged = 4,   // no convergence, unbounded scene, numerical breakdown
  kExitOutput = 5,         // an output file could not be written
  kExitNoDisplay = 6,      // no display or EGL device for rendering
  kExitOutOfMemory = 7,    // the scene needs more memory than is available
  kExitInterrupted = 130,  // SIGINT or SIGTERM: outputs written so far are complete
};

}  // namespace fetic::app
