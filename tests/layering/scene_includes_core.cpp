// The control of scene_includes_wavefront.cpp: the same compilation, with a
// header of core, a room below scene, compiles.
#include "core/film.h"
