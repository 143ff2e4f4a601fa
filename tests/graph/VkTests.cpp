// Tests of the Vulkan layer (core/vk): context, formats, resources, pipelines, timestamps.
#include <gtest/gtest.h>

#include <cstring>
#include <glm/glm.hpp>

#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Context.h"
#include "core/vk/Formats.h"
#include "core/vk/Resources.h"
#include "core/vk/Timestamps.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::gpu;

namespace {

class VkTest : public GpuTest {};

// Expects `fn` to throw RuntimeError whose message contains every fragment.
template <class Fn>
void expectRuntimeError(Fn&& fn, std::initializer_list<std::string> fragments) {
    try {
        fn();
        ADD_FAILURE() << "expected a RuntimeError";
    } catch (const RuntimeError& e) {
        std::string message = e.what();
        for (const auto& f : fragments)
            EXPECT_NE(message.find(f), std::string::npos) << "'" << f << "' not in: " << message;
    }
}

ImageDesc desc(uint32_t w, uint32_t h, vk::Format format, std::string name = "test") {
    return ImageDesc{.width = w, .height = h, .format = format, .debugName = std::move(name)};
}

}  // namespace

// --- Formats --------------------------------------------------------------------------------

TEST(VkFormats, ParseAndNameRoundTrip) {
    for (const auto& name : formatNames()) {
        vk::Format f = parseFormat(name);
        EXPECT_EQ(formatName(f), name);
        EXPECT_EQ(glslFormatQualifier(f), name);
        EXPECT_GT(formatBytesPerPixel(f), 0u);
        EXPECT_GE(formatChannels(f), 1u);
    }
    EXPECT_EQ(formatNames().size(), 11u);
    EXPECT_EQ(parseFormat("rgba16f"), vk::Format::eR16G16B16A16Sfloat);
    EXPECT_EQ(formatBytesPerPixel(vk::Format::eR16G16B16A16Sfloat), 8u);
    EXPECT_EQ(formatBytesPerPixel(vk::Format::eR8Unorm), 1u);
    EXPECT_EQ(formatChannels(vk::Format::eR32G32Uint), 2u);
}

TEST(VkFormats, UnknownNameListsValidOnes) {
    try {
        parseFormat("rgba32");
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
        std::string message = e.what();
        EXPECT_NE(message.find("'rgba32'"), std::string::npos) << message;
        EXPECT_NE(message.find("did you mean"), std::string::npos) << message;
        EXPECT_NE(message.find("rgba16f"), std::string::npos) << message;
    }
}

// --- Context --------------------------------------------------------------------------------

TEST_F(VkTest, ContextPicksADevice) {
    EXPECT_FALSE(ctx().deviceName().empty());
    EXPECT_FALSE(ctx().driverName().empty());
    EXPECT_FALSE(ctx().deviceTypeName().empty());
    EXPECT_GT(ctx().timestampPeriodNs(), 0.0);
    EXPECT_TRUE(ctx().validationEnabled()) << "install vulkan-validationlayers";
    auto devices = Context::listDevices();
    ASSERT_FALSE(devices.empty());
    EXPECT_EQ(devices[0].rfind("0: ", 0), 0u) << devices[0];
}

TEST_F(VkTest, DeviceByIndexAndName) {
    Context byIndex(ContextOptions{.device = "0"});
    std::string name = byIndex.deviceName();
    // A case-flipped substring of the name selects the same device.
    std::string part = name.substr(0, std::min<size_t>(name.size(), 5));
    for (auto& c : part) c = static_cast<char>(std::isupper(c) ? std::tolower(c) : std::toupper(c));
    Context byName(ContextOptions{.device = part});
    EXPECT_EQ(byName.deviceName(), name);
}

TEST_F(VkTest, UnknownDeviceListsAvailableDevices) {
    auto devices = Context::listDevices();
    ASSERT_FALSE(devices.empty());
    expectRuntimeError([] { Context c(ContextOptions{.device = "no-such-gpu-xyz"}); },
                       {"no-such-gpu-xyz", "available devices", devices[0]});
    expectRuntimeError([] { Context c(ContextOptions{.device = "99"}); }, {"99", devices[0]});
}

