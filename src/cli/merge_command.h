// `wavepath merge PARTIALS... -o OUT`: adds partial films (from `render
// --samples A:B`, or checkpoints) of adjacent sample ranges into one film and
// writes its image, bit-identical to the one-process render of the union, or
// the merged film itself when OUT ends in .wpfilm.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace wp::cli {

struct MergeCommand {
    std::vector<std::string> partials;
    std::string output_path;
    bool quiet = false;
};

void add_merge_options(CLI::App& merge, MergeCommand& command);

// Throws FilmFileError (exit 3) for a film that cannot be read, was made by
// another render, or leaves a gap or an overlap; OutputError for the output.
void run_merge(const MergeCommand& command);

}  // namespace wp::cli
