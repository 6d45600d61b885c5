// wavepath command line: subcommands `render`, `merge`, `convert`, `devices` and `version`. Exit codes are
// listed in cli/errors.h (and docs/usage.md).
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "cli/convert_command.h"
#include "cli/errors.h"
#include "cli/merge_command.h"
#include "cli/render_command.h"
#include "opencl/device.h"

int main(int argc, char** argv) {
    using namespace wp::cli;
    CLI::App app{"wavepath: a physically based Monte Carlo path tracer", "wavepath"};
    // Not require_subcommand(1): CLI11 would then call an unknown subcommand
    // "missing" rather than "not expected"; a missing one is checked below.
    app.require_subcommand(0, 1);

    RenderCommand render_command;
    CLI::App* render = app.add_subcommand("render", "Render a scene file to an image");
    add_render_options(*render, render_command);
    MergeCommand merge_command;
    CLI::App* merge = app.add_subcommand("merge", "Merge partial films (render --samples A:B) into one image");
    add_merge_options(*merge, merge_command);
    ConvertCommand convert_command;
    CLI::App* convert =
        app.add_subcommand("convert", "Write a Mitsuba 3 XML scene as the equivalent wavepath JSON scene");
    add_convert_options(*convert, convert_command);
    CLI::App* version = app.add_subcommand("version", "Print the version");
    CLI::App* devices = app.add_subcommand("devices", "List the OpenCL platforms and devices");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        return report_parse_error(app, error);
    }
    try {
        if (version->parsed()) {
            std::cout << "wavepath " WAVEPATH_VERSION << std::endl;
        } else if (devices->parsed()) {
            std::cout << wp::describe_devices(wp::list_devices()) << std::flush;
        } else if (render->parsed()) {
            return run_render(render_command);
        } else if (merge->parsed()) {
            run_merge(merge_command);
        } else if (convert->parsed()) {
            run_convert(convert_command);
        } else {
            throw UsageError(
                "a subcommand is required: render, merge, convert, devices or version (see wavepath --help)");
        }
        return kExitOk;
    } catch (...) {
        return report_error(std::current_exception());
    }
}
