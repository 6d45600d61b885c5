#include "scene/serialized_mesh.h"

#include <zlib.h>

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "import/mesh_file_error.h"
#include "import/mesh_invariants.h"
#include "scene/limits.h"

namespace wp {
namespace {

constexpr std::uint16_t kSignature = 0x041C;
constexpr std::uint32_t kHasNormals = 0x0001, kHasTexcoords = 0x0002, kHasColors = 0x0008;
constexpr std::uint32_t kDoublePrecision = 0x2000;
// DEFLATE produces at most 1032 bytes per input byte (zlib's technical notes): counts that
// claim more than that of the compressed bytes left are refused before anything is read.
constexpr std::uint64_t kMaxInflateRatio = 1032;
constexpr std::size_t kMaxNameBytes = 1 << 16;

template <class T>
T little_endian(const unsigned char* bytes) {
    T value = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) value |= T(bytes[i]) << (8 * i);
    return value;
}

// The zlib stream of one mesh, read on demand.
class Inflater {
 public:
    explicit Inflater(std::string_view input) {
        stream_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(input.data()));
        stream_.avail_in = static_cast<uInt>(std::min<std::size_t>(input.size(), std::numeric_limits<uInt>::max()));
        rest_ = input.size() - stream_.avail_in;
        if (inflateInit(&stream_) != Z_OK) throw MeshFileError("zlib cannot start inflating");
    }
    ~Inflater() { inflateEnd(&stream_); }
    Inflater(const Inflater&) = delete;
    Inflater& operator=(const Inflater&) = delete;

    // Compressed bytes not yet read.
    std::uint64_t compressed_left() const { return stream_.avail_in + rest_; }

    void read(void* out, std::size_t size, const char* what) {
        auto* next = static_cast<unsigned char*>(out);
        while (size > 0) {
            if (ended_) throw MeshFileError(std::string("the zlib stream ends before ") + what);
            if (stream_.avail_in == 0 && rest_ > 0) {
                const std::size_t more = std::min<std::size_t>(rest_, std::numeric_limits<uInt>::max());
                stream_.avail_in = static_cast<uInt>(more);
                rest_ -= more;
            }
            if (stream_.avail_in == 0) throw MeshFileError(std::string("the file ends before ") + what);
            const std::size_t chunk = std::min<std::size_t>(size, std::numeric_limits<uInt>::max());
            stream_.next_out = next;
            stream_.avail_out = static_cast<uInt>(chunk);
            const int status = inflate(&stream_, Z_NO_FLUSH);
            const std::size_t produced = chunk - stream_.avail_out;
            next += produced;
            size -= produced;
            if (status == Z_STREAM_END) {
                ended_ = true;
            } else if (status == Z_DATA_ERROR || status == Z_NEED_DICT) {
                throw MeshFileError(std::string("corrupt zlib stream (") + (stream_.msg ? stream_.msg : "no message") +
                                    ") in " + what);
            } else if (status == Z_MEM_ERROR) {
                throw std::bad_alloc();
            } else if (status != Z_OK && status != Z_BUF_ERROR) {
                throw MeshFileError("zlib failed inflating " + std::string(what) + " (status " +
                                    std::to_string(status) + ")");
            }
        }
    }

    // The stream must end here (zlib then checks its checksum): else the file is truncated or corrupt.
    void finish(const char* what) {
        unsigned char extra = 0;
        if (!ended_) {
            try {
                read(&extra, 1, what);
            } catch (const MeshFileError&) {
                if (ended_) return;
                throw;
            }
            throw MeshFileError(std::string("the zlib stream holds more than ") + what);
        }
    }

    template <class T>
    T value(const char* what) {
        unsigned char bytes[sizeof(T)];
        read(bytes, sizeof bytes, what);
        return little_endian<T>(bytes);
    }

 private:
    z_stream stream_{};
    std::size_t rest_ = 0;  // input beyond what avail_in (32 bits) holds
    bool ended_ = false;
};

