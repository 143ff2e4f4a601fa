// ImageFile: the user's own images as a graph input — one EXR/PNG (or JPEG, HDR, TGA, BMP, ...)
// or a numbered sequence (`frame%04d.exr`, frame = firstFrame + frame index), with channel
// selection for multi-layer EXRs (AOVs: colour, albedo, normal, depth, motion). The file must
// have the render size; a missing or wrong-size file is an InputError naming it (exit 2). The
// anchor is Falcor's ImageLoader pass.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/graph/Pass.h"
#include "core/vk/Resources.h"

namespace fovea::passes {

class ImageFilePass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void validate(const graph::ValidateContext& ctx) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    // A single file (no frame pattern) gives the same image every frame.
    bool cacheable() const override { return mPath.find('%') == std::string::npos; }

private:
    // The file of frame index `frame`.
    std::string fileFor(uint64_t frame) const;
    // Reads `file` with the selected channels and checks its size against the render size.
    std::vector<float> readChecked(const std::string& file, uint32_t width, uint32_t height) const;

    std::string mPath;
    std::string mResolvedPath;  // mPath resolved against the graph file's folder (compile)
    int mFirstFrame{};
    std::string mChannels;
};

// The message for a malformed frame pattern (formatFramePattern's InputError, validate()).
std::string framePatternError(const std::string& pattern);

// `pattern` with its one printf-style integer conversion (`%d`, `%4d`, `%04d`; `%%` is a
// literal '%') replaced by `frame`. Any other conversion, or more than one, is an InputError
// naming `what` (the pattern is never handed to printf). No conversion: `pattern` itself.
std::string formatFramePattern(const std::string& pattern, uint64_t frame, const std::string& what);

}  // namespace fovea::passes
