// The ranks of an MPI job (built only with the WAVEPATH_MPI CMake option).
#pragma once

#include <memory>

#include "distributed/ranks.h"

namespace wp {

// Initialises MPI (only the calling thread makes MPI calls); MPI is finalised
// when the returned object is destroyed.
std::unique_ptr<Ranks> make_mpi_ranks();

}  // namespace wp
