// tinygltf's implementation, compiled once for the whole program (see TinyGltf.h). Warnings of the
// third-party code are not ours to fix.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#define TINYGLTF_IMPLEMENTATION
#include "core/scene/gltf/TinyGltf.h"
#pragma GCC diagnostic pop
