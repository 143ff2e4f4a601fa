#include "core/graph/Reflection.h"

#include <stdexcept>

namespace fovea::graph {

uint64_t BufferSize::bytes(uint32_t width, uint32_t height) const {
    uint64_t total = header + perPixel * uint64_t(width) * height;
    if (block > 0) {
        const uint64_t across = (uint64_t(width) + block - 1) / block + extraBlocks;
        const uint64_t down = (uint64_t(height) + block - 1) / block + extraBlocks;
        total += perBlock * across * down;
    }
    return total;
}

FieldBuilder Reflection::add(const std::string& name, FieldKind kind, vk::Format format,
                             SizeRule rule) {
    // A pass author's mistake, caught the first time the pass is reflected (tests reflect all).
    if (find(name)) throw std::logic_error("pass declares field '" + name + "' twice");
    // Reserve so references handed out by earlier builders stay valid while declaring.
    if (mFields.capacity() == mFields.size()) mFields.reserve(mFields.size() * 2 + 8);
    FieldDesc& desc = mFields.emplace_back();
    desc.name = name;
    desc.kind = kind;
    desc.format = format;
    desc.size = rule;
    return FieldBuilder(desc);
}

FieldBuilder Reflection::input(const std::string& name, vk::Format format) {
    return add(name, FieldKind::Input, format, SizeRule::Any);
}
FieldBuilder Reflection::output(const std::string& name, vk::Format format) {
    return add(name, FieldKind::Output, format, SizeRule::Screen);
}
FieldBuilder Reflection::internal(const std::string& name, vk::Format format) {
    return add(name, FieldKind::Internal, format, SizeRule::Screen);
}

const FieldDesc* Reflection::find(const std::string& name) const {
    for (const auto& f : mFields)
        if (f.name == name) return &f;
    return nullptr;
}

std::vector<std::string> Reflection::names(FieldKind kind) const {
    std::vector<std::string> out;
    for (const auto& f : mFields)
        if (f.kind == kind) out.push_back(f.name);
    return out;
}

std::string previousBindingName(const std::string& field, uint32_t framesBack) {
    return (framesBack == 1 ? std::string("prev") : "prev" + std::to_string(framesBack)) + "_" +
           field;
}

std::pair<std::string, uint32_t> parsePreviousBindingName(const std::string& name) {
    if (name.rfind("prev", 0) != 0) return {"", 0};
    size_t underscore = name.find('_', 4);
    if (underscore == std::string::npos || underscore + 1 >= name.size()) return {"", 0};
    const std::string digits = name.substr(4, underscore - 4);
    uint32_t back = 1;
    if (!digits.empty()) {
        if (digits.size() > 3 || digits.find_first_not_of("0123456789") != std::string::npos)
            return {"", 0};
        back = uint32_t(std::stoul(digits));
        if (back < 2) return {"", 0};  // "prev1_x" is spelled "prev_x"
    }
    return {name.substr(underscore + 1), back};
}

const char* fieldKindName(FieldKind kind) {
    switch (kind) {
        case FieldKind::Input:
            return "input";
        case FieldKind::Output:
            return "output";
        case FieldKind::Internal:
            return "internal";
    }
    return "?";
}

const char* sizeRuleName(SizeRule rule) {
    switch (rule) {
        case SizeRule::Any:
            return "any";
        case SizeRule::Screen:
            return "screen";
        case SizeRule::Scaled:
            return "scaled";
        case SizeRule::Fixed:
            return "fixed";
        case SizeRule::SameAsInput:
            return "same-as-input";
        case SizeRule::Buffer:
            return "buffer";
    }
    return "?";
}

const char* bufferInitName(BufferInit init) {
    switch (init) {
        case BufferInit::Undefined:
            return "undefined";
        case BufferInit::Zero:
            return "zero";
        case BufferInit::ZeroOnReset:
            return "zero-on-reset";
        case BufferInit::Contents:
            return "contents";
    }
    return "?";
}

}  // namespace fovea::graph
