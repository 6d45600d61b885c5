// wavepath command line entry point.
#include <CLI/CLI.hpp>
#include <iostream>

int main(int argc, char** argv) {
    CLI::App app{"wavepath: a physically based Monte Carlo path tracer"};
    app.require_subcommand(1);
    auto* version = app.add_subcommand("version", "Print the version and exit");
    version->callback([] { std::cout << "wavepath " WAVEPATH_VERSION "\n"; });
    CLI11_PARSE(app, argc, argv);
    return 0;
}
