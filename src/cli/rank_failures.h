// Failures on MPI ranks: every rank must end the job with one error line and
// the same exit code, and none may wait for a rank that has given up.
#pragma once

#include <functional>

#include "distributed/ranks.h"

namespace wp::cli {

// Runs `step` on every rank; a step must not wait for other ranks (they may
// have failed before). When it threw on any rank, every rank throws: the
// first failing rank (in rank order) reports its error (with "rank N: "
// unless it is the root) and the others throw AlreadyReported with its exit
// code. In one process, the step's own exception.
void on_every_rank(Ranks& ranks, const std::function<void()>& step);

// Runs `step`, which waits for the other ranks. A failure on one of several
// ranks is reported (with "rank N: ") and ends the whole job with its exit
// code at once: the other ranks would wait for this one for ever. In one
// process, the exception passes.
void or_end_the_job(Ranks& ranks, const std::function<void()>& step);

}  // namespace wp::cli
