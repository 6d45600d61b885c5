#include "longrun/film_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

#include "core/atomic_file.h"
#include "scene/limits.h"

namespace wp {

namespace {

constexpr std::array<char, 8> kMagic{'W', 'P', 'F', 'I', 'L', 'M', '\r', '\n'};
constexpr std::size_t kEstimatorBytes = 16;
constexpr std::uint32_t kFlagSquares = 1;
constexpr std::uint32_t kFlagRound = 2;    // version 2 on
constexpr std::uint32_t kFlagPhotons = 4;  // version 3 on
constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8 + kEstimatorBytes + 4 + 4 + 8 + 8 + 4 + 4;
constexpr std::size_t kChecksumBytes = 8;

class Writer {
 public:
    template <class T>
    void put(const T& value) {
        const auto* bytes = reinterpret_cast<const char*>(&value);
        bytes_.insert(bytes_.end(), bytes, bytes + sizeof value);
    }
    void put_bytes(const void* data, std::size_t size) {
        const auto* bytes = static_cast<const char*>(data);
        bytes_.insert(bytes_.end(), bytes, bytes + size);
    }
    std::vector<char>& bytes() { return bytes_; }

 private:
    std::vector<char> bytes_;
};

class Reader {
 public:
    explicit Reader(const std::vector<char>& bytes) : bytes_(bytes) {}
    template <class T>
    T get() {
        T value;
        std::memcpy(&value, bytes_.data() + at_, sizeof value);
        at_ += sizeof value;
        return value;
    }
    void get_bytes(void* data, std::size_t size) {
        if (size == 0) return;  // into an empty vector, whose data() may be null, which memcpy must not get
        std::memcpy(data, bytes_.data() + at_, size);
        at_ += size;
    }

 private:
    const std::vector<char>& bytes_;
    std::size_t at_ = 0;
};

std::vector<char> encode(const FilmFile& file) {
    const Film& film = file.film;
    Writer w;
    w.put_bytes(kMagic.data(), kMagic.size());
    w.put(kFilmFileVersion);
    w.put(std::uint32_t((film.squares.empty() ? 0 : kFlagSquares) | (film.in_round() ? kFlagRound : 0) |
                        (film.photons.empty() ? 0 : kFlagPhotons)));
    w.put(file.identity.scene);
    w.put(file.identity.settings);
    // A name of all 16 bytes has no NUL after it; the reader stops at 16.
    if (file.identity.estimator.size() > kEstimatorBytes)
        throw std::logic_error("estimator name '" + file.identity.estimator + "' is longer than the film file's " +
                               std::to_string(kEstimatorBytes) + " bytes");
    std::array<char, kEstimatorBytes> estimator{};
    std::copy(file.identity.estimator.begin(), file.identity.estimator.end(), estimator.begin());
    w.put_bytes(estimator.data(), estimator.size());
    w.put(std::uint32_t(film.width));
    w.put(std::uint32_t(film.height));
    w.put(film.items.begin);
    w.put(film.items.end);
    w.put(std::uint32_t(WP_FILM_LIMBS));
    w.put(std::uint32_t(WP_FILM_FRACTION_BITS));
    w.put_bytes(film.sums.data(), sizeof(film_sum) * film.sums.size());
    w.put_bytes(film.squares.data(), sizeof(film_sum) * film.squares.size());
    if (film.in_round()) {
        w.put(std::uint32_t(film.round_pixels.size()));
        w.put_bytes(film.round_pixels.data(), sizeof(std::uint32_t) * film.round_pixels.size());
        w.put_bytes(film.samples_before.data(), sizeof(std::uint32_t) * film.samples_before.size());
    }
    if (!film.photons.empty()) {
        const PhotonEstimate& photons = film.photons;
        w.put(photons.photons_per_iteration);
        for (const std::vector<double>* values : {&photons.count, &photons.radius, &photons.footprint, &photons.flux})
            w.put_bytes(values->data(), sizeof(double) * values->size());
    }
    w.put(fnv1a64(w.bytes().data(), w.bytes().size()));
    return std::move(w.bytes());
}

[[noreturn]] void refuse(const std::string& path, const std::string& problem) {
    throw FilmFileError(path + ": " + problem);
}

std::vector<char> read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) refuse(path, "cannot read the film file");
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) refuse(path, "cannot read the film file");
    return bytes;
}