// `count` values of `components` floats or doubles, as floats, read a slice at a time so that
// memory follows what the stream actually holds.
std::vector<float> read_reals(Inflater& in, std::uint64_t count, bool doubles, const char* what) {
    std::vector<float> values;
    constexpr std::uint64_t kSlice = 1 << 16;
    std::vector<unsigned char> bytes;
    for (std::uint64_t done = 0; done < count;) {
        const std::uint64_t n = std::min(kSlice, count - done);
        const std::size_t size = doubles ? 8 : 4;
        bytes.resize(n * size);
        in.read(bytes.data(), bytes.size(), what);
        for (std::uint64_t i = 0; i < n; ++i) {
            if (doubles) {
                values.push_back(
                    static_cast<float>(std::bit_cast<double>(little_endian<std::uint64_t>(&bytes[i * 8]))));
            } else {
                values.push_back(std::bit_cast<float>(little_endian<std::uint32_t>(&bytes[i * 4])));
            }
        }
        done += n;
    }
    return values;
}

void skip_reals(Inflater& in, std::uint64_t count, bool doubles, const char* what) {
    std::vector<unsigned char> bytes(1 << 16);
    for (std::uint64_t left = count * (doubles ? 8 : 4); left > 0;) {
        const std::size_t n = std::size_t(std::min<std::uint64_t>(left, bytes.size()));
        in.read(bytes.data(), n, what);
        left -= n;
    }
}

std::vector<glm::vec3> as_vectors(const std::vector<float>& values) {
    std::vector<glm::vec3> vectors(values.size() / 3);
    for (std::size_t i = 0; i < vectors.size(); ++i) vectors[i] = {values[3 * i], values[3 * i + 1], values[3 * i + 2]};
    return vectors;
}

// Where mesh `shape_index` starts: 0 for the first, else from the table at the file's end.
std::size_t mesh_offset(std::string_view bytes, std::uint16_t version, std::int64_t shape_index) {
    if (shape_index == 0) return 0;
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const std::size_t size = bytes.size();
    if (size < 8) throw MeshFileError("too short for the table of meshes at its end");
    const std::uint32_t count = little_endian<std::uint32_t>(data + size - 4);
    if (std::uint64_t(shape_index) >= count) {
        throw MeshFileError("shape_index " + std::to_string(shape_index) + " is out of range (the file holds " +
                            std::to_string(count) + " meshes)");
    }
    const std::uint64_t entry = version == 4 ? 8 : 4;
    if (entry * count + 4 > size)
        throw MeshFileError("its table of " + std::to_string(count) + " meshes is longer than the file");
    const std::uint64_t at = size - 4 - entry * (count - std::uint64_t(shape_index));
    const std::uint64_t offset =
        version == 4 ? little_endian<std::uint64_t>(data + at) : little_endian<std::uint32_t>(data + at);
    if (offset > size - 4 - entry * count || offset + 4 > size)
        throw MeshFileError("mesh " + std::to_string(shape_index) + " starts at byte " + std::to_string(offset) +
                            ", outside the file");
    return std::size_t(offset);
}

}  // namespace

