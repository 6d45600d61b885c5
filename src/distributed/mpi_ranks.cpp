#include "distributed/mpi_ranks.h"

// The C API only: Open MPI's C++ bindings are deprecated (and warn).
#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <algorithm>
#include <cstdlib>

namespace wp {

namespace {

// Any MPI error ends the job: MPI_ERRORS_ARE_FATAL, the default on
// MPI_COMM_WORLD, which also ends it when a rank dies.
class MpiRanks final : public Ranks {
 public:
    MpiRanks() {
        int provided = 0;
        MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &size_);
    }
    ~MpiRanks() override { MPI_Finalize(); }
    MpiRanks(const MpiRanks&) = delete;
    MpiRanks& operator=(const MpiRanks&) = delete;

    int rank() const override { return rank_; }
    int size() const override { return size_; }

    bool any(bool local) override {
        int value = local ? 1 : 0, result = 0;
        MPI_Allreduce(&value, &result, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
        return result != 0;
    }

    std::vector<std::uint64_t> gather(const std::vector<std::uint64_t>& values) override {
        std::vector<std::uint64_t> all(is_root() ? values.size() * std::size_t(size_) : 0);
        MPI_Gather(values.data(), int(values.size()), MPI_UINT64_T, all.data(), int(values.size()), MPI_UINT64_T, 0,
                   MPI_COMM_WORLD);
        return all;
    }

    void sum_films_to_root(Film& film) override {
        if (!is_root()) {
            send(film.sums);
            send(film.squares);
            return;
        }
        Film other = film;
        for (int from = 1; from < size_; ++from) {
            receive(other.sums, from);
            receive(other.squares, from);
            film.add_sums(other);
        }
    }

    [[noreturn]] void abort(int exit_code) override {
        MPI_Abort(MPI_COMM_WORLD, exit_code);
        std::_Exit(exit_code);  // MPI_Abort does not return; this is for the compiler
    }

 protected:
    void broadcast_bytes(void* data, std::size_t size) override {
        MPI_Bcast(data, int(size), MPI_BYTE, 0, MPI_COMM_WORLD);
    }

 private:
    // Films may exceed an int's count of bytes: sent in chunks.
    static constexpr std::size_t kChunkBytes = std::size_t(1) << 30;

    void send(const std::vector<film_sum>& sums) {
        const char* bytes = reinterpret_cast<const char*>(sums.data());
        for (std::size_t at = 0, size = sums.size() * sizeof(film_sum); at < size; at += kChunkBytes)
            MPI_Send(bytes + at, int(std::min(kChunkBytes, size - at)), MPI_BYTE, 0, 0, MPI_COMM_WORLD);
    }

    void receive(std::vector<film_sum>& sums, int from) {
        char* bytes = reinterpret_cast<char*>(sums.data());
        for (std::size_t at = 0, size = sums.size() * sizeof(film_sum); at < size; at += kChunkBytes)
            MPI_Recv(bytes + at, int(std::min(kChunkBytes, size - at)), MPI_BYTE, from, 0, MPI_COMM_WORLD,
                     MPI_STATUS_IGNORE);
    }

    int rank_ = 0, size_ = 1;
};

}  // namespace

std::unique_ptr<Ranks> make_mpi_ranks() { return std::make_unique<MpiRanks>(); }

}  // namespace wp