// Magic and version first: a newer version may lay out the rest otherwise.
std::uint32_t check_magic_and_version(const std::string& path, const std::vector<char>& bytes) {
    if (bytes.size() < kMagic.size() || !std::equal(kMagic.begin(), kMagic.end(), bytes.begin()))
        refuse(path, "not a wavepath film file (no WPFILM signature)");
    if (bytes.size() < kMagic.size() + 4) refuse(path, "truncated (" + std::to_string(bytes.size()) + " bytes)");
    std::uint32_t version;
    std::memcpy(&version, bytes.data() + kMagic.size(), sizeof version);
    if (version > kFilmFileVersion)
        refuse(path, "film format version " + std::to_string(version) + " is newer than this wavepath reads (" +
                         std::to_string(kFilmFileVersion) + ")");
    if (version == 0) refuse(path, "film format version 0 does not exist");
    return version;
}

// The adaptive round's table size, from the bytes after the sums (0 if they
// are too few to hold its pixel count: the size check then says truncated).
std::uint64_t round_table_bytes(const std::vector<char>& bytes, std::uint64_t at, std::uint64_t pixels) {
    std::uint32_t n = 0;
    if (bytes.size() >= at + sizeof n) std::memcpy(&n, bytes.data() + at, sizeof n);
    return sizeof n + sizeof(std::uint32_t) * (std::uint64_t(n) + pixels);
}

// An adaptive round as read (after the checksum): its pixels ascending and
// in the film, all holding the same samples before it, and a range of whole
// work items of that round.
void check_round(const std::string& path, const Film& film) {
    const std::vector<std::uint32_t>& round = film.round_pixels;
    if (round.empty() || round.size() > film.pixel_count())
        refuse(path, "corrupted adaptive round (" + std::to_string(round.size()) + " pixels)");
    for (std::size_t i = 0; i < round.size(); ++i)
        if (round[i] >= film.pixel_count() || (i > 0 && round[i] <= round[i - 1]) ||
            film.samples_before[round[i]] != film.samples_before[round[0]])
            refuse(path, "corrupted adaptive round (pixel " + std::to_string(round[i]) + ")");
    for (std::uint32_t before : film.samples_before)
        if (before > std::uint32_t(kMaxSpp))
            refuse(path, "corrupted adaptive round (" + std::to_string(before) + " samples)");
    if (film.items.end > std::uint64_t(kMaxSpp) * round.size())
        refuse(path, "corrupted adaptive round (work items to " + std::to_string(film.items.end) + ")");
}

// The bytes of a photon estimate of `pixels` pixels in a file of `version`
// (the footprints from version 4 on).
std::uint64_t photon_estimate_bytes(std::uint64_t pixels, std::uint32_t version) {
    return sizeof(std::uint64_t) + sizeof(double) * pixels * ((version >= 4 ? 3 : 2) + kFilmChannels);
}

