// SIGINT and SIGTERM during a render: the first asks the render to stop
// after the pass in flight (the image so far and the checkpoint are then
// written, exit code kExitInterrupted); a second SIGINT or SIGTERM ends the
// process at once (exit code 130). Every output is written atomically, so
// neither leaves a half-written file behind.
#pragma once

#include <atomic>

namespace wp::cli {

class StopSignals {
 public:
    // Installs the handlers (one StopSignals at a time).
    StopSignals();
    // Restores the previous handlers.
    ~StopSignals();
    StopSignals(const StopSignals&) = delete;
    StopSignals& operator=(const StopSignals&) = delete;

    // Set by the first signal.
    const std::atomic<bool>& requested() const;
};

}  // namespace wp::cli
