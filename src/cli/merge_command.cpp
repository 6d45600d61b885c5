#include "cli/merge_command.h"

#include <algorithm>
#include <iostream>

#include "core/atomic_file.h"
#include "image/image_io.h"
#include "longrun/film_file.h"

namespace wp::cli {

namespace {

struct NamedFilm {
    std::string path;
    FilmFile file;
};

// Every film made by the first one's render, sorted by their ranges.
std::vector<NamedFilm> read_partials(const std::vector<std::string>& paths) {
    std::vector<NamedFilm> films;
    for (const std::string& path : paths) {
        films.push_back({path, read_film_file(path)});
        if (films.back().file.film.in_round())
            throw FilmFileError(path +
                                ": rendered with --adaptive, whose pixels have their own sample counts: "
                                "it cannot be merged");
        const FilmFile& first = films.front().file;
        check_film_matches(path, films.back().file, first.identity, first.film.width, first.film.height);
    }
    std::stable_sort(films.begin(), films.end(), [](const NamedFilm& a, const NamedFilm& b) {
        return a.file.film.items.begin < b.file.film.items.begin;
    });
    return films;
}

std::string samples_range(const Film& film) {
    const std::uint64_t pixels = film.pixel_count();
    return "work items " + std::to_string(film.items.begin) + " to " + std::to_string(film.items.end) + " (" +
           std::to_string(film.min_samples()) +
           (film.min_samples() == film.max_samples() ? "" : "-" + std::to_string(film.max_samples())) +
           " samples per pixel, " + std::to_string(pixels) + " pixels)";
}

}  // namespace

void add_merge_options(CLI::App& merge, MergeCommand& command) {
    merge.add_option("partials", command.partials, "Film files (.wpfilm) of adjacent sample ranges, in any order")
        ->required();
    merge
        .add_option("-o,--output", command.output_path,
                    "Output image (.exr .pfm .hdr .png .jpg), or a merged film (.wpfilm)")
        ->required();
    merge.add_flag("-q,--quiet", command.quiet, "No summary on stderr (errors still appear)");
}

void run_merge(const MergeCommand& command) {
    if (is_film_path(command.output_path))
        check_writable_destination(command.output_path);
    else
        validate_output_path(command.output_path);
    std::vector<NamedFilm> films = read_partials(command.partials);
    // Squares are kept only if every film has them.
    const bool squares =
        std::all_of(films.begin(), films.end(), [](const NamedFilm& f) { return !f.file.film.squares.empty(); });
    for (NamedFilm& f : films)
        if (!squares) f.file.film.squares.clear();
    Film merged = films.front().file.film;
    for (std::size_t i = 1; i < films.size(); ++i) {
        const Film& next = films[i].file.film;
        if (next.items.begin != merged.items.end)
            throw FilmFileError(films[i].path + ": starts at work item " + std::to_string(next.items.begin) +
                                " but the films before it end at " + std::to_string(merged.items.end) +
                                (next.items.begin > merged.items.end ? " (a gap)" : " (an overlap)"));
        merged.append(next);
    }
    if (is_film_path(command.output_path))
        write_film_file(command.output_path, {films.front().file.identity, merged});
    else
        write_image(merged.image(), command.output_path);
    if (!command.quiet)
        std::cerr << "wavepath: merged " << films.size() << " films into " << command.output_path << ": "
                  << samples_range(merged) << std::endl;
}

}  // namespace wp::cli
