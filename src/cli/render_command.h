// `wavepath render`: load, override, render, write, report.
#pragma once

#include "cli/options.h"

namespace wp::cli {

// Checks every output path (and a checkpoint to resume) before the render,
// so that a typo costs seconds, not a render. Throws SceneError,
// FilmFileError, UsageError, OutputError or the backend's exception; a
// failure leaves no output file behind. Returns kExitOk, or
// kExitInterrupted when a signal stopped the render (the image of the
// samples so far is written).
int run_render(const RenderCommand& command);

}  // namespace wp::cli
