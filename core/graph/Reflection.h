// What a pass declares about its resources: inputs, outputs and internals, each with a format
// and a size rule. The graph compiler reads this to check edges, resolve sizes, plan lifetimes,
// aliasing and barriers; the pass never allocates or synchronizes its own graph resources.
#pragma once
#include <cstdint>
#include <string>
#include <vector>
#include <vulkan/vulkan.hpp>

namespace fovea::graph {

enum class FieldKind { Input, Output, Internal };

enum class SizeRule {
    Any,          // inputs only: no size constraint
    Screen,       // the graph's render size
    Scaled,       // render size * scale (rounded up, at least 1)
    Fixed,        // width x height
    SameAsInput,  // the size of input `sameAs`
    Buffer,       // a storage buffer of `bufferBytes` bytes, not an image
};

struct FieldDesc {
    std::string name;
    FieldKind kind = FieldKind::Input;
    vk::Format format = vk::Format::eUndefined;  // eUndefined on an input = any format
    SizeRule size = SizeRule::Screen;
    float scale = 1.0f;
    uint32_t width = 0, height = 0;
    std::string sameAs;
    uint64_t bufferBytes = 0;
    bool optional = false;    // inputs: may stay unconnected
    bool persistent = false;  // outputs/internals: content survives between frames (never aliased)
    // Inputs: the shader reads it as float (sampler2D / image2D), so an integer-format image
    // (r32ui, ...) cannot be bound; the compiler rejects such an edge naming pass and field.
    bool floatOnly = false;
    std::string doc;

    bool isImage() const { return size != SizeRule::Buffer; }
};

// Fluent builder returned by Reflection::input/output/internal.
class FieldBuilder {
public:
    explicit FieldBuilder(FieldDesc& desc) : mDesc(desc) {}
    FieldBuilder& screen() { return rule(SizeRule::Screen); }
    FieldBuilder& anySize() { return rule(SizeRule::Any); }
    FieldBuilder& scaled(float scale) {
        mDesc.scale = scale;
        return rule(SizeRule::Scaled);
    }
    FieldBuilder& fixed(uint32_t width, uint32_t height) {
        mDesc.width = width;
        mDesc.height = height;
        return rule(SizeRule::Fixed);
    }
    FieldBuilder& sameAs(const std::string& input) {
        mDesc.sameAs = input;
        return rule(SizeRule::SameAsInput);
    }
    FieldBuilder& buffer(uint64_t bytes) {
        mDesc.bufferBytes = bytes;
        return rule(SizeRule::Buffer);
    }
    FieldBuilder& optional() {
        mDesc.optional = true;
        return *this;
    }
    FieldBuilder& persistent() {
        mDesc.persistent = true;
        return *this;
    }
    FieldBuilder& floatOnly() {
        mDesc.floatOnly = true;
        return *this;
    }
    FieldBuilder& doc(const std::string& text) {
        mDesc.doc = text;
        return *this;
    }

private:
    FieldBuilder& rule(SizeRule r) {
        mDesc.size = r;
        return *this;
    }
    FieldDesc& mDesc;
};

class Reflection {
public:
    // Inputs default to SizeRule::Any; outputs and internals to Screen.
    FieldBuilder input(const std::string& name, vk::Format format = vk::Format::eUndefined);
    FieldBuilder output(const std::string& name, vk::Format format);
    FieldBuilder internal(const std::string& name, vk::Format format);

    const std::vector<FieldDesc>& fields() const { return mFields; }
    const FieldDesc* find(const std::string& name) const;
    std::vector<std::string> names(FieldKind kind) const;

private:
    FieldBuilder add(const std::string& name, FieldKind kind, vk::Format format, SizeRule rule);
    std::vector<FieldDesc> mFields;
};

const char* fieldKindName(FieldKind kind);
const char* sizeRuleName(SizeRule rule);

}  // namespace fovea::graph
