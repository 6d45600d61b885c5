#include "cli/backends.h"

#include <algorithm>
#include <array>

#include "cli/errors.h"
#include "cli/flag_checks.h"
#include "reference/reference_renderer.h"

namespace wp::cli {

namespace {

constexpr int kMaxThreads = 4096;

using RenderFn = RenderResult (*)(const Scene&, const BackendOptions&, const ProgressFn&);

struct Backend {
    const char* name;
    const char* description;
    RenderFn render;
};

RenderResult render_on_reference(const Scene& scene, const BackendOptions& options, const ProgressFn& progress) {
    return render_reference(scene, ReferenceOptions{options.threads, options.precision == "double"}, progress);
}

constexpr std::array<Backend, 1> kBackends{{
    {"reference", "scalar C++ path tracer on the CPU threads", render_on_reference},
}};

std::string backend_help() {
    std::string help = "Renderer:";
    for (const Backend& backend : kBackends) help += std::string(" ") + backend.name + " (" + backend.description + ")";
    return help;
}

}  // namespace

std::vector<std::string> backend_names() {
    std::vector<std::string> names;
    for (const Backend& backend : kBackends) names.emplace_back(backend.name);
    return names;
}

void add_backend_options(CLI::App& render, BackendOptions& options) {
    render.add_option("--backend", options.name, backend_help())
        ->check(CLI::IsMember(backend_names()))
        ->capture_default_str();
    render.add_option("--threads", options.threads, "CPU threads for the reference backend (0: all)")
        ->check(integer_in(0, kMaxThreads))
        ->capture_default_str();
    render.add_option("--precision", options.precision, "Arithmetic of the reference backend")
        ->check(CLI::IsMember({"float", "double"}))
        ->capture_default_str();
}

RenderResult render_with_backend(const Scene& scene, const BackendOptions& options, const ProgressFn& progress) {
    const auto backend = std::find_if(kBackends.begin(), kBackends.end(),
                                      [&](const Backend& candidate) { return options.name == candidate.name; });
    if (backend == kBackends.end()) throw UsageError("--backend: unknown backend '" + options.name + "'");
    return backend->render(scene, options, progress);
}

}  // namespace wp::cli
