// Image files a user names (ImageFile pass, --reference, compare): the header check
// (readImageSize), then the decode into RGBA float with the pixel cap, and channel selection.
// The name's extension follows the input's magic bytes (fovea picks the decoder by content, but
// the saved inputs read better so): PNG, OpenEXR, Radiance HDR, JPEG; anything else is a .png.
#include <cstring>

#include "core/image/ImageIO.h"
#include "tests/fuzz/FuzzInput.h"

namespace {

const char* extensionFor(const uint8_t* data, size_t size) {
    auto starts = [&](const char* magic, size_t n) {
        return size >= n && std::memcmp(data, magic, n) == 0;
    };
    if (starts("\x89PNG", 4)) return ".png";
    if (starts("\x76\x2f\x31\x01", 4)) return ".exr";
    if (starts("#?", 2)) return ".hdr";
    if (starts("\xff\xd8\xff", 3)) return ".jpg";
    return ".png";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace fovea;
    fuzz::expectOnlyInputErrors("image", [&] {
        const auto path =
            fuzz::writeInput(data, size, std::string("image") + extensionFor(data, size));
        const image::ImageSize header = image::readImageSize(path);
        // At most 2^16 pixels: the fuzzer's time goes into headers and decoders, not into
        // clearing large buffers (the cap itself is the rule under test for larger headers).
        constexpr uint64_t kMaxPixels = uint64_t(1) << 16;
        const image::ImageRGBA pixels = image::readImage(path, kMaxPixels);
        if (pixels.width != header.width || pixels.height != header.height) {
            std::fprintf(stderr, "fuzz image: header says %ux%u, decode gave %ux%u\n", header.width,
                         header.height, pixels.width, pixels.height);
            std::abort();
        }
        (void)image::readImageChannels(path, {"R", "G"});
    });
    return 0;
}