// A photon estimate as read (after the checksum): photons a render may emit,
// counts, radii, footprints and flux finite and not negative, and a pixel of
// radius 0 (no visible point yet) without photons. Version 3 had every
// radius positive from the start.
void check_photons(const std::string& path, const PhotonEstimate& photons, std::uint32_t version) {
    if (photons.photons_per_iteration < 1 || photons.photons_per_iteration > std::uint64_t(kMaxPhotons))
        refuse(path, "corrupted photon estimate (" + std::to_string(photons.photons_per_iteration) +
                         " photons per iteration)");
    auto all = [](const std::vector<double>& values, auto ok) { return std::all_of(values.begin(), values.end(), ok); };
    auto finite_and_not_negative = [](double x) { return std::isfinite(x) && x >= 0.0; };
    auto radius_ok = [&](double r) { return std::isfinite(r) && (version >= 4 ? r >= 0.0 : r > 0.0); };
    if (!all(photons.count, finite_and_not_negative) || !all(photons.flux, finite_and_not_negative) ||
        !all(photons.footprint, finite_and_not_negative) || !all(photons.radius, radius_ok))
        refuse(path, "corrupted photon estimate (a count, radius, footprint or flux out of range)");
    for (std::size_t p = 0; p < photons.radius.size(); ++p)
        if (photons.radius[p] == 0.0 &&
            (photons.count[p] != 0.0 || photons.footprint[p] != 0.0 || photons.flux[kFilmChannels * p] != 0.0 ||
             photons.flux[kFilmChannels * p + 1] != 0.0 || photons.flux[kFilmChannels * p + 2] != 0.0))
            refuse(path, "corrupted photon estimate (pixel " + std::to_string(p) +
                             " has photons or a footprint but no radius)");
}

}  // namespace

bool is_film_path(const std::string& path) {
    const std::string ext = kFilmFileExtension;
    return path.size() >= ext.size() && path.compare(path.size() - ext.size(), ext.size(), ext) == 0;
}

void write_film_file(const std::string& path, const FilmFile& file) {
    const std::vector<char> bytes = encode(file);
    write_atomically(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        out.write(bytes.data(), std::streamsize(bytes.size()));
        out.close();
        if (!out) throw OutputError("cannot write " + path + ": write failed (disk full?)");
    });
}

FilmFile read_film_file(const std::string& path) { return parse_film_file(read_bytes(path), path); }