TEST_F(VkTest, ValidationMessagesAreCaptured) {
    if (!ctx().validationEnabled()) GTEST_SKIP() << "no validation layer";
    // Anisotropy without the feature enabled is a cheap, harmless validation error.
    {
        vk::raii::Sampler bad(ctx().device(), vk::SamplerCreateInfo{.anisotropyEnable = VK_TRUE,
                                                                    .maxAnisotropy = 2.0f});
    }
    EXPECT_GT(ctx().validationMessageCount(), 0u);
    ctx().clearValidationMessages();
    EXPECT_EQ(ctx().validationMessageCount(), 0u);
}

// Proves synchronization validation is live. Note: the Debian 12 layer (1.3.239) reports
// dispatch -> transfer hazards but misses dispatch -> dispatch ones, so this uses a copy.
TEST_F(VkTest, SyncValidationCatchesMissingBarrier) {
    if (!ctx().syncValidationEnabled()) GTEST_SKIP() << "no synchronization validation";
    ComputePipeline fill(ctx(), "test/fill.comp");
    Image image(ctx(), desc(8, 8, vk::Format::eR32G32B32A32Sfloat, "hazard"));
    Buffer readback(ctx(), image.byteSize(), vk::BufferUsageFlagBits::eTransferDst, true,
                    "readback");
    ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        fill.bind("result", image).set("value", glm::vec4(1.0f)).dispatch(cmd, 8, 8);
        // Read-after-write without a barrier.
        vk::BufferImageCopy region{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                   .imageExtent = vk::Extent3D{8, 8, 1}};
        cmd.copyImageToBuffer(image.image(), vk::ImageLayout::eGeneral, readback.buffer(), region);
    });
    auto messages = ctx().validationMessages();
    ctx().clearValidationMessages();
    ASSERT_FALSE(messages.empty());
    EXPECT_NE(messages[0].find("SYNC-HAZARD-READ-AFTER-WRITE"), std::string::npos) << messages[0];
}

// --- Resources ------------------------------------------------------------------------------

TEST_F(VkTest, ImageRawRoundTripEveryFormat) {
    for (const auto& name : formatNames()) {
        SCOPED_TRACE(name);
        Image image(ctx(), desc(7, 5, parseFormat(name), name));
        // Fresh images are zero.
        for (std::byte b : image.download(ctx())) ASSERT_EQ(b, std::byte{0});
        std::vector<std::byte> data(image.byteSize());
        for (size_t i = 0; i < data.size(); ++i) data[i] = std::byte((i * 37 + 11) % 61);
        image.upload(ctx(), data.data(), data.size());
        EXPECT_EQ(image.download(ctx()), data);
    }
}

TEST_F(VkTest, ImageRGBA32FConversionEveryFormat) {
    for (const auto& name : formatNames()) {
        SCOPED_TRACE(name);
        const vk::Format format = parseFormat(name);
        Image image(ctx(), desc(3, 2, format, name));
        const uint32_t channels = formatChannels(format);
        std::vector<float> in(3 * 2 * 4), expected(in.size());
        for (size_t i = 0; i < in.size(); ++i) {
            // Exactly representable everywhere: multiples of 1/255 that are also small halves
            // would be rare, so pick per kind.
            float v = formatIsUint(format) ? float(i * 3)
                      : (format == vk::Format::eR8G8B8A8Unorm || format == vk::Format::eR8Unorm)
                          ? float(i * 10) / 255.0f
                          : float(i) * 0.25f - 1.0f;
            in[i] = v;
            uint32_t c = i % 4;
            expected[i] = c < channels ? v : (c == 3 ? 1.0f : 0.0f);
        }
        image.uploadRGBA32F(ctx(), in);
        std::vector<float> out = image.downloadRGBA32F(ctx());
        ASSERT_EQ(out.size(), expected.size());
        for (size_t i = 0; i < out.size(); ++i) EXPECT_FLOAT_EQ(out[i], expected[i]) << "at " << i;
    }
}

