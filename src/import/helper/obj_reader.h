// wavepath's OBJ reader inside assimp: tinyobjloader parses the file, and
// the reader hands assimp the scene assimp's own OBJ reader would build from
// it (a node per object, a mesh per run of one material, a vertex per face
// corner, polygons untriangulated), so that assimp's post-processing
// triangulates and joins vertices as before. assimp's reader allocates and
// fills a 16 MiB line buffer for every file, which in an importer process
// of its own cost more than the rest of a small file's import
// (bench/results/big_scenes.md). Its failures are MeshFileErrors, which
// assimp's ReadFile keeps (Importer::GetException).
#pragma once

#include <assimp/BaseImporter.h>

#include <string>

namespace wp {

class TinyObjReader : public Assimp::BaseImporter {
 public:
    // The name assimp reports for it (the importer's "importerIndex").
    static constexpr const char* kName = "Wavefront Object Importer (tinyobjloader)";

    bool CanRead(const std::string& file, Assimp::IOSystem* io, bool check_signature) const override;
    const aiImporterDesc* GetInfo() const override;

 protected:
    void InternReadFile(const std::string& file, aiScene* scene, Assimp::IOSystem* io) override;
};

// Replaces assimp's OBJ reader in `importer` with TinyObjReader.
void use_tiny_obj_reader(Assimp::Importer& importer);

}  // namespace wp
