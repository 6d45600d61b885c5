#include "cli/render_command.h"

#include <iostream>

#include "cli/progress.h"
#include "cli/summary.h"
#include "core/atomic_file.h"
#include "image/image_io.h"

namespace wp::cli {

void run_render(const RenderCommand& command) {
    validate_output_path(command.output_path);
    if (!command.stats_json_path.empty()) check_writable_destination(command.stats_json_path);
    if (!command.backend.profile_json.empty()) check_writable_destination(command.backend.profile_json);

    Scene scene = load_scene(command.scene_path);
    apply_overrides(command.overrides, scene);

    ProgressReporter progress(choose_progress_style(command.quiet), std::cerr);
    const RenderResult result = render_with_backend(scene, command.backend, progress.callback());
    progress.finish();

    write_image(result.image, command.output_path);
    const RunSummary summary{command.backend.name, command.output_path, scene.camera.width,
                             scene.camera.height,  scene.render.spp,    result.stats};
    if (!command.stats_json_path.empty()) write_stats_json(summary, command.stats_json_path);
    if (!command.quiet) std::cerr << format_summary_line(summary) << std::endl;
}

}  // namespace wp::cli
