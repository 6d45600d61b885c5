// The queue graph declared once (kernels/interface/stages.h): the kernels
// are what it declares, the host's queue bookkeeping follows from it, and
// docs/architecture.md states it. (That a push the declaration does not list
// fails to compile is tested with the program builds, tests/opencl.)
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "support/kernel_sources.h"
#include "wavefront/host_trace.h"
#include "wavefront/queue_plan.h"
#include "wavefront/stage.h"

namespace wp {
namespace {

const std::map<std::string, std::uint32_t> kQueueByName{{"FREE", WP_QUEUE_FREE},
                                                        {"HIT", WP_QUEUE_HIT},
                                                        {"RAY", WP_QUEUE_RAY},
                                                        {"SHADOW", WP_QUEUE_SHADOW},
                                                        {"PHOTON_FREE", WP_QUEUE_PHOTON_FREE},
                                                        {"PHOTON_RAY", WP_QUEUE_PHOTON_RAY},
                                                        {"PHOTON_HIT", WP_QUEUE_PHOTON_HIT}};

std::uint32_t bit(const char* queue) { return 1u << kQueueByName.at(queue); }

// The queues of a mask by name, "FREE RAY" (in index order), for messages and comparisons.
std::string queue_names(std::uint32_t mask) {
    std::vector<std::pair<std::uint32_t, std::string>> named;
    for (const auto& [name, queue] : kQueueByName)
        if (mask >> queue & 1u) named.emplace_back(queue, name);
    std::sort(named.begin(), named.end());
    std::string names;
    for (const auto& [queue, name] : named) {
        if (!names.empty()) names += ' ';
        names += name;
    }
    return names;
}

// Queue names in `text` (FREE, HIT ...), as a mask.
std::uint32_t queues_named_in(const std::string& text) {
    static const std::regex word(R"(\b[A-Z_]+\b)");
    std::uint32_t mask = 0;
    for (std::sregex_iterator m(text.begin(), text.end(), word), end; m != end; ++m)
        if (auto queue = kQueueByName.find(m->str()); queue != kQueueByName.end()) mask |= 1u << queue->second;
    return mask;
}

TEST(StageDeclaration, QueueNamesOfTheTestAreEveryQueue) {
    EXPECT_EQ(kQueueByName.size(), std::size_t(WP_QUEUE_COUNT));
    std::uint32_t all = 0;
    for (const auto& entry : kQueueByName) all |= 1u << entry.second;
    EXPECT_EQ(all, (1u << WP_QUEUE_COUNT) - 1u);
}

// What is wrong with kernels/<stage>.cl against the stage's declaration
// ("" when nothing): the file defines the stage's kernel, opens it with the
// stage's queues, and pushes to every queue the declaration lists (a push it
// does not list fails to compile, device/path_queues.h).
std::string kernel_file_problem(const StageDeclaration& stage) {
    const std::string kernel = stage.kernel, file = kernel + ".cl";
    if (!std::filesystem::exists(test::kKernelDirectory / file)) return "no kernels/" + file;
    const std::string code = test::without_comments(test::read_text(test::kKernelDirectory / file));
    std::smatch opening;
    if (!std::regex_search(code, opening,
                           std::regex("void " + kernel + R"(\(WP_STAGE_PARAMS\)\s*\{\s*STAGE_QUEUES\(\s*(\w+)\s*,)")))
        return "kernels/" + file + " defines no kernel " + kernel + " that opens with STAGE_QUEUES";
    if (opening[1] != kernel) return "kernel " + kernel + " opens with the queues of " + opening[1].str();
    std::uint32_t pushed = 0;
    static const std::regex push(R"(STAGE_PUSH\(\s*(\w+)\s*,)");
    for (std::sregex_iterator m(code.begin(), code.end(), push), end; m != end; ++m)
        pushed |= queues_named_in((*m)[1].str());
    if (pushed != stage.pushes)
        return "kernel " + kernel + " pushes to " + queue_names(pushed) + ", declared " + queue_names(stage.pushes);
    return "";
}

TEST(StageDeclaration, EveryStageHasItsKernelWithTheDeclaredQueues) {
    for (const StageDeclaration& stage : stage_declarations) EXPECT_EQ(kernel_file_problem(stage), "") << stage.kernel;
}

// The check above fails on the two mistakes it is there for: a stage added to
// the declaration without a kernel, and a declared push no kernel makes.
TEST(StageDeclaration, KernelCheckFindsAStageWithoutKernelAndAPushNeverMade) {
    StageDeclaration without_kernel{"shade_indirect", StageLoop::CAMERA,   WP_QUEUE_HIT,
                                    bit("RAY"),       PathFeature::ALWAYS, StageTrace::NO_RAYS};
    EXPECT_EQ(kernel_file_problem(without_kernel), "no kernels/shade_indirect.cl");
    StageDeclaration intersect = declaration(Stage::intersect);
    intersect.pushes |= bit("SHADOW");
    EXPECT_EQ(kernel_file_problem(intersect), "kernel intersect pushes to HIT, declared HIT SHADOW");
}

TEST(StageDeclaration, IntersectShadowRunsOnlyWhereShadowRaysHaveTheirOwnStage) {
    FeatureSet features;
    features.spheres = features.diffuse = true;
    const std::vector<Stage> without_shadow_stage{Stage::generate, Stage::intersect, Stage::shade};
    features.shadow_stage = true;
    EXPECT_EQ(iteration_stages(features), without_shadow_stage);  // no next-event estimation
    features.nee = true;
    features.shadow_stage = false;
    EXPECT_EQ(iteration_stages(features), without_shadow_stage);  // shade traces them
    features.shadow_stage = true;
    const std::vector<Stage> with_nee{Stage::generate, Stage::intersect, Stage::shade, Stage::intersect_shadow};
    EXPECT_EQ(iteration_stages(features), with_nee);
    EXPECT_TRUE(iteration_stages(features, StageLoop::PHOTON).empty());
    features.sppm = true;  // the camera pass is path tracing's; the photon pass runs its own loop
    EXPECT_EQ(iteration_stages(features), with_nee);
    const std::vector<Stage> photons{Stage::emit_photons, Stage::intersect_photons, Stage::shade_photons};
    EXPECT_EQ(iteration_stages(features, StageLoop::PHOTON), photons);
}

// intersect_and_shade takes intersect's and shade's places, whether or not
// the shadow rays have their own stage.
TEST(StageDeclaration, IntersectAndShadeReplacesIntersectThenShade) {
    FeatureSet features;
    features.spheres = features.diffuse = features.nee = true;
    features.intersect_and_shade = true;
    const std::vector<Stage> in_shade{Stage::generate, Stage::intersect_and_shade};
    EXPECT_EQ(iteration_stages(features), in_shade);
    features.shadow_stage = true;
    const std::vector<Stage> own_stage{Stage::generate, Stage::intersect_and_shade, Stage::intersect_shadow};
    EXPECT_EQ(iteration_stages(features), own_stage);
}

// Where the host traces (--intersector embree), a stage that traces leaves
// the tracing to it: its kernel has a WP_HOST_TRACED branch, and no other
// kernel has one. What the host writes for it is read, by its kernel or by
// that of a stage it pushes to (intersect's hits by shade).
TEST(StageDeclaration, TracingStagesReadTheHostsResultsWhereItTraces) {
    auto source_of = [](const StageDeclaration& stage) {
        return test::read_text(test::kKernelDirectory / (std::string(stage.kernel) + ".cl"));
    };
    auto code_of = [](const StageDeclaration& stage) {  // with the kernel headers it includes
        return test::kernel_code_with_includes(std::string(stage.kernel) + ".cl");
    };
    for (const StageDeclaration& stage : stage_declarations) {
        const std::string source = source_of(stage);
        EXPECT_EQ(source.find("WP_HOST_TRACED") != std::string::npos, stage.traces != StageTrace::NO_RAYS)
            << stage.kernel;
        const std::vector<std::string> written = host_trace_fields(stage.traces).writes;
        EXPECT_EQ(written.empty(), stage.traces == StageTrace::NO_RAYS) << stage.kernel;
        if (stage.traces == StageTrace::NO_RAYS) continue;
        std::string readers = code_of(stage);
        for (const StageDeclaration& next : stage_declarations)
            if (stage.pushes >> next.consumes & 1u) readers += code_of(next);
        EXPECT_TRUE(std::any_of(written.begin(), written.end(), [&](const std::string& field) {
            return readers.find("PATH_READ(" + field) != std::string::npos;
        })) << stage.kernel;
    }
    EXPECT_EQ(declaration(Stage::intersect).traces, StageTrace::CLOSEST_HIT);
    EXPECT_EQ(declaration(Stage::intersect_and_shade).traces, StageTrace::CLOSEST_HIT);
    EXPECT_EQ(declaration(Stage::intersect_shadow).traces, StageTrace::ANY_HIT);
}

// The queue bookkeeping of the iteration `features` run (plan_queues),
// looked up by stage: of(Stage::shade).built_after.
struct PlannedIteration {
    QueuePlan plan;
    const StageBookkeeping& operator()(Stage stage) const { return plan[static_cast<std::size_t>(stage)]; }
};

PlannedIteration planned(const FeatureSet& features, std::uint32_t entries_read = 0) {
    return {plan_queues(iteration_stages(features), entries_read)};
}

// The bookkeeping derived from the declaration (and docs/architecture.md
// describes): scan compaction builds RAY after generate, HIT after
// intersect, and FREE after shade, with SHADOW where intersect_shadow takes
// it; it only counts RAY after shade (generate adds to it before intersect
// reads it) and SHADOW where no stage takes it; nothing after
// intersect_shadow. It clears a queue's marks where it is built or counted
// for the last time before its consumer (SHADOW after shade whether
// intersect_shadow takes it or no stage does). Atomic pushes empty HIT
// before intersect, FREE, SHADOW and RAY before shade.
TEST(StageDeclaration, QueueBookkeepingFollowsFromTheDeclaration) {
    for (bool shadow_stage : {true, false}) {
        SCOPED_TRACE(shadow_stage ? "with a shadow stage" : "shade traces the shadow rays, or there are none");
        FeatureSet features;
        features.nee = features.shadow_stage = shadow_stage;
        const PlannedIteration of = planned(features);
        EXPECT_EQ(queue_names(of(Stage::generate).built_after), "RAY");
        EXPECT_EQ(queue_names(of(Stage::intersect).built_after), "HIT");
        EXPECT_EQ(queue_names(of(Stage::shade).built_after), shadow_stage ? "FREE SHADOW" : "FREE");
        EXPECT_EQ(queue_names(of(Stage::intersect_shadow).built_after), "");
        EXPECT_EQ(queue_names(of(Stage::generate).counted_after), "");
        EXPECT_EQ(queue_names(of(Stage::intersect).counted_after), "");
        EXPECT_EQ(queue_names(of(Stage::shade).counted_after), shadow_stage ? "RAY" : "RAY SHADOW");
        EXPECT_EQ(queue_names(of(Stage::intersect_shadow).counted_after), "");
        EXPECT_EQ(queue_names(of(Stage::generate).marks_cleared_after), "RAY");
        EXPECT_EQ(queue_names(of(Stage::intersect).marks_cleared_after), "HIT");
        EXPECT_EQ(queue_names(of(Stage::shade).marks_cleared_after), "FREE SHADOW");  // not RAY: generate adds to it
        EXPECT_EQ(queue_names(of(Stage::intersect_shadow).marks_cleared_after), "");
        EXPECT_EQ(queue_names(of(Stage::generate).counts_cleared_before), "");
        EXPECT_EQ(queue_names(of(Stage::intersect).counts_cleared_before), "HIT");
        EXPECT_EQ(queue_names(of(Stage::shade).counts_cleared_before), "FREE RAY SHADOW");
        EXPECT_EQ(queue_names(of(Stage::intersect_shadow).counts_cleared_before), "");
    }
}

// What --profile's rays by depth reads (SHADOW's entries) is built even where
// no stage consumes it; the rest of the plan is as without it.
TEST(StageDeclaration, QueuesReadByTheProfileAreBuilt) {
    FeatureSet features;
    features.nee = true;
    const PlannedIteration of = planned(features, 1u << WP_QUEUE_SHADOW);
    EXPECT_EQ(queue_names(of(Stage::shade).built_after), "FREE SHADOW");
    EXPECT_EQ(queue_names(of(Stage::shade).counted_after), "RAY");
    EXPECT_EQ(queue_names(of(Stage::shade).marks_cleared_after), "FREE SHADOW");
    EXPECT_EQ(queue_names(of(Stage::generate).built_after), "RAY");
}

// intersect_and_shade takes RAY and pushes to it: scan compaction counts RAY
// after it (for the iteration's count) without clearing its marks, which
// generate adds to, and builds it after generate, clearing the marks there,
// where RAY is built for the last time before the stage reads it.
TEST(StageDeclaration, QueueBookkeepingOfIntersectAndShade) {
    FeatureSet features;
    features.nee = features.intersect_and_shade = true;
    const PlannedIteration of = planned(features);
    EXPECT_EQ(queue_names(of(Stage::generate).built_after), "RAY");
    EXPECT_EQ(queue_names(of(Stage::generate).marks_cleared_after), "RAY");
    EXPECT_EQ(queue_names(of(Stage::intersect_and_shade).built_after), "FREE");
    EXPECT_EQ(queue_names(of(Stage::intersect_and_shade).counted_after), "RAY SHADOW");
    EXPECT_EQ(queue_names(of(Stage::intersect_and_shade).marks_cleared_after), "FREE SHADOW");
    EXPECT_EQ(queue_names(of(Stage::intersect).built_after), "");  // not in the iteration
    EXPECT_EQ(queue_names(of(Stage::shade).built_after), "");
}

// docs/architecture.md's table of stages ("Stages and queues") has a row per
// stage, in the declaration's order, naming the queue it consumes and exactly
// the queues it pushes to.
TEST(StageDeclaration, ArchitectureDocTableStatesTheDeclaration) {
    const std::string doc = test::read_text(WAVEPATH_SOURCE_DIR "/docs/architecture.md");
    static const std::regex row(R"(\n\| [^|\n]* \| `(\w+)\.cl` \| ([^|\n]*) \| ([^|\n]*) \|)");
    std::vector<std::string> rows;
    for (std::sregex_iterator m(doc.begin(), doc.end(), row), end; m != end; ++m) {
        const std::string kernel = (*m)[1];
        auto stage = std::find_if(stage_declarations.begin(), stage_declarations.end(),
                                  [&](const StageDeclaration& s) { return s.kernel == kernel; });
        if (stage == stage_declarations.end()) continue;  // compact.cl, accumulate.cl
        rows.push_back(kernel);
        EXPECT_EQ(queue_names(queues_named_in((*m)[2])), queue_names(1u << stage->consumes)) << kernel;
        EXPECT_EQ(queue_names(queues_named_in((*m)[3])), queue_names(stage->pushes)) << kernel;
    }
    std::vector<std::string> declared;
    for (const StageDeclaration& stage : stage_declarations) declared.push_back(stage.kernel);
    EXPECT_EQ(rows, declared);
}

}  // namespace
}  // namespace wp
