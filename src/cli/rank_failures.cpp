#include "cli/rank_failures.h"

#include <string>

#include "cli/errors.h"

namespace wp::cli {

namespace {

std::string rank_prefix(const Ranks& ranks) {
    return ranks.is_root() ? "" : "rank " + std::to_string(ranks.rank()) + ": ";
}

}  // namespace

void on_every_rank(Ranks& ranks, const std::function<void()>& step) {
    std::exception_ptr failure;
    try {
        step();
    } catch (...) {
        failure = std::current_exception();
    }
    if (ranks.size() == 1) {
        if (failure) std::rethrow_exception(failure);
        return;
    }
    // The first failing rank and its exit code, as the root sees them.
    struct Verdict {
        int rank = -1, exit_code = 0;
    };
    const std::vector<std::uint64_t> codes = ranks.gather({std::uint64_t(failure ? exit_code_of(failure) : 0)});
    const Verdict verdict = ranks.root_decides([&] {
        Verdict first;
        for (std::size_t r = 0; r < codes.size() && first.rank < 0; ++r)
            if (codes[r] != 0) first = {int(r), int(codes[r])};
        return first;
    });
    if (verdict.rank < 0) return;
    if (verdict.rank == ranks.rank()) report_error(failure, rank_prefix(ranks));
    throw AlreadyReported(verdict.exit_code);
}

void or_end_the_job(Ranks& ranks, const std::function<void()>& step) {
    if (ranks.size() == 1) return step();
    try {
        step();
    } catch (...) {
        ranks.abort(report_error(std::current_exception(), rank_prefix(ranks)));
    }
}

}  // namespace wp::cli
