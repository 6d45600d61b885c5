// Render progress on stderr: a bar redrawn in place when stderr is a
// terminal, an occasional plain line when it is a log, nothing when quiet.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <ostream>
#include <string>
#include <string_view>

#include "core/render.h"

namespace wp::cli {

enum class ProgressStyle { Silent, Bar, Lines };

// Bar when stderr is a terminal, Lines otherwise, Silent when quiet.
ProgressStyle choose_progress_style(bool quiet);

// "7s", "2m05s", "1h02m".
std::string format_duration(double seconds);
// The ETA extrapolates the time spent sampling (sampling_s, which leaves out
// the kernel build and other setup); "ETA --" until samples are done.
// "[#########-----------]  45.0%  elapsed 7s  ETA 9s" (no line ending).
std::string format_progress_bar(double fraction, double elapsed_s, double sampling_s);
// "wavepath: 45% done, 7s elapsed, ETA 9s".
std::string format_progress_line(double fraction, double elapsed_s, double sampling_s);

class ProgressReporter {
 public:
    using Clock = std::chrono::steady_clock;

    // Redraws a bar at most every 0.1 s, writes a line at most every 5 s.
    ProgressReporter(ProgressStyle style, std::ostream& out);
    // For tests: any interval between outputs.
    ProgressReporter(ProgressStyle style, std::ostream& out, Clock::duration interval);
    // Ends a bar's line if finish() was not reached, so an error message
    // that follows starts on a line of its own.
    ~ProgressReporter();
    ProgressReporter(const ProgressReporter&) = delete;
    ProgressReporter& operator=(const ProgressReporter&) = delete;

    // Thread-safe; fractions may arrive out of order, the largest counts. The
    // first call starts the sampling clock the ETA is measured on.
    void update(double fraction_done);
    // Writes "wavepath: <what>" on a line of its own at once (not when Silent).
    void step(std::string_view what);
    // step() and update() for a renderer.
    Progress callback();
    // Draws the complete bar and ends its line (no-op for other styles).
    void finish();

 private:
    double record(double fraction_done);
    void draw(double fraction, Clock::time_point now);
    void end_bar_line();

    ProgressStyle style_;
    std::ostream& out_;
    Clock::duration interval_;
    Clock::time_point start_ = Clock::now();
    std::atomic<double> fraction_{0.0};
    std::once_flag sampling_started_;
    Clock::time_point sampling_start_;  // set once, by the first update()
    std::mutex draw_mutex_;
    Clock::time_point last_output_ = start_;
    bool bar_open_ = false;  // a bar is on screen without its line ending
};

}  // namespace wp::cli
