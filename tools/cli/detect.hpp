// `vkcollide detect`: reads the scene, opens the devices, adds the objects, runs the
// detections (one scene, --frames times, or each frame of a --sequence) and writes what the
// command line asks for. Returns the exit status (0, 1 an error, 3 validation messages).
#pragma once

#include "cli/options.hpp"

namespace cli {

int runDetect(const CommandLine& line);

}  // namespace cli
