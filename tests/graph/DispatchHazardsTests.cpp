// The barriers between one pass's dispatches, derived from their bindings (gpu::DispatchHazards,
// docs/architecture.md "Barriers between the dispatches of one pass"). The validation layer of
// Debian 12 misses dispatch->dispatch hazards (architecture.md "Validation"), so these tests
// count the barriers each access pattern gets: one per hazard, none between independent work.
#include <gtest/gtest.h>

#include <glm/vec2.hpp>
#include <memory>
#include <vector>

#include "core/vk/ComputePipeline.h"
#include "core/vk/DispatchHazards.h"
#include "core/vk/Resources.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::gpu;

namespace {

constexpr uint32_t kCount = 3;  // three words: also one VkDispatchIndirectCommand

class DispatchHazardsTest : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        for (const char* name : {"a", "b", "c", "d"}) mBuffers.push_back(makeBuffer(name));
        mScale.set("scale", 1.0f).set("count", kCount).set("offset", glm::vec2(0.0f));
    }

    std::unique_ptr<Buffer> makeBuffer(const char* name) {
        auto b = std::make_unique<Buffer>(ctx(), 64,
                                          vk::BufferUsageFlagBits::eStorageBuffer |
                                              vk::BufferUsageFlagBits::eIndirectBuffer |
                                              vk::BufferUsageFlagBits::eTransferDst,
                                          false, name);
        const std::vector<float> zeros(16, 0.0f);  // 0.0f reads as 0 groups when indirect
        b->upload(ctx(), zeros.data(), 64);
        return b;
    }
    const Buffer& buf(char name) { return *mBuffers[size_t(name - 'a')]; }

    // scale_buffer.comp: reads `inputData` (readonly), writes `Output` (writeonly).
    void copy(DispatchHazards& h, const vk::raii::CommandBuffer& cmd, char from, char to) {
        mScale.bind("inputData", buf(from)).bind("Output", buf(to));
        h.beforeDispatch(cmd, mScale);
        mScale.dispatch(cmd, kCount);
    }
    void copyIndirect(DispatchHazards& h, const vk::raii::CommandBuffer& cmd, char from, char to,
                      char args) {
        mScale.bind("inputData", buf(from)).bind("Output", buf(to));
        h.beforeDispatch(cmd, mScale, buf(args).buffer());
        mScale.dispatchIndirect(cmd, buf(args));
    }

    ComputePipeline mScale{ctx(), "test/scale_buffer.comp"};
    std::vector<std::unique_ptr<Buffer>> mBuffers;
};

TEST_F(DispatchHazardsTest, AccessesFollowTheShaderQualifiers) {
    mScale.bind("inputData", buf('a')).bind("Output", buf('b'));
    const auto accesses = mScale.accesses();
    ASSERT_EQ(accesses.size(), 2u);
    EXPECT_EQ(accesses[0].handle, uint64_t(VkBuffer(buf('a').buffer())));
    EXPECT_TRUE(accesses[0].read);
    EXPECT_FALSE(accesses[0].write);  // readonly
    EXPECT_EQ(accesses[1].handle, uint64_t(VkBuffer(buf('b').buffer())));
    EXPECT_FALSE(accesses[1].read);  // writeonly
    EXPECT_TRUE(accesses[1].write);

    ComputePipeline rw(ctx(), "test/read_write.comp");  // storage image rw + uniform buffer
    Image target(ctx(), ImageDesc{.width = 4,
                                  .height = 4,
                                  .format = vk::Format::eR16G16B16A16Sfloat,
                                  .debugName = "target"});
    Buffer params(ctx(), 16,
                  vk::BufferUsageFlagBits::eUniformBuffer | vk::BufferUsageFlagBits::eTransferDst,
                  false, "params");
    rw.bind("target", target).bind("params", params);
    for (const auto& a : rw.accesses()) {
        if (a.image) {
            EXPECT_TRUE(a.read && a.write);
        } else {
            EXPECT_TRUE(a.read && !a.write);
        }
    }
}

