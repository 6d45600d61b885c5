// libFuzzer target: bytes -> a film file (checkpoints and partial films), or
// the one FilmFileError naming the file. A film that loads is then checked
// against a render and turned into an image, as --resume and merge do.
// Anything else (another exception, a crash, a sanitizer report, a hang, a
// huge allocation) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "longrun/film_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string path = "fuzz.wpfilm";
    try {
        const wp::FilmFile file = wp::parse_film_file(
            std::vector<char>(reinterpret_cast<const char*>(data), reinterpret_cast<const char*>(data) + size), path);
        wp::check_film_matches(path, file, file.identity, file.film.width, file.film.height);
        const wp::Film& film = file.film;
        if (film.min_samples() > film.max_samples()) std::abort();
        if (film.image().rgb.size() != film.sums.size()) std::abort();
    } catch (const wp::FilmFileError& error) {
        // "<path>: <problem>"
        if (std::string(error.what()).rfind(path + ": ", 0) != 0) std::abort();
    }
    return 0;
}
