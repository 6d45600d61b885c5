// `wavepath render`: load, override, render, write, report.
#pragma once

#include "cli/options.h"

namespace wp::cli {

// Checks every output path before the render, so that a typo costs
// seconds, not a render. Throws SceneError, UsageError, OutputError or the
// backend's exception; a failure leaves no output file behind.
void run_render(const RenderCommand& command);

}  // namespace wp::cli
