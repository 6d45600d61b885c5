// How the command line reports failures: one line on stderr and an exit
// code that tells scripts what kind of thing went wrong.
#pragma once

#include <CLI/CLI.hpp>
#include <exception>
#include <stdexcept>
#include <string>

namespace wp::cli {

enum ExitCode : int {
    kExitOk = 0,
    kExitRuntime = 1,  // the render failed (including OpenCL errors)
    kExitUsage = 2,    // bad command-line flags
    kExitScene = 3,    // the scene file is missing or invalid
    kExitOutput = 4,   // the image or stats file cannot be written
    // SIGINT or SIGTERM stopped the render: the image of the samples so far
    // (and the checkpoint, if asked for) was written (cli/signals.h).
    kExitInterrupted = 5,
};

// A flag value that is well-formed but not acceptable, found after parsing
// (e.g. --width that makes too many pixels with the scene's height).
class UsageError : public std::runtime_error {
 public:
    using std::runtime_error::runtime_error;
};

// A failure that was already reported (on another MPI rank, or on this one
// with its rank): report_error prints nothing and returns its exit code.
class AlreadyReported : public std::exception {
 public:
    explicit AlreadyReported(int exit_code) : exit_code_(exit_code) {}
    int exit_code() const { return exit_code_; }
    const char* what() const noexcept override { return "already reported"; }

 private:
    int exit_code_;
};

// Prints "wavepath: error: <where><message>" (newlines in the message folded so it
// stays one line; other control characters and bytes that are not UTF-8 as
// \xNN) and returns the exit code for the exception's kind (film files that
// cannot be used: kExitScene).
int report_error(const std::exception_ptr& error, const std::string& where = "");

// The exit code report_error would return, without printing.
int exit_code_of(const std::exception_ptr& error);

// --help prints the help and returns 0; any other parse error is reported as
// one line and returns kExitUsage.
int report_parse_error(const CLI::App& app, const CLI::ParseError& error);

}  // namespace wp::cli
