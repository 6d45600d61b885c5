// A problem with a mesh file, one line without the file's name (the scene
// loader prefixes the scene file, the JSON path and the mesh file).
#pragma once

#include <stdexcept>

namespace wp {

class MeshFileError : public std::runtime_error {
 public:
    using std::runtime_error::runtime_error;
};

}  // namespace wp
