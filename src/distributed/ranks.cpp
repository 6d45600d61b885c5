#include "distributed/ranks.h"

#include <cstdlib>
#include <stdexcept>
#include <string>

#ifdef WAVEPATH_MPI
#include "distributed/mpi_ranks.h"
#endif

namespace wp {

namespace {

// The number of ranks a launcher announces (Open MPI's mpirun, or a PMI/PMIx
// launcher such as srun), 0 when none started this process.
int launched_ranks() {
    for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "PMI_SIZE"})
        if (const char* value = std::getenv(variable)) return std::atoi(value);
    return std::getenv("PMIX_RANK") || std::getenv("PMI_RANK") ? 1 : 0;
}

}  // namespace

void SingleProcess::abort(int exit_code) { std::_Exit(exit_code); }

bool built_with_mpi() {
#ifdef WAVEPATH_MPI
    return true;
#else
    return false;
#endif
}

std::unique_ptr<Ranks> join_ranks() {
    const int launched = launched_ranks();
    if (launched == 0) return std::make_unique<SingleProcess>();
#ifdef WAVEPATH_MPI
    return make_mpi_ranks();
#else
    if (launched > 1)
        throw std::runtime_error("started as one of " + std::to_string(launched) +
                                 " MPI ranks, but this wavepath was built without MPI (the WAVEPATH_MPI CMake "
                                 "option): each rank would render the whole image");
    return std::make_unique<SingleProcess>();
#endif
}

ItemRange share_of(const ItemRange& items, int rank, int ranks) {
    const auto boundary = [&](int r) {
        // size * r / ranks without overflow: size < 2^64, r <= ranks < 2^31.
        return items.begin + std::uint64_t((unsigned __int128)items.size() * unsigned(r) / unsigned(ranks));
    };
    return {boundary(rank), boundary(rank + 1)};
}

}  // namespace wp
