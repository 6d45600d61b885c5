// The long render on every backend: a render stopped at any work item
// (mid-round of the pixels, mid-pass) and continued from its checkpoint file
// gives the uninterrupted render's bits; the time budget and a stop request
// end it after a whole pass; checkpoints are written as asked.
#include "longrun/render_loop.h"

#include <gtest/gtest.h>

#include <cstring>
#include <functional>

#include "longrun/film_file.h"
#include "megakernel/megakernel_renderer.h"
#include "reference/reference_renderer.h"
#include "support/temp_directory.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront/wavefront_test_support.h"

namespace wp {
namespace {

using MakeRenderer = std::function<std::unique_ptr<FilmRenderer>(const Scene&)>;

struct Backend {
    const char* name;
    MakeRenderer make;
};

// 2^10 paths in flight: passes of 2^14 work items, so the 24x24 x 40 spp
// render (23040 items) takes two passes on the wavefront.
const Backend kBackends[] = {
    {"wavefront",
     [](const Scene& s) {
         WavefrontOptions o;
         o.wavefront = 1024;
         return make_wavefront_renderer(s, o, {});
     }},
    {"megakernel", [](const Scene& s) { return make_megakernel_renderer(s, {}, {}); }},
    {"reference",
     [](const Scene& s) {
         return make_reference_renderer(s, {2, false});
     }},
};

bool same_film(const Film& a, const Film& b) {
    return a.items == b.items && a.sums.size() == b.sums.size() &&
           std::memcmp(a.sums.data(), b.sums.data(), sizeof(film_sum) * a.sums.size()) == 0;
}

bool same_image(const Image& a, const Image& b) {
    return a.rgb.size() == b.rgb.size() && std::memcmp(a.rgb.data(), b.rgb.data(), sizeof(float) * a.rgb.size()) == 0;
}

LongRunPlan plan_to(std::uint64_t end) {
    LongRunPlan plan;
    plan.items = {0, end};
    return plan;
}

class LongRender : public ::testing::TestWithParam<Backend> {
 protected:
    Scene scene_ = test::small_room(24, 40);
    std::uint64_t pixels_ = 24 * 24, total_ = pixels_ * 40;
    test::TempDirectory dir_{"long_render"};
};

TEST_P(LongRender, ResumedFromACheckpointGivesTheUninterruptedBits) {
    const Backend& backend = GetParam();
    const RenderResult whole = render_every_item(*backend.make(scene_), 24, 24, 40, {});
    // One item; a pixel short of a round; mid-round; past the first wavefront pass.
    for (std::uint64_t stop : {std::uint64_t(1), pixels_ - 1, 7 * pixels_ + 123, (std::uint64_t(1) << 14) + 5}) {
        SCOPED_TRACE(stop);
        LongRunPlan first = plan_to(stop);
        first.checkpoint_path = dir_ / "checkpoint.wpfilm";
        run_long_render(*backend.make(scene_), first, {});

        LongRunPlan rest = plan_to(total_);
        rest.start = read_film_file(first.checkpoint_path).film;
        ASSERT_EQ(rest.start->items, (ItemRange{0, stop}));
        const LongRunResult resumed = run_long_render(*backend.make(scene_), rest, {});
        EXPECT_EQ(resumed.stats.samples, total_ - stop);
        EXPECT_TRUE(same_image(resumed.film.image(), whole.image));
    }
}

TEST_P(LongRender, StopRequestEndsAfterOnePass) {
    const Backend& backend = GetParam();
    std::unique_ptr<FilmRenderer> renderer = backend.make(scene_);
    const std::uint64_t pass = renderer->pass_items();
    std::atomic<bool> stop{true};
    LongRunPlan plan = plan_to(total_);
    plan.stop_requested = &stop;
    const LongRunResult result = run_long_render(*renderer, plan, {});
    const std::uint64_t expected_end = std::min(pass, total_);
    EXPECT_EQ(result.film.items, (ItemRange{0, expected_end}));
    EXPECT_EQ(result.reason, expected_end < total_ ? StopReason::Interrupted : StopReason::Done);
}

INSTANTIATE_TEST_SUITE_P(Backends, LongRender, ::testing::ValuesIn(kBackends),
                         [](const auto& info) { return std::string(info.param.name); });

// A budget no pass fits: the first pass still runs (it measures the pass),
// the second does not.
TEST(LongRenderBudget, TimeBudgetStopsBeforeAPassThatWouldExceedIt) {
    Scene scene = test::small_room(8, 8);
    std::unique_ptr<FilmRenderer> renderer = make_reference_renderer(scene, {2, false});
    const std::uint64_t pass = renderer->pass_items();
    LongRunPlan plan = plan_to(3 * pass);
    plan.time_budget_s = 1e-6;
    const LongRunResult result = run_long_render(*renderer, plan, {});
    EXPECT_EQ(result.reason, StopReason::TimeBudget);
    EXPECT_EQ(result.film.items, (ItemRange{0, pass}));
    plan = plan_to(64 * 8);
    plan.time_budget_s = 1e6;
    EXPECT_EQ(run_long_render(*make_reference_renderer(scene, {2, false}), plan, {}).reason, StopReason::Done);
}

// --checkpoint-every 0: a checkpoint after every pass but the last, and one
// at the end; the last file holds the final film.
TEST(LongRenderCheckpoints, WrittenAfterEveryPassAndAtTheEnd) {
    test::TempDirectory dir("checkpoints");
    Scene scene = test::small_room(24, 40);
    std::unique_ptr<FilmRenderer> renderer = make_reference_renderer(scene, {2, false});
    const std::uint64_t total = std::uint64_t(24) * 24 * 40;
    LongRunPlan plan = plan_to(total);
    plan.checkpoint_path = dir / "c.wpfilm";
    plan.checkpoint_every_s = 0.0;
    plan.identity = render_identity(scene, "reference-float");
    const LongRunResult result = run_long_render(*renderer, plan, {});
    const std::uint64_t passes = (total + renderer->pass_items() - 1) / renderer->pass_items();
    EXPECT_EQ(result.checkpoints, int(passes));
    const FilmFile file = read_film_file(plan.checkpoint_path);
    EXPECT_EQ(file.identity, plan.identity);
    EXPECT_TRUE(same_film(file.film, result.film));
}

}  // namespace
}  // namespace wp