FilmFile parse_film_file(const std::vector<char>& bytes, const std::string& path) {
    const std::uint32_t version = check_magic_and_version(path, bytes);
    if (bytes.size() < kHeaderBytes + kChecksumBytes)
        refuse(path, "truncated (" + std::to_string(bytes.size()) + " bytes, shorter than the header)");
    Reader r(bytes);
    FilmFile file;
    Film& film = file.film;
    r.get<std::array<char, 8>>();
    r.get<std::uint32_t>();
    const auto flags = r.get<std::uint32_t>();
    file.identity.scene = r.get<std::uint64_t>();
    file.identity.settings = r.get<std::uint64_t>();
    const auto estimator = r.get<std::array<char, kEstimatorBytes>>();
    file.identity.estimator.assign(estimator.data(), strnlen(estimator.data(), kEstimatorBytes));
    const auto width = r.get<std::uint32_t>(), height = r.get<std::uint32_t>();
    film.items.begin = r.get<std::uint64_t>();
    film.items.end = r.get<std::uint64_t>();
    const auto limbs = r.get<std::uint32_t>(), fraction_bits = r.get<std::uint32_t>();
    // Before any size is taken from the flags: a flag this version does not
    // know sizes nothing this reader could check.
    const std::uint32_t known = version >= 3   ? kFlagSquares | kFlagRound | kFlagPhotons
                                : version == 2 ? kFlagSquares | kFlagRound
                                               : kFlagSquares;
    if (flags & ~known) refuse(path, "unknown flags " + std::to_string(flags));

    // Sizes from the header are only trusted once bounded.
    if (width < 1 || height < 1 || width > std::uint32_t(kMaxResolution) || height > std::uint32_t(kMaxResolution) ||
        std::uint64_t(width) * height > std::uint64_t(kMaxPixels))
        refuse(path, "corrupted header (size " + std::to_string(width) + "x" + std::to_string(height) + ")");
    const bool squares = (flags & kFlagSquares) != 0, in_round = (flags & kFlagRound) != 0;
    const bool photons = (flags & kFlagPhotons) != 0;
    const std::uint64_t pixels = std::uint64_t(width) * height;
    const std::uint64_t sums = std::uint64_t(kFilmChannels) * pixels * (squares ? 2 : 1);
    const std::uint64_t sums_end = kHeaderBytes + sizeof(film_sum) * sums;
    const std::uint64_t expected = sums_end + (in_round ? round_table_bytes(bytes, sums_end, pixels) : 0) +
                                   (photons ? photon_estimate_bytes(pixels, version) : 0) + kChecksumBytes;
    if (bytes.size() < expected)
        refuse(path, "truncated (" + std::to_string(bytes.size()) + " bytes of " + std::to_string(expected) + ")");
    if (bytes.size() > expected)
        refuse(path, "corrupted (" + std::to_string(bytes.size() - expected) + " bytes after the checksum)");
    std::uint64_t stored;
    std::memcpy(&stored, bytes.data() + expected - kChecksumBytes, sizeof stored);
    if (stored != fnv1a64(bytes.data(), expected - kChecksumBytes)) refuse(path, "corrupted (checksum mismatch)");
    if (limbs != WP_FILM_LIMBS || fraction_bits != WP_FILM_FRACTION_BITS)
        refuse(path, "film sums of " + std::to_string(limbs) + " limbs and " + std::to_string(fraction_bits) +
                         " fraction bits, this wavepath keeps " + std::to_string(WP_FILM_LIMBS) + " and " +
                         std::to_string(WP_FILM_FRACTION_BITS));
    if (film.items.begin > film.items.end || film.items.end > std::uint64_t(kMaxSpp) * pixels)
        refuse(path, "corrupted header (work items " + std::to_string(film.items.begin) + " to " +
                         std::to_string(film.items.end) + ")");

    film.width = int(width);
    film.height = int(height);
    film.sums.resize(std::uint64_t(kFilmChannels) * width * height);
    r.get_bytes(film.sums.data(), sizeof(film_sum) * film.sums.size());
    if (squares) {
        film.squares.resize(film.sums.size());
        r.get_bytes(film.squares.data(), sizeof(film_sum) * film.squares.size());
    }
    if (in_round) {
        film.round_pixels.resize(r.get<std::uint32_t>());
        r.get_bytes(film.round_pixels.data(), sizeof(std::uint32_t) * film.round_pixels.size());
        film.samples_before.resize(pixels);
        r.get_bytes(film.samples_before.data(), sizeof(std::uint32_t) * pixels);
        check_round(path, film);
    }
    if (photons) {
        film.photons = PhotonEstimate::start(pixels, r.get<std::uint64_t>());
        for (std::vector<double>* values :
             {&film.photons.count, &film.photons.radius, &film.photons.footprint, &film.photons.flux})
            if (values != &film.photons.footprint || version >= 4)
                r.get_bytes(values->data(), sizeof(double) * values->size());
        check_photons(path, film.photons, version);
    }
    return file;
}

void check_film_matches(const std::string& path, const FilmFile& file, const RenderIdentity& identity, int width,
                        int height) {
    const Film& film = file.film;
    if (film.width != width || film.height != height)
        refuse(path, "a film of " + std::to_string(film.width) + "x" + std::to_string(film.height) +
                         " pixels, this render is " + std::to_string(width) + "x" + std::to_string(height));
    if (file.identity.estimator != identity.estimator)
        refuse(path,
               "rendered by the " + file.identity.estimator + " estimator, this render uses " + identity.estimator);
    if (file.identity.scene != identity.scene) refuse(path, "rendered from another scene (its content differs)");
    if (file.identity.settings != identity.settings)
        refuse(path,
               "rendered with other settings (max_depth, rr_depth, seed, nee, mis, hemisphere, sampler, "
               "adaptive sampling or the integrator and its settings differ)");
}

}  // namespace wp
