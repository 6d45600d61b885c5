// The processes of one render: one alone, or the ranks of an MPI job
// (`mpirun -n N wavepath render ...`, docs/long-renders.md, "MPI"). Rank 0 is
// the root: it decides what every rank does next (stop, checkpoint), so all
// ranks take the same decisions, and it writes every file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <vector>

#include "core/film.h"

namespace wp {

class Ranks {
 public:
    virtual ~Ranks() = default;

    virtual int rank() const = 0;
    virtual int size() const = 0;
    bool is_root() const { return rank() == 0; }

    // True on every rank when it is true on any.
    virtual bool any(bool local) = 0;
    // The root's `value` on every rank.
    template <class T>
    void broadcast(T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        broadcast_bytes(&value, sizeof value);
    }
    // The root's `values` (adaptive sampling's round) on every rank.
    template <class T>
    void broadcast(std::vector<T>& values) {
        static_assert(std::is_trivially_copyable_v<T>);
        std::uint64_t size = values.size();
        broadcast(size);
        values.resize(size);
        if (size > 0) broadcast_bytes(values.data(), size * sizeof(T));
    }
    // The root decides, every rank follows: `decide()` runs on the root
    // alone, and every rank returns the root's result (a trivially copyable
    // value or a vector of them, broadcast). Like every call here it is a
    // collective: each rank makes it at the same point, so a branch on its
    // result is taken alike everywhere, and what only the root knows (its
    // clock, the summed films) reaches every rank only through it.
    template <class Decide>
    std::invoke_result_t<Decide&> root_decides(Decide&& decide) {
        std::invoke_result_t<Decide&> decision{};
        if (is_root()) decision = decide();
        broadcast(decision);
        return decision;
    }
    // Every rank's `values` (each rank passes as many), in rank order, on the
    // root; empty elsewhere.
    virtual std::vector<std::uint64_t> gather(const std::vector<std::uint64_t>& values) = 0;
    // Adds every other rank's film sums (and squares) into the root's `film`,
    // rank 1 first, then 2, and so on: a fixed order, although exact sums
    // give the same bits in any. Every film has the same size and squares.
    virtual void sum_films_to_root(Film& film) = 0;
    // Ends every rank of the job at once with `exit_code` (after a failure
    // on this rank that the others cannot learn of: they may be waiting on it).
    [[noreturn]] virtual void abort(int exit_code) = 0;

 protected:
    virtual void broadcast_bytes(void* data, std::size_t size) = 0;
};

// A render in one process: rank 0 of 1.
class SingleProcess final : public Ranks {
 public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    bool any(bool local) override { return local; }
    std::vector<std::uint64_t> gather(const std::vector<std::uint64_t>& values) override { return values; }
    void sum_films_to_root(Film&) override {}
    [[noreturn]] void abort(int exit_code) override;

 protected:
    void broadcast_bytes(void*, std::size_t) override {}
};

// Whether this build can run as MPI ranks (the WAVEPATH_MPI CMake option).
bool built_with_mpi();

// The ranks of an MPI job when mpirun (or another launcher setting the
// PMI/PMIx environment) started this process, else a SingleProcess. Throws
// std::runtime_error when launched as several ranks by a build without MPI
// (each would render the whole image).
std::unique_ptr<Ranks> join_ranks();

// Rank `rank` of `ranks`' share of `items`: the ranks split it in contiguous
// parts, in rank order, whose sizes differ by at most one work item.
ItemRange share_of(const ItemRange& items, int rank, int ranks);

}  // namespace wp
