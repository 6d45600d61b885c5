#include "cli/errors.h"

#include <iostream>
#include <new>

#include "core/atomic_file.h"
#include "longrun/film_file.h"
#include "scene/scene.h"

namespace wp::cli {

namespace {

std::string one_line(std::string message) {
    while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
    std::string line;
    for (char c : message) line += c == '\n' ? std::string("; ") : std::string(1, c);
    return line;
}

struct Failure {
    int exit_code;
    std::string message;
};

Failure classify(const std::exception_ptr& error) {
    try {
        std::rethrow_exception(error);
    } catch (const UsageError& e) {
        return {kExitUsage, e.what()};
    } catch (const SceneError& e) {
        return {kExitScene, e.what()};
    } catch (const FilmFileError& e) {
        return {kExitScene, e.what()};
    } catch (const OutputError& e) {
        return {kExitOutput, e.what()};
    } catch (const std::bad_alloc&) {
        return {kExitRuntime, "out of memory"};
    } catch (const std::exception& e) {
        return {kExitRuntime, e.what()};
    } catch (...) {
        return {kExitRuntime, "unknown failure"};
    }
}

void print_error_line(const std::string& message) {
    std::cerr << "wavepath: error: " << one_line(message) << std::endl;
}

}  // namespace

int report_error(const std::exception_ptr& error) {
    const Failure failure = classify(error);
    print_error_line(failure.message);
    return failure.exit_code;
}

int report_parse_error(const CLI::App& app, const CLI::ParseError& error) {
    if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(error);  // --help
    std::string help_command = "wavepath";
    for (const CLI::App* subcommand : app.get_subcommands()) help_command += " " + subcommand->get_name();
    print_error_line(std::string(error.what()) + " (see " + help_command + " --help)");
    return kExitUsage;
}

}  // namespace wp::cli
