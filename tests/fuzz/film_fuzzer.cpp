// libFuzzer target: bytes -> a film file (checkpoints and partial films), or
// the one FilmFileError naming the file. A film that loads is then checked
// against a render and turned into an image, as --resume and merge do.
// Anything else (another exception, a crash, a sanitizer report, a hang, a
// huge allocation) is a finding. Each input is read twice: as it is, and
// with its last 8 bytes replaced by the checksum of the others, so that the
// fuzzer reaches the checks after the checksum's (it cannot forge FNV-1a).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "longrun/film_file.h"

namespace {

const std::string kPath = "fuzz.wpfilm";

void read_film(const std::vector<char>& bytes) {
    try {
        const wp::FilmFile file = wp::parse_film_file(bytes, kPath);
        wp::check_film_matches(kPath, file, file.identity, file.film.width, file.film.height);
        const wp::Film& film = file.film;
        if (film.min_samples() > film.max_samples()) std::abort();
        if (film.image().rgb.size() != film.sums.size()) std::abort();
    } catch (const wp::FilmFileError& error) {
        // "<path>: <problem>"
        if (std::string(error.what()).rfind(kPath + ": ", 0) != 0) std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<char> bytes(reinterpret_cast<const char*>(data), reinterpret_cast<const char*>(data) + size);
    read_film(bytes);
    if (size >= 8) {
        const std::uint64_t checksum = wp::fnv1a64(bytes.data(), size - 8);
        std::memcpy(bytes.data() + size - 8, &checksum, sizeof checksum);
        read_film(bytes);
    }
    return 0;
}
