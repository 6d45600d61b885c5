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
// Seconds left at `fraction` done, from the rate since the first samples were
// reported done (at first_fraction, since_first_s ago): the kernel build,
// the first launches' compilation (PoCL compiles a kernel at its first
// launch) and the filling of the wavefront all come before them and would
// make the ETA absurd. -1: not measured yet.
double estimate_eta(double fraction, double first_fraction, double since_first_s);

// What a fraction done means to the user: the count it goes through (samples
// per pixel for a render, shapes for a scene's load) at fraction 0 and 1
// (both 0: not shown), with its unit and the decimals shown of the count
// reached, and a time budget (0: none) that caps the ETA.
struct ProgressPlan {
    double count_at_start = 0.0, count_at_end = 0.0;
    double time_budget_s = 0.0;
    std::string unit = "spp";
    int decimals = 1;
};

// "12.5/64 spp" at `fraction` of `plan`, "" when the plan shows no count.
std::string format_count_done(const ProgressPlan& plan, double fraction);

// eta_s < 0 shows "ETA --"; spp_done (format_count_done) is left out when "".
// "[#########-----------]  45.0%  12.5/64 spp  elapsed 7s  ETA 9s" (no line ending).
std::string format_progress_bar(double fraction, double elapsed_s, double eta_s, const std::string& spp_done = "");
// "wavepath: 45% done, 12.5/64 spp, 7s elapsed, ETA 9s".
std::string format_progress_line(double fraction, double elapsed_s, double eta_s, const std::string& spp_done = "");

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
    // first fraction above 0 starts the clock the ETA is measured on.
    void update(double fraction_done);
    // Writes "wavepath: <what>" on a line of its own at once (not when Silent).
    void step(std::string_view what);
    // step() and update() for a renderer.
    Progress callback();
    // Shows the plan's count and caps the ETA by the time budget (call before the first update()).
    void set_plan(const ProgressPlan& plan) { plan_ = plan; }
    // Draws the complete bar and ends its line (no-op for other styles).
    void finish();
    // finish() if a bar is on screen; nothing if none was drawn (a scene
    // that loaded too quickly to show its bar).
    void finish_shown();

 private:
    double record(double fraction_done);
    void draw(double fraction, Clock::time_point now);
    void end_bar_line();

    ProgressStyle style_;
    std::ostream& out_;
    Clock::duration interval_;
    Clock::time_point start_ = Clock::now();
    std::atomic<double> fraction_{0.0};
    std::once_flag first_samples_;
    Clock::time_point first_samples_time_;  // when a fraction above 0 first arrived
    double first_fraction_ = 0.0;           // that fraction
    std::mutex draw_mutex_;
    Clock::time_point last_output_ = start_;
    bool bar_open_ = false;  // a bar is on screen without its line ending
    ProgressPlan plan_;
};

}  // namespace wp::cli
