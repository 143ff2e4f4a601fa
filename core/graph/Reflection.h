// What a pass declares about its resources: inputs, outputs and internals, each with a format
// and a size rule. The graph compiler reads this to check edges, resolve sizes, plan lifetimes,
// aliasing and barriers; the pass never allocates or synchronizes its own graph resources.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
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
    Buffer,       // a storage buffer (not an image) of BufferSize bytes
};

// Bytes of a buffer field: a fixed part plus parts that follow the render size, so a buffer that
// holds one entry per pixel or per block never needs a user-facing capacity parameter.
// bytes = header + perPixel * width * height
//       + perBlock * (ceil(width / block) + extraBlocks) * (ceil(height / block) + extraBlocks)
struct BufferSize {
    uint64_t header = 0;
    uint64_t perPixel = 0;
    uint64_t perBlock = 0;
    uint32_t block = 0;        // block edge in pixels (0 = no per-block part)
    uint32_t extraBlocks = 0;  // blocks added per axis (e.g. one more for a moving block grid)
    uint64_t bytes(uint32_t width, uint32_t height) const;
};

// What a buffer output/internal holds when the graph hands it to the pass. The graph writes it
// (and orders the write before the pass), so no pass clears, uploads or allocates its own.
enum class BufferInit {
    Undefined,    // whatever the pass wrote last (after allocation: undefined)
    Zero,         // zeros on the first frame after allocation (e.g. counters since compile)
    ZeroOnReset,  // zeros on that frame and on every frame that starts a history (reset, resize,
                  // camera cut): counters "since the last reset"
    Contents,     // FieldDesc::contents, uploaded once when the buffer is allocated (constant
                  // tables); the pass must not write it
};

struct FieldDesc {
    std::string name;
    FieldKind kind = FieldKind::Input;
    vk::Format format = vk::Format::eUndefined;  // eUndefined on an input = any format
    SizeRule size = SizeRule::Screen;
    float scale = 1.0f;
    uint32_t width = 0, height = 0;
    std::string sameAs;
    BufferSize buffer;
    bool optional = false;    // inputs: may stay unconnected
    bool persistent = false;  // outputs/internals: content survives between frames (never aliased)
    // Outputs/internals (images): the graph keeps this many previous frames of the field. The pass
    // reads them with ExecuteContext::previous (shaders: `prev_<field>`, `prev2_<field>`, ...),
    // writes only this frame's image, and asks historyValid() whether they hold a frame yet.
    uint32_t historyFrames = 0;
    // Inputs: the shader reads it as float (sampler2D / image2D), so an integer-format image
    // (r32ui, ...) cannot be bound; the compiler rejects such an edge naming pass and field.
    bool floatOnly = false;
    // Buffers: also usable as indirect dispatch arguments (vkCmdDispatchIndirect); the graph's
    // barriers then cover the indirect-command read.
    bool indirect = false;
    // Buffers: in host-visible, mapped memory (gpu::Buffer::mapped), for data the pass writes
    // from the CPU each frame (e.g. a staging copy of an image file). Frames are synchronous, so
    // the previous frame's GPU reads are done when execute() writes it.
    bool hostVisible = false;
    BufferInit init = BufferInit::Undefined;
    // BufferInit::Contents: the bytes, in storage that outlives every graph (a static table);
    // their size must equal the buffer's.
    const void* contents = nullptr;
    uint64_t contentsBytes = 0;
    // Buffers: size from the extent of input `sizeOf` instead of the render size (a per-block
    // buffer of an image that may be smaller than the screen, e.g. a Visual-Polar buffer).
    std::string sizeOf;
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
        mDesc.buffer = BufferSize{.header = bytes};
        return rule(SizeRule::Buffer);
    }
    // header + bytesPerPixel * width * height (render size).
    FieldBuilder& bufferPerPixel(uint64_t bytesPerPixel, uint64_t headerBytes = 0) {
        mDesc.buffer = BufferSize{.header = headerBytes, .perPixel = bytesPerPixel};
        return rule(SizeRule::Buffer);
    }
    // header + bytesPerBlock per block of blockSize x blockSize pixels covering the render size,
    // with extraBlocks more blocks per axis.
    FieldBuilder& bufferPerBlock(uint32_t blockSize, uint64_t bytesPerBlock,
                                 uint64_t headerBytes = 0, uint32_t extraBlocks = 0) {
        mDesc.buffer = BufferSize{.header = headerBytes,
                                  .perBlock = bytesPerBlock,
                                  .block = blockSize,
                                  .extraBlocks = extraBlocks};
        return rule(SizeRule::Buffer);
    }
    // Keep `frames` previous frames of this output/internal image (pass-declared history).
    FieldBuilder& history(uint32_t frames = 1) {
        mDesc.historyFrames = frames;
        return *this;
    }
    FieldBuilder& optional() {
        mDesc.optional = true;
        return *this;
    }
    // Undoes optional() of a shared declaration (core/graph/DenoiserInputs.h) for a pass that
    // cannot run without the input.
    FieldBuilder& required() {
        mDesc.optional = false;
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
    FieldBuilder& indirect() {
        mDesc.indirect = true;
        return *this;
    }
    FieldBuilder& hostVisible() {
        mDesc.hostVisible = true;
        return *this;
    }
    // Buffers: zeros on the first frame after allocation (BufferInit::Zero).
    FieldBuilder& zeroed() {
        mDesc.init = BufferInit::Zero;
        return *this;
    }
    // Buffers: zeros whenever a history starts (BufferInit::ZeroOnReset).
    FieldBuilder& zeroOnReset() {
        mDesc.init = BufferInit::ZeroOnReset;
        return *this;
    }
    // Buffers: constant bytes uploaded when allocated (BufferInit::Contents); `data` must
    // outlive the graph (static storage). The buffer is persistent.
    FieldBuilder& contents(const void* data, uint64_t bytes) {
        mDesc.init = BufferInit::Contents;
        mDesc.contents = data;
        mDesc.contentsBytes = bytes;
        mDesc.persistent = true;
        return *this;
    }
    // Buffers: per-pixel/per-block parts follow this input's extent, not the render size.
    FieldBuilder& sizedBy(const std::string& input) {
        mDesc.sizeOf = input;
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

// Shader resource names of a field's previous frames: "prev_<field>" (1 frame back) and
// "prev<N>_<field>" (N >= 2). parse returns {field, N}, or {"", 0} for any other name.
std::string previousBindingName(const std::string& field, uint32_t framesBack);
std::pair<std::string, uint32_t> parsePreviousBindingName(const std::string& name);

const char* fieldKindName(FieldKind kind);
const char* sizeRuleName(SizeRule rule);
const char* bufferInitName(BufferInit init);

}  // namespace fovea::graph
