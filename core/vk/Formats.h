// Image formats fovea understands by name (graph JSON, CLI, shader qualifiers).
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>
#include <vulkan/vulkan.hpp>

namespace fovea::gpu {

// "rgba32f" -> eR32G32B32A32Sfloat. Throws std::invalid_argument listing the valid names.
vk::Format parseFormat(std::string_view name);

// Inverse of parseFormat. Formats without a fovea name fall back to vk::to_string ("R8G8Snorm")
// so error messages can still name them.
std::string formatName(vk::Format format);

// Every name parseFormat accepts, in a stable order.
std::vector<std::string> formatNames();

// Throw std::invalid_argument for formats without a fovea name.
uint32_t formatBytesPerPixel(vk::Format format);
uint32_t formatChannels(vk::Format format);

// True for r32ui/rg32ui/rgba32ui: shaders must use uimage2D, and clears use uint values.
bool formatIsUint(vk::Format format);

// True for rgba8/r8 (8-bit UNORM): such images hold display-encoded values (e.g. Tonemap's
// `ldr`), so image writers store them as-is instead of encoding them again.
bool formatIsUnorm8(vk::Format format);

// The GLSL image format layout qualifier ("rgba32f", "rgba8", "r32ui").
std::string glslFormatQualifier(vk::Format format);

}  // namespace fovea::gpu
