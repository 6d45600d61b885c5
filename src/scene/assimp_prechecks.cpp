#include "scene/assimp_prechecks.h"

#include <assimp/BaseImporter.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "scene/gltf_check.h"
#include "scene/mesh_file.h"
#include "scene/off_check.h"
#include "scene/ply_check.h"

namespace wp {
namespace {

std::string read_file(const std::filesystem::path& path, std::uintmax_t size) {
    std::ifstream in(path, std::ios::binary);
    std::string text(size, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    return text;
}

bool ends_with_ignoring_case(const std::string& text, const std::string& suffix) {
    return suffix.size() <= text.size() &&
           std::equal(suffix.begin(), suffix.end(), text.end() - static_cast<std::ptrdiff_t>(suffix.size()),
                      [](unsigned char a, unsigned char b) { return std::tolower(a) == std::tolower(b); });
}

std::set<std::string> extensions_of(Assimp::BaseImporter& reader) {
    std::set<std::string> extensions;
    reader.GetExtensionList(extensions);
    return extensions;
}

bool claims_name(Assimp::BaseImporter& reader, const std::string& file) {
    const std::set<std::string> extensions = extensions_of(reader);
    return std::any_of(extensions.begin(), extensions.end(),
                       [&](const std::string& extension) { return ends_with_ignoring_case(file, "." + extension); });
}

// The reader assimp 5.2.5's Importer::ReadFile picks for the file, as it
// picks it: the one whose extensions end the name (if several do, the first
// whose signature check accepts the file), else the first whose signature
// check accepts it (PLY's: "ply" anywhere in the first 200 bytes); null if
// none. Throws if several readers claim the name and none accepts the file:
// assimp would then try every reader's signature, and a .gltf could be read
// as anything (fuzz_mesh: as Quick3D, which asked for 2 TB).
Assimp::BaseImporter* chosen_reader(const Assimp::Importer& importer, const std::string& file) {
    std::vector<Assimp::BaseImporter*> readers;
    for (std::size_t i = 0; i < importer.GetImporterCount(); ++i) readers.push_back(importer.GetImporter(i));
    std::vector<Assimp::BaseImporter*> claimants;
    std::copy_if(readers.begin(), readers.end(), std::back_inserter(claimants),
                 [&](Assimp::BaseImporter* reader) { return claims_name(*reader, file); });
    if (claimants.size() == 1) return claimants[0];
    const auto accepts = [&](Assimp::BaseImporter* reader) {
        return reader->CanRead(file, importer.GetIOHandler(), true);
    };
    const std::vector<Assimp::BaseImporter*>& candidates = claimants.empty() ? readers : claimants;
    const auto reader = std::find_if(candidates.begin(), candidates.end(), accepts);
    if (reader != candidates.end()) return *reader;
    if (claimants.empty()) return nullptr;
    std::string names;
    for (const Assimp::BaseImporter* claimant : claimants)
        names += (names.empty() ? "" : ", ") + std::string(claimant->GetInfo()->mName);
    throw MeshFileError("none of assimp's readers for its extension (" + names + ") accepts it");
}

}  // namespace

void check_before_assimp(const std::filesystem::path& path) {
    std::error_code error;
    const std::uintmax_t file_size = std::filesystem::file_size(path, error);
    if (error) return;  // not a regular file: reading it reports the problem
    const Assimp::Importer importer;
    Assimp::BaseImporter* reader = chosen_reader(importer, path.string());
    if (reader == nullptr) return;  // assimp says so
    if (reader == importer.GetImporter("ply")) check_ply(read_file(path, file_size));
    if (reader == importer.GetImporter("off")) check_off(read_file(path, file_size));
    if (extensions_of(*reader).contains("gltf")) check_gltf(read_file(path, file_size));  // 1.0 or 2.0
}

}  // namespace wp
