#include "cli/signals.h"

#include <signal.h>
#include <unistd.h>

#include <cstring>

namespace wp::cli {

namespace {

std::atomic<bool> stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the handler may only touch lock-free atomics");

struct sigaction previous_interrupt, previous_terminate;

void write_message(const char* message) {
    // Only async-signal-safe calls here: write(2), _exit(2).
    [[maybe_unused]] ssize_t ignored = ::write(STDERR_FILENO, message, std::strlen(message));
}

void on_stop_signal(int) {
    if (stop_requested.exchange(true)) {
        write_message("\nwavepath: stopped at once\n");
        ::_exit(130);
    }
    write_message("\nwavepath: stopping after the pass in flight (interrupt again to quit at once)\n");
}

}  // namespace

StopSignals::StopSignals() {
    stop_requested = false;
    struct sigaction action {};
    action.sa_handler = on_stop_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;  // OpenCL and file calls carry on
    sigaction(SIGINT, &action, &previous_interrupt);
    sigaction(SIGTERM, &action, &previous_terminate);
}

StopSignals::~StopSignals() {
    sigaction(SIGINT, &previous_interrupt, nullptr);
    sigaction(SIGTERM, &previous_terminate, nullptr);
}

const std::atomic<bool>& StopSignals::requested() const { return stop_requested; }

}  // namespace wp::cli