TEST_F(DispatchHazardsTest, EachHazardGetsOneBarrierAndIndependentWorkNone) {
    struct Case {
        const char* name;
        std::vector<std::pair<char, char>> copies;  // (from, to) in order
        uint64_t barriers;
    };
    const std::vector<Case> cases = {
        {"read after read, distinct writes", {{'a', 'b'}, {'a', 'c'}}, 0},
        {"read after write", {{'a', 'b'}, {'b', 'c'}}, 1},
        {"write after read", {{'a', 'b'}, {'c', 'a'}}, 1},
        {"write after write", {{'a', 'b'}, {'c', 'b'}}, 1},
        // The barrier covers everything before it: the third copy is independent of what
        // followed the barrier, the fourth reads what the second wrote.
        {"a barrier clears what it covers", {{'a', 'b'}, {'b', 'c'}, {'a', 'd'}, {'c', 'b'}}, 2},
        {"a chain", {{'a', 'b'}, {'b', 'c'}, {'c', 'd'}, {'d', 'a'}}, 3},
    };
    for (const Case& c : cases) {
        DispatchHazards h;
        ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
            for (auto [from, to] : c.copies) copy(h, cmd, from, to);
        });
        EXPECT_EQ(h.barriers(), c.barriers) << c.name;
        EXPECT_EQ(h.indirectBarriers(), 0u) << c.name;
        EXPECT_EQ(h.dispatches(), c.copies.size()) << c.name;
    }
}

TEST_F(DispatchHazardsTest, IndirectArgumentsWaitAtTheIndirectStage) {
    {  // A dispatch writes the arguments the next one reads its group counts from.
        DispatchHazards h;
        ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
            copy(h, cmd, 'a', 'd');
            copyIndirect(h, cmd, 'a', 'b', 'd');
        });
        EXPECT_EQ(h.barriers(), 1u);
        EXPECT_EQ(h.indirectBarriers(), 1u);
    }
    {  // A compute-only barrier in between does not make the arguments visible to the
       // indirect-command stage: the indirect dispatch still waits there.
        DispatchHazards h;
        ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
            copy(h, cmd, 'a', 'd');
            copy(h, cmd, 'd', 'b');  // reads d as storage: compute barrier
            copyIndirect(h, cmd, 'a', 'c', 'd');
        });
        EXPECT_EQ(h.barriers(), 2u);
        EXPECT_EQ(h.indirectBarriers(), 1u);
    }
    {  // Writing a buffer an earlier dispatch read its group counts from.
        DispatchHazards h;
        ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
            copyIndirect(h, cmd, 'a', 'b', 'd');
            copy(h, cmd, 'a', 'd');
        });
        EXPECT_EQ(h.barriers(), 1u);
        EXPECT_EQ(h.indirectBarriers(), 1u);
    }
    {  // Arguments nobody wrote in this pass: no barrier.
        DispatchHazards h;
        ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
            copyIndirect(h, cmd, 'a', 'b', 'd');
            copyIndirect(h, cmd, 'a', 'c', 'd');
        });
        EXPECT_EQ(h.barriers(), 0u);
    }
}

TEST_F(DispatchHazardsTest, ImagesWrittenThenSampledAreOrdered) {
    ComputePipeline imageCopy(ctx(), "test/copy.comp");  // sampled src -> writeonly storage dst
    auto image = [](const char* name) {
        return ImageDesc{.width = 8, .height = 8, .debugName = name};
    };
    Image x(ctx(), image("x")), y(ctx(), image("y")), z(ctx(), image("z"));
    DispatchHazards h;
    ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        for (auto [from, to] : {std::pair{&x, &y}, {&x, &z}, {&y, &x}}) {
            imageCopy.bind("src", *from).bind("dst", *to);
            h.beforeDispatch(cmd, imageCopy);
            imageCopy.dispatch(cmd, 8, 8);
        }
    });
    // x->y and x->z are independent; y->x reads y (written) and writes x (read): one barrier.
    EXPECT_EQ(h.barriers(), 1u);
}

}  // namespace