TEST_F(VkTest, ImageUploadSizeMismatchThrows) {
    Image image(ctx(), desc(4, 4, vk::Format::eR32Sfloat, "small"));
    std::vector<float> data(15);
    expectRuntimeError([&] { image.upload(ctx(), data.data(), data.size() * 4); },
                       {"small", "60", "64"});
}

TEST_F(VkTest, BufferRoundTrip) {
    std::vector<uint32_t> data(1000);
    for (size_t i = 0; i < data.size(); ++i) data[i] = uint32_t(i * i);
    Buffer device(ctx(), data.size() * 4,
                  vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferSrc |
                      vk::BufferUsageFlagBits::eTransferDst,
                  false, "device");
    device.upload(ctx(), data.data(), data.size() * 4);
    EXPECT_EQ(device.downloadAs<uint32_t>(ctx()), data);
    // Partial upload at an offset.
    uint32_t patch[2] = {7, 9};
    device.upload(ctx(), patch, sizeof patch, 4 * 10);
    auto back = device.downloadAs<uint32_t>(ctx());
    EXPECT_EQ(back[10], 7u);
    EXPECT_EQ(back[11], 9u);
    EXPECT_EQ(back[12], 144u);

    Buffer host(ctx(), 64, vk::BufferUsageFlagBits::eStorageBuffer, true, "host");
    ASSERT_NE(host.mapped(), nullptr);
    std::vector<float> floats(16, 2.5f);
    host.upload(ctx(), floats.data(), 64);
    EXPECT_EQ(host.downloadAs<float>(ctx()), floats);
    expectRuntimeError([&] { host.upload(ctx(), floats.data(), 64, 4); }, {"host", "exceeds"});
}

// --- ComputePipeline ------------------------------------------------------------------------

TEST_F(VkTest, FillDispatchWritesExactPixels) {
    ComputePipeline fill(ctx(), "test/fill.comp");
    EXPECT_EQ(fill.interface().localSize, (std::array<uint32_t, 3>{8, 8, 1}));
    Image image(ctx(), desc(13, 9, vk::Format::eR32G32B32A32Sfloat, "fill target"));
    const glm::vec4 value(1.5f, -2.0f, 0.25f, 1.0f);
    ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        fill.bind("result", image).set("value", value).dispatch(cmd, image.width(), image.height());
    });
    std::vector<float> px = image.downloadRGBA32F(ctx());
    for (size_t i = 0; i < px.size(); ++i) ASSERT_EQ(px[i], value[i % 4]) << "at " << i;

    // With a define the pipeline is a different shader: .xy gets the coordinate added.
    ComputePipeline coords(ctx(), "test/fill.comp", {{"ADD_COORDS", "1"}});
    ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        coords.bind("result", image).set("value", value).dispatch(cmd, 13, 9);
    });
    px = image.downloadRGBA32F(ctx());
    for (uint32_t y = 0; y < 9; ++y)
        for (uint32_t x = 0; x < 13; ++x) {
            const float* p = &px[(y * 13 + x) * 4];
            ASSERT_EQ(p[0], value.x + float(x));
            ASSERT_EQ(p[1], value.y + float(y));
            ASSERT_EQ(p[2], value.z);
        }
}