ImportedMesh parse_serialized_mesh(std::string_view bytes, std::int64_t shape_index) {
    if (shape_index < 0) throw MeshFileError("shape_index must be >= 0, got " + std::to_string(shape_index));
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    if (bytes.size() < 4)
        throw MeshFileError("too short for a serialized mesh (" + std::to_string(bytes.size()) + " bytes)");
    if (little_endian<std::uint16_t>(data) != kSignature)
        throw MeshFileError("not a Mitsuba serialized mesh (its first two bytes are not 0x041C)");
    const std::uint16_t version = little_endian<std::uint16_t>(data + 2);
    if (version != 3 && version != 4)
        throw MeshFileError("serialized format version " + std::to_string(version) + " (Mitsuba reads 3 and 4)");
    const std::size_t offset = mesh_offset(bytes, version, shape_index);
    if (little_endian<std::uint16_t>(data + offset) != kSignature ||
        little_endian<std::uint16_t>(data + offset + 2) != version)
        throw MeshFileError("mesh " + std::to_string(shape_index) + " at byte " + std::to_string(offset) +
                            " does not start with the file's header");

    Inflater in(bytes.substr(offset + 4));
    const std::uint32_t flags = in.value<std::uint32_t>("the flags");
    if (version == 4) {
        std::size_t length = 0;
        while (in.value<std::uint8_t>("the end of the mesh's name") != 0) {
            if (++length > kMaxNameBytes)
                throw MeshFileError("the mesh's name is longer than " + std::to_string(kMaxNameBytes) + " bytes");
        }
    }
    const std::uint64_t vertices = in.value<std::uint64_t>("the vertex count");
    const std::uint64_t triangles = in.value<std::uint64_t>("the triangle count");
    if (vertices > std::numeric_limits<std::uint32_t>::max())
        throw MeshFileError(std::to_string(vertices) + " vertices, more than 2^32 - 1");
    if (triangles > kMaxTriangles)
        throw MeshFileError(std::to_string(triangles) + " triangles, more than the " + std::to_string(kMaxTriangles) +
                            " a scene may have");
    const bool doubles = (flags & kDoublePrecision) != 0;
    const std::uint64_t per_vertex =
        3 + ((flags & kHasNormals) ? 3 : 0) + ((flags & kHasTexcoords) ? 2 : 0) + ((flags & kHasColors) ? 3 : 0);
    const std::uint64_t claimed = vertices * per_vertex * (doubles ? 8 : 4) + triangles * 12;
    // zlib may hold a few bytes of input it has read in its bit buffer: 16 bytes' worth of slack.
    if (claimed > kMaxInflateRatio * (in.compressed_left() + 16))
        throw MeshFileError(std::to_string(vertices) + " vertices and " + std::to_string(triangles) +
                            " triangles need " + std::to_string(claimed) + " bytes, more than the " +
                            std::to_string(in.compressed_left()) + " compressed bytes left in the file can hold");

    ImportedMesh mesh;
    mesh.positions = as_vectors(read_reals(in, 3 * vertices, doubles, "the positions"));
    if (flags & kHasNormals) {
        mesh.normals = as_vectors(read_reals(in, 3 * vertices, doubles, "the normals"));
        mesh.has_normals = true;
    }
    if (flags & kHasTexcoords) {
        const std::vector<float> uvs = read_reals(in, 2 * vertices, doubles, "the texture coordinates");
        for (std::size_t v = 0; v < vertices; ++v) mesh.uvs.emplace_back(uvs[2 * v], uvs[2 * v + 1]);
        mesh.has_uvs = true;
    }
    if (flags & kHasColors) skip_reals(in, 3 * vertices, doubles, "the colours");
    std::vector<unsigned char> indices;
    constexpr std::uint64_t kSlice = 1 << 16;
    for (std::uint64_t done = 0; done < triangles;) {
        const std::uint64_t n = std::min(kSlice, triangles - done);
        indices.resize(n * 12);
        in.read(indices.data(), indices.size(), "the triangles");
        for (std::uint64_t t = 0; t < n; ++t) {
            const std::uint32_t corners[3] = {little_endian<std::uint32_t>(&indices[12 * t]),
                                              little_endian<std::uint32_t>(&indices[12 * t + 4]),
                                              little_endian<std::uint32_t>(&indices[12 * t + 8])};
            check_face(corners, mesh.positions.size());
            mesh.triangles.push_back({corners[0], corners[1], corners[2]});
        }
        done += n;
    }
    in.finish("the mesh");
    for (const glm::vec3& p : mesh.positions) check_finite_vertex(glm::dvec3(p));
    return mesh;
}

ImportedMesh read_serialized_mesh(const std::filesystem::path& path, std::int64_t shape_index) {
    // Not a FIFO or a device, which could be read without end.
    std::error_code error;
    if (std::filesystem::exists(path, error) && !std::filesystem::is_regular_file(path, error))
        throw MeshFileError("cannot read: not a regular file");
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw MeshFileError(std::string("cannot open: ") + std::strerror(errno));
    std::string bytes;
    char buffer[1 << 16];
    std::size_t count;
    while ((count = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) bytes.append(buffer, count);
    if (std::ferror(file.get())) throw MeshFileError(std::string("cannot read: ") + std::strerror(errno));
    return parse_serialized_mesh(bytes, shape_index);
}

}  // namespace wp
