// The one way fovea includes tinygltf (Debian's libtinygltf-dev 2.7.0, header-only use: the
// implementation is compiled once, in TinyGltfImpl.cpp). The configuration must be identical in
// every translation unit, hence this header:
//  - TINYGLTF_NO_STB_IMAGE / _WRITE: tinygltf neither decodes nor writes images. fovea decodes only
//    the images the scene uses, itself (GltfTextures.cpp, stb_image from libstb-dev), so an unused
//    broken image is a warning rather than a failed load, and 16-bit images are converted exactly.
//  - TINYGLTF_NO_EXTERNAL_IMAGE: tinygltf does not read image files either (same reason).
//  - nlohmann/json.hpp is found where Debian installs it (tinygltf's default include).
#pragma once

#ifndef TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE
#endif
#ifndef TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#endif
#ifndef TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#endif

#include <tiny_gltf.h>
