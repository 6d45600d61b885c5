#include "cli/errors.h"

#include <algorithm>
#include <iostream>
#include <new>
#include <string_view>

#include "core/atomic_file.h"
#include "longrun/film_file.h"
#include "scene/scene.h"

namespace wp::cli {

namespace {

// Bytes of a valid UTF-8 sequence starting at text[i] (1 to 4), or 0.
std::size_t utf8_sequence_length(std::string_view text, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char lead = byte(i);
    std::size_t length = lead < 0x80                   ? 1
                         : lead >= 0xC2 && lead < 0xE0 ? 2
                         : lead >= 0xE0 && lead < 0xF0 ? 3
                         : lead >= 0xF0 && lead < 0xF5 ? 4
                                                       : 0;
    if (length == 0 || i + length > text.size()) return 0;
    for (std::size_t k = 1; k < length; ++k) {
        if ((byte(i + k) & 0xC0) != 0x80) return 0;
    }
    // Overlong forms, UTF-16 surrogates and code points beyond U+10FFFF.
    const unsigned char second = length > 1 ? byte(i + 1) : 0;
    if ((lead == 0xE0 && second < 0xA0) || (lead == 0xED && second >= 0xA0) || (lead == 0xF0 && second < 0x90) ||
        (lead == 0xF4 && second >= 0x90))
        return 0;
    return length;
}

// One printable line: messages quote file names, file contents and parser
// tokens, which may hold newlines, terminal escapes or bytes that are not
// UTF-8. Newlines fold into "; "; other control characters and invalid UTF-8
// bytes become \xNN; valid UTF-8 (non-ASCII file names) stays as it is.
std::string printable_line(std::string_view message) {
    while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.remove_suffix(1);
    std::string line;
    for (std::size_t i = 0; i < message.size();) {
        const unsigned char c = static_cast<unsigned char>(message[i]);
        const std::size_t length = utf8_sequence_length(message, i);
        if (c == '\n') {
            line += "; ";
        } else if (length == 0 || c < 0x20 || c == 0x7F) {
            static constexpr char kHex[] = "0123456789abcdef";
            line += {'\\', 'x', kHex[c >> 4], kHex[c & 15]};
        } else {
            line += message.substr(i, length);
        }
        i += std::max<std::size_t>(length, 1);
    }
    return line;
}

struct Failure {
    int exit_code;
    std::string message;
    bool reported = false;  // AlreadyReported
};

Failure classify(const std::exception_ptr& error) {
    try {
        std::rethrow_exception(error);
    } catch (const AlreadyReported& e) {
        return {e.exit_code(), "", true};
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
    std::cerr << "wavepath: error: " << printable_line(message) << std::endl;
}

}  // namespace

int report_error(const std::exception_ptr& error, const std::string& where) {
    const Failure failure = classify(error);
    if (!failure.reported) print_error_line(where + failure.message);
    return failure.exit_code;
}

int exit_code_of(const std::exception_ptr& error) { return classify(error).exit_code; }

int report_parse_error(const CLI::App& app, const CLI::ParseError& error) {
    if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(error);  // --help
    std::string help_command = "wavepath";
    for (const CLI::App* subcommand : app.get_subcommands()) help_command += " " + subcommand->get_name();
    print_error_line(std::string(error.what()) + " (see " + help_command + " --help)");
    return kExitUsage;
}

}  // namespace wp::cli
