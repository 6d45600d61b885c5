#include "cli/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace wp::cli {

namespace {

constexpr auto kBarInterval = std::chrono::milliseconds(100);  // ~10 Hz redraw
constexpr auto kLineInterval = std::chrono::seconds(5);        // sparse enough for CI logs
constexpr int kBarWidth = 30;

std::string eta_text(double eta_s) { return eta_s < 0.0 ? "ETA --" : "ETA " + format_duration(eta_s); }

double seconds(ProgressReporter::Clock::duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

ProgressStyle choose_progress_style(bool quiet) {
    if (quiet) return ProgressStyle::Silent;
    return ::isatty(STDERR_FILENO) ? ProgressStyle::Bar : ProgressStyle::Lines;
}

std::string format_duration(double seconds) {
    const long total = std::lround(std::max(seconds, 0.0));
    char text[32];
    if (total < 60)
        std::snprintf(text, sizeof text, "%lds", total);
    else if (total < 3600)
        std::snprintf(text, sizeof text, "%ldm%02lds", total / 60, total % 60);
    else
        std::snprintf(text, sizeof text, "%ldh%02ldm", total / 3600, total / 60 % 60);
    return text;
}

double estimate_eta(double fraction, double first_fraction, double since_first_s) {
    if (fraction <= first_fraction || since_first_s <= 0.0) return -1.0;
    return since_first_s * (1.0 - fraction) / (fraction - first_fraction);
}

std::string format_count_done(const ProgressPlan& plan, double fraction) {
    if (plan.count_at_end <= 0.0) return "";
    char text[64];
    std::snprintf(text, sizeof text, "%.*f/%.0f ", plan.decimals,
                  plan.count_at_start + fraction * (plan.count_at_end - plan.count_at_start), plan.count_at_end);
    return text + plan.unit;
}

std::string format_progress_bar(double fraction, double elapsed_s, double eta_s, const std::string& spp_done) {
    const int filled = static_cast<int>(fraction * kBarWidth);
    std::string bar(1, '[');
    bar.append(filled, '#').append(kBarWidth - filled, '-');
    char percent[32];
    std::snprintf(percent, sizeof percent, "] %5.1f%%  ", 100.0 * fraction);
    bar.append(percent);
    if (!spp_done.empty()) bar.append(spp_done).append("  ");
    return bar.append("elapsed ").append(format_duration(elapsed_s)).append("  ").append(eta_text(eta_s));
}

std::string format_progress_line(double fraction, double elapsed_s, double eta_s, const std::string& spp_done) {
    std::string line = "wavepath: " + std::to_string(static_cast<int>(100.0 * fraction)) + "% done, ";
    if (!spp_done.empty()) line.append(spp_done).append(", ");
    return line + format_duration(elapsed_s) + " elapsed, " + eta_text(eta_s);
}

ProgressReporter::ProgressReporter(ProgressStyle style, std::ostream& out)
    : ProgressReporter(style, out, style == ProgressStyle::Bar ? Clock::duration(kBarInterval) : kLineInterval) {}

ProgressReporter::ProgressReporter(ProgressStyle style, std::ostream& out, Clock::duration interval)
    : style_(style), out_(out), interval_(interval) {}

ProgressReporter::~ProgressReporter() { end_bar_line(); }

void ProgressReporter::end_bar_line() {
    if (bar_open_) out_ << std::endl;
    bar_open_ = false;
}

double ProgressReporter::record(double fraction_done) {
    const double clamped = std::clamp(fraction_done, 0.0, 1.0);
    double seen = fraction_.load();
    while (clamped > seen && !fraction_.compare_exchange_weak(seen, clamped)) {
    }
    return std::max(seen, clamped);
}

void ProgressReporter::update(double fraction_done) {
    if (style_ == ProgressStyle::Silent) return;
    const double fraction = record(fraction_done);
    if (fraction > 0.0)
        std::call_once(first_samples_, [&] {
            first_samples_time_ = Clock::now();
            first_fraction_ = fraction;
        });
    if (fraction <= 0.0) return;  // nothing measured to show yet
    // Another thread drawing right now already shows (nearly) this fraction.
    std::unique_lock lock(draw_mutex_, std::try_to_lock);
    if (!lock) return;
    const Clock::time_point now = Clock::now();
    if (now - last_output_ < interval_) return;
    last_output_ = now;
    draw(fraction, now);
}

void ProgressReporter::step(std::string_view what) {
    if (style_ == ProgressStyle::Silent) return;
    std::lock_guard lock(draw_mutex_);
    end_bar_line();
    out_ << "wavepath: " << what << std::endl;
}

Progress ProgressReporter::callback() {
    return {[this](std::string_view what) { step(what); }, [this](double fraction_done) { update(fraction_done); }};
}

void ProgressReporter::finish() {
    if (style_ != ProgressStyle::Bar) return;
    std::lock_guard lock(draw_mutex_);
    draw(1.0, Clock::now());
    end_bar_line();
}

void ProgressReporter::finish_shown() {
    std::lock_guard lock(draw_mutex_);
    if (!bar_open_) return;
    draw(1.0, Clock::now());
    end_bar_line();
}

void ProgressReporter::draw(double fraction, Clock::time_point now) {
    const double elapsed_s = seconds(now - start_);
    // Before the first update() nothing has been sampled (finish() without one).
    // Nothing measured yet when finish() comes before any samples.
    const double since_first_s = seconds(now - first_samples_time_);
    double eta_s = fraction >= 1.0 ? 0.0 : estimate_eta(fraction, first_fraction_, since_first_s);
    if (plan_.time_budget_s > 0.0 && fraction > 0.0) {  // the budget ends the render first
        const double budget_left_s = std::max(0.0, plan_.time_budget_s - since_first_s);
        eta_s = eta_s < 0.0 ? budget_left_s : std::min(eta_s, budget_left_s);
    }
    const std::string spp_done = format_count_done(plan_, fraction);
    if (style_ == ProgressStyle::Bar) {
        out_ << "\r" << format_progress_bar(fraction, elapsed_s, eta_s, spp_done) << "\033[K"
             << std::flush;  // clear leftovers
        bar_open_ = true;
    } else {
        out_ << format_progress_line(fraction, elapsed_s, eta_s, spp_done) << std::endl;
    }
}

}  // namespace wp::cli
