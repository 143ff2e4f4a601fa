#include "core/graph/Reflection.h"

#include <stdexcept>

namespace fovea::graph {

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

}  // namespace fovea::graph