TEST_F(VkTest, SampledCopyAndUniformBuffer) {
    ComputePipeline copy(ctx(), "test/copy.comp");
    Image src(ctx(), desc(20, 6, vk::Format::eR32G32B32A32Sfloat, "src"));
    Image dst(ctx(), desc(20, 6, vk::Format::eR32G32B32A32Sfloat, "dst"));
    std::vector<float> pattern(20 * 6 * 4);
    for (size_t i = 0; i < pattern.size(); ++i) pattern[i] = float(i) * 0.5f;
    src.uploadRGBA32F(ctx(), pattern);
    ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        copy.bind("src", src).bind("dst", dst).dispatch(cmd, 20, 6);
    });
    EXPECT_EQ(dst.downloadRGBA32F(ctx()), pattern);

    // Read-modify-write of an rgba16f storage image with a uniform buffer.
    ComputePipeline rw(ctx(), "test/read_write.comp");
    Image target(ctx(), desc(5, 5, vk::Format::eR16G16B16A16Sfloat, "target"));
    Buffer params(ctx(), 16,
                  vk::BufferUsageFlagBits::eUniformBuffer | vk::BufferUsageFlagBits::eTransferDst,
                  false, "params");
    const float add[4] = {1, 2, 3, 4};
    params.upload(ctx(), add, sizeof add);
    ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        rw.bind("target", target).bind("params", params).dispatch(cmd, 5, 5);
        // The second dispatch reads what the first wrote.
        vk::MemoryBarrier2 barrier{.srcStageMask = vk::PipelineStageFlagBits2::eComputeShader,
                                   .srcAccessMask = vk::AccessFlagBits2::eShaderStorageWrite,
                                   .dstStageMask = vk::PipelineStageFlagBits2::eComputeShader,
                                   .dstAccessMask = vk::AccessFlagBits2::eShaderStorageRead |
                                                    vk::AccessFlagBits2::eShaderStorageWrite};
        cmd.pipelineBarrier2(
            vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &barrier});
        rw.dispatch(cmd, 5, 5);
    });
    for (size_t i = 0; auto v : target.downloadRGBA32F(ctx())) EXPECT_EQ(v, 2 * add[i++ % 4]);
}

TEST_F(VkTest, StorageBufferDispatch) {
    ComputePipeline scale(ctx(), "test/scale_buffer.comp");
    ASSERT_TRUE(scale.hasBinding("inputData"));
    ASSERT_TRUE(scale.hasBinding("Output"));
    const uint32_t n = 100;
    std::vector<float> in(n);
    for (uint32_t i = 0; i < n; ++i) in[i] = float(i);
    Buffer input(ctx(), n * 4,
                 vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst,
                 false, "input");
    Buffer output(ctx(), n * 4,
                  vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferSrc,
                  false, "output");
    input.upload(ctx(), in.data(), n * 4);
    ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        scale.bind("inputData", input)
            .bind("Output", output)
            .set("scale", 3.0f)
            .set("count", n)
            .set("offset", glm::vec2(0.5f, 0.0f))
            .dispatch(cmd, n);
    });
    auto out = output.downloadAs<float>(ctx());
    for (uint32_t i = 0; i < n; ++i) ASSERT_EQ(out[i], float(i) * 3.0f + 0.5f);
}

TEST_F(VkTest, UnknownBindingSuggestsName) {
    ComputePipeline fill(ctx(), "test/fill.comp");
    Image image(ctx(), desc(4, 4, vk::Format::eR32G32B32A32Sfloat));
    expectRuntimeError(
        [&] { fill.bind("reslt", image); },
        {"shader 'test/fill.comp' has no resource 'reslt'", "(did you mean 'result'?)"});
    expectRuntimeError([&] { fill.set("valeu", glm::vec4(1.0f)); },
                       {"no push constant 'valeu'", "did you mean 'value'"});
}

TEST_F(VkTest, WrongKindAndFormatErrors) {
    ComputePipeline fill(ctx(), "test/fill.comp");
    Image half(ctx(), desc(4, 4, vk::Format::eR16G16B16A16Sfloat, "halfImage"));
    expectRuntimeError([&] { fill.bind("result", half); }, {"rgba32f", "rgba16f", "halfImage"});
    Buffer buffer(ctx(), 64);
    expectRuntimeError([&] { fill.bind("result", buffer); }, {"storage image"});
    ComputePipeline scale(ctx(), "test/scale_buffer.comp");
    expectRuntimeError([&] { scale.bind("inputData", half); }, {"storage buffer"});
}

TEST_F(VkTest, MissingBindingErrorsAtDispatch) {
    ComputePipeline copy(ctx(), "test/copy.comp");
    Image dst(ctx(), desc(4, 4, vk::Format::eR32G32B32A32Sfloat));
    copy.bind("dst", dst);
    expectRuntimeError(
        [&] {
            ctx().submitAndWait(
                [&](const vk::raii::CommandBuffer& cmd) { copy.dispatch(cmd, 4, 4); });
        },
        {"shader 'test/copy.comp' expects resource 'src' but none was bound"});
}

