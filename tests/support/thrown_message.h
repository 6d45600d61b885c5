// The message an error of a given type carries, for tests of error lines.
#pragma once

#include <string>
#include <utility>

namespace wp::test {

// The what() of the `Error` that `call()` throws, or `if_none` if it returns.
template <class Error, class Call>
std::string thrown_message(Call&& call, const std::string& if_none = "(none)") {
    try {
        std::forward<Call>(call)();
    } catch (const Error& error) {
        return error.what();
    }
    return if_none;
}

}  // namespace wp::test
