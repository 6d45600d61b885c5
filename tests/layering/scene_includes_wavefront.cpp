// A file of the scene room that includes a header of the wavefront room, three
// levels above it (docs/architecture.md, "Layers"). tests/layering/CMakeLists.txt
// compiles it as the scene room's files are compiled, with the include roots of
// scene and the rooms below it, and expects the include not to be found.
#include "wavefront/pipeline.h"
