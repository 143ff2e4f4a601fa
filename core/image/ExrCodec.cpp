// EXR through OpenEXR (libopenexr-dev): float RGBA out, any channel set in.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <algorithm>
#include <cstring>
#include <fstream>

#include "core/image/ImageCodecs.h"
#include "core/util/Error.h"

namespace fovea::image::codec {

namespace {

constexpr char kExrMagic[4] = {0x76, 0x2f, 0x31, 0x01};

// OpenEXR's output goes to memory; the caller writes it with checked stdio (a full disk must be
// an error, and OpenEXR's own file output would leave a short file behind).
class MemoryOStream : public Imf::OStream {
public:
    MemoryOStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override {
        if (n < 0) throw std::logic_error("negative write");
        if (mPos + uint64_t(n) > bytes.size()) bytes.resize(mPos + uint64_t(n));
        std::memcpy(bytes.data() + mPos, c, size_t(n));
        mPos += uint64_t(n);
    }
    uint64_t tellp() override { return mPos; }
    void seekp(uint64_t pos) override { mPos = pos; }
    std::vector<unsigned char> bytes;

private:
    uint64_t mPos = 0;
};

// OpenEXR sizes an attribute's value from the int32 in front of it before reading it: a 541-byte
// file whose string attribute claims 842 MB made a decoder allocate and clear 842 MB (found by
// the image fuzz target; tests/fuzz/regressions/image/). Every attribute of every header must fit
// in the file, which costs one pass over the header (names, types and sizes; values skipped).
void checkExrHeaderSizes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    char magic[4] = {};
    uint32_t version = 0;
    if (!in.read(magic, 4) || std::memcmp(magic, kExrMagic, 4) != 0) return;
    if (!in.read(reinterpret_cast<char*>(&version), 4)) return;  // OpenEXR reports it
    const uint64_t fileSize = std::filesystem::file_size(path);
    const bool multiPart = (version & 0x1000u) != 0;
    auto readName = [&](std::string& name) {  // NUL-terminated, at most 255 bytes in OpenEXR
        name.clear();
        for (char c; in.get(c) && c != '\0';)
            if (name.size() < 256) name.push_back(c);
        return bool(in);
    };
    std::string name, type;
    for (int headers = 0; readName(name);) {
        if (name.empty()) {  // end of a header; a multi-part file ends with an empty header
            if (!multiPart || in.peek() == 0 || ++headers > 1024) return;
            continue;
        }
        int32_t size = 0;
        if (!readName(type) || !in.read(reinterpret_cast<char*>(&size), 4)) return;
        const uint64_t at = uint64_t(in.tellg());
        if (size < 0 || at + uint64_t(size) > fileSize)
            throw InputError(path.string(), "",
                             "OpenEXR header attribute '" + name + "' claims " +
                                 std::to_string(size) + " bytes at offset " + std::to_string(at) +
                                 "; the file has " + std::to_string(fileSize));
        in.seekg(size, std::ios::cur);
    }
}

// The data window's size and the channel names; InputError for what fovea cannot take.
Decoded header(const std::filesystem::path& path, const Imf::Header& h) {
    const Imath::Box2i dw = h.dataWindow();
    const int64_t w = int64_t(dw.max.x) - int64_t(dw.min.x) + 1;
    const int64_t ht = int64_t(dw.max.y) - int64_t(dw.min.y) + 1;
    if (w <= 0 || ht <= 0 || w > INT32_MAX || ht > INT32_MAX)
        throw InputError(path.string(), "", "image has no pixels (empty data window)");
    Decoded d;
    d.width = uint32_t(w);
    d.height = uint32_t(ht);
    for (auto it = h.channels().begin(); it != h.channels().end(); ++it) {
        if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
            throw InputError(path.string(), "",
                             std::string("channel '") + it.name() +
                                 "' is subsampled; fovea reads full-resolution channels only");
        d.channels.push_back(it.name());
    }
    if (d.channels.empty()) throw InputError(path.string(), "", "image has no channels");
    // R, G, B, A first, in that order (OpenEXR lists names alphabetically: A, B, G, R), then the
    // others as stored: the order a channel list is shown in.
    const std::vector<std::string> rgba = {"R", "G", "B", "A"};
    std::stable_sort(d.channels.begin(), d.channels.end(), [&](const auto& x, const auto& y) {
        const auto rank = [&](const std::string& n) {
            return std::find(rgba.begin(), rgba.end(), n) - rgba.begin();
        };
        return rank(x) < rank(y);
    });
    return d;
}

template <class Fn>
auto withOpenExr(const std::filesystem::path& path, Fn fn) {
    checkExrHeaderSizes(path);
    try {
        Imf::InputFile file(path.c_str());
        return fn(file);
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError(path.string(), "", std::string("cannot read image: ") + e.what());
    }
}

}  // namespace

bool isExr(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    char magic[4] = {};
    return in.read(magic, 4) && std::memcmp(magic, kExrMagic, 4) == 0;
}

Decoded probeExr(const std::filesystem::path& path) {
    return withOpenExr(path, [&](Imf::InputFile& file) { return header(path, file.header()); });
}

Decoded decodeExr(const std::filesystem::path& path, uint64_t maxPixels) {
    return withOpenExr(path, [&](Imf::InputFile& file) {
        Decoded d = header(path, file.header());
        checkPixelCount(path, d.width, d.height, maxPixels);
        const size_t n = d.channels.size();
        d.pixels.assign(size_t(d.width) * d.height * n, 0.0f);
        const Imath::Box2i dw = file.header().dataWindow();
        Imf::FrameBuffer frame;
        for (size_t c = 0; c < n; ++c)
            frame.insert(d.channels[c],
                         Imf::Slice::Make(Imf::FLOAT, d.pixels.data() + c, dw, n * sizeof(float),
                                          n * sizeof(float) * d.width));
        file.setFrameBuffer(frame);
        file.readPixels(dw.min.y, dw.max.y);
        return d;
    });
}

std::vector<unsigned char> encodeExr(uint32_t width, uint32_t height, const float* rgba) {
    Imf::Header h(static_cast<int>(width), static_cast<int>(height));
    h.compression() = Imf::ZIP_COMPRESSION;
    const char* names[4] = {"R", "G", "B", "A"};
    for (const char* name : names) h.channels().insert(name, Imf::Channel(Imf::FLOAT));
    MemoryOStream stream;
    {
        Imf::OutputFile file(stream, h);
        Imf::FrameBuffer frame;
        const size_t xStride = 4 * sizeof(float);
        for (int c = 0; c < 4; ++c)
            frame.insert(names[c], Imf::Slice(Imf::FLOAT,
                                              reinterpret_cast<char*>(const_cast<float*>(rgba + c)),
                                              xStride, xStride * width));
        file.setFrameBuffer(frame);
        file.writePixels(int(height));
    }  // the destructor writes the line offset table
    return std::move(stream.bytes);
}

}  // namespace fovea::image::codec