TEST_F(VkTest, PushConstantTypeChecks) {
    ComputePipeline scale(ctx(), "test/scale_buffer.comp");
    expectRuntimeError([&] { scale.set("scale", 1.0); }, {"'scale'", "4 bytes", "8-byte"});
    expectRuntimeError([&] { scale.set("offset", 1.0f); }, {"'offset'", "vec2"});
    expectRuntimeError([&] { scale.set("count", 1.0f); }, {"'count'", "floating-point"});
    expectRuntimeError([&] { scale.set("scale", 1); }, {"'scale'", "integer"});
    scale.set("count", 5).set("count", 5u).set("offset", glm::vec2(1.0f));  // all fine
    const auto* offset = scale.interface().findPushConstant("offset");
    ASSERT_NE(offset, nullptr);
    EXPECT_EQ(offset->offset, 8u);
    EXPECT_EQ(offset->typeName, "vec2");
}

// --- Timestamps and aliasing ----------------------------------------------------------------

TEST_F(VkTest, TimestampsAreNonDecreasing) {
    TimestampPool pool(ctx(), 4);
    ComputePipeline fill(ctx(), "test/fill.comp");
    Image image(ctx(), desc(64, 64, vk::Format::eR32G32B32A32Sfloat));
    ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        pool.reset(cmd);
        pool.write(cmd, 0);
        fill.bind("result", image).set("value", glm::vec4(1.0f)).dispatch(cmd, 64, 64);
        pool.write(cmd, 1);
        fill.set("value", glm::vec4(2.0f)).dispatch(cmd, 64, 64);
        pool.write(cmd, 2);
    });
    auto ticks = pool.readTicks(3);
    ASSERT_EQ(ticks.size(), 3u);
    EXPECT_LE(ticks[0], ticks[1]);
    EXPECT_LE(ticks[1], ticks[2]);
    EXPECT_GE(pool.ticksToMs(ticks[2] - ticks[0]), 0.0);
    EXPECT_DOUBLE_EQ(pool.ticksToMs(1'000'000), ctx().timestampPeriodNs());
    // Query 3 was never written: an error instead of waiting forever.
    expectRuntimeError([&] { pool.readTicks(4); }, {"timestamp 3"});
}

TEST_F(VkTest, AliasedImagesShareMemorySequentially) {
    ImageDesc a = desc(16, 16, vk::Format::eR32G32B32A32Sfloat, "aliasA");
    ImageDesc b = desc(24, 8, vk::Format::eR32G32B32A32Sfloat, "aliasB");
    auto reqA = Image::memoryRequirements(ctx(), a);
    auto reqB = Image::memoryRequirements(ctx(), b);
    auto block = std::make_shared<MemoryBlock>(ctx(), std::max(reqA.size, reqB.size),
                                               reqA.memoryTypeBits & reqB.memoryTypeBits);
    Image imageA(ctx(), a, block, 0);
    Image imageB(ctx(), b, block, 0);
    EXPECT_TRUE(imageA.aliased());
    EXPECT_EQ(imageA.allocationSize(), reqA.size);
    ComputePipeline fill(ctx(), "test/fill.comp");
    for (auto [image, value] : {std::pair{&imageA, 3.0f}, std::pair{&imageB, 7.0f}}) {
        ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
            image->recordTransition(cmd, vk::ImageLayout::eUndefined, vk::ImageLayout::eGeneral);
            fill.bind("result", *image)
                .set("value", glm::vec4(value))
                .dispatch(cmd, image->width(), image->height());
        });
        for (float v : image->downloadRGBA32F(ctx())) ASSERT_EQ(v, value);
    }
    // An offset that breaks alignment or overruns the block is refused.
    expectRuntimeError([&] { Image c(ctx(), a, block, block->size()); }, {"aliasA", "offset"});
}
