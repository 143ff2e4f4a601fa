#include "core/vk/Formats.h"

#include <array>
#include <stdexcept>

#include "core/util/DidYouMean.h"

namespace fovea::gpu {
namespace {

struct FormatInfo {
    const char* name;  // doubles as the GLSL layout qualifier: fovea names were chosen to match
    vk::Format format;
    uint32_t bytesPerPixel;
    uint32_t channels;
    bool isUint;
};

constexpr std::array kFormats{
    FormatInfo{"rgba32f", vk::Format::eR32G32B32A32Sfloat, 16, 4, false},
    FormatInfo{"rgba16f", vk::Format::eR16G16B16A16Sfloat, 8, 4, false},
    FormatInfo{"rg32f", vk::Format::eR32G32Sfloat, 8, 2, false},
    FormatInfo{"rg16f", vk::Format::eR16G16Sfloat, 4, 2, false},
    FormatInfo{"r32f", vk::Format::eR32Sfloat, 4, 1, false},
    FormatInfo{"r16f", vk::Format::eR16Sfloat, 2, 1, false},
    FormatInfo{"rgba8", vk::Format::eR8G8B8A8Unorm, 4, 4, false},
    FormatInfo{"r8", vk::Format::eR8Unorm, 1, 1, false},
    FormatInfo{"r32ui", vk::Format::eR32Uint, 4, 1, true},
    FormatInfo{"rg32ui", vk::Format::eR32G32Uint, 8, 2, true},
    FormatInfo{"rgba32ui", vk::Format::eR32G32B32A32Uint, 16, 4, true},
};

const FormatInfo* find(vk::Format format) {
    for (const auto& info : kFormats) {
        if (info.format == format) return &info;
    }
    return nullptr;
}

const FormatInfo& require(vk::Format format) {
    if (const FormatInfo* info = find(format)) return *info;
    throw std::invalid_argument("format " + vk::to_string(format) +
                                " is not supported by fovea (supported: rgba32f, rgba16f, rg32f, "
                                "rg16f, r32f, r16f, rgba8, r8, r32ui, rg32ui, rgba32ui)");
}

}  // namespace

vk::Format parseFormat(std::string_view name) {
    for (const auto& info : kFormats) {
        if (name == info.name) return info.format;
    }
    std::string valid;
    for (const auto& info : kFormats) valid += (valid.empty() ? "" : ", ") + std::string(info.name);
    throw std::invalid_argument("unknown format '" + std::string(name) + "'" +
                                didYouMean(name, formatNames()) + "; valid formats: " + valid);
}

std::string formatName(vk::Format format) {
    if (const FormatInfo* info = find(format)) return info->name;
    return vk::to_string(format);
}

std::vector<std::string> formatNames() {
    std::vector<std::string> names;
    for (const auto& info : kFormats) names.emplace_back(info.name);
    return names;
}

uint32_t formatBytesPerPixel(vk::Format format) {
    return require(format).bytesPerPixel;
}

uint32_t formatChannels(vk::Format format) {
    return require(format).channels;
}

bool formatIsUint(vk::Format format) {
    return require(format).isUint;
}

bool formatIsUnorm8(vk::Format format) {
    return format == vk::Format::eR8G8B8A8Unorm || format == vk::Format::eR8Unorm;
}

std::string glslFormatQualifier(vk::Format format) {
    return require(format).name;
}

}  // namespace fovea::gpu
