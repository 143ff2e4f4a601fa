// Test-only pass types for the CPU compile stages (CompilerTests, ParamTests). They declare fields
// and parameters like real passes but never touch a GPU: execute() is never called by these tests.
// They live in a local PassRegistry (testRegistry()), never in the global passRegistry().
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "core/graph/Pass.h"
#include "core/graph/PassRegistry.h"

namespace fovea::testpasses {

constexpr vk::Format kRgba32f = vk::Format::eR32G32B32A32Sfloat;
constexpr vk::Format kRgba8 = vk::Format::eR8G8B8A8Unorm;
constexpr uint64_t kRgba32fBytes = 16;  // bytes per pixel of rgba32f

// Base of every test pass: execute() is a no-op (never called in CPU tests).
class TestPass : public graph::Pass {
public:
    void execute(graph::ExecuteContext&) override {}
};

// output `color` rgba32f, screen size.
class Src : public TestPass {
public:
    void reflect(graph::Reflection& r) const override {
        r.output("color", kRgba32f).screen().doc("source image");
    }
};

// output `ldr` rgba8, screen size (format mismatch tests).
class LdrSrc : public TestPass {
public:
    void reflect(graph::Reflection& r) const override { r.output("ldr", kRgba8).screen(); }
};

// input `in` rgba32f, output `out` rgba32f same size as `in`; parameter `strength`.
class Filter : public TestPass {
public:
    void params(graph::ParamVisitor& v) override {
        v.add("strength", mStrength, 1.0f, "filter strength", {0, 10});
    }
    void reflect(graph::Reflection& r) const override {
        r.input("in", kRgba32f).doc("image to filter");
        r.output("out", kRgba32f).sameAs("in").doc("filtered image");
    }
    float strength() const { return mStrength; }

private:
    float mStrength = 0.0f;
};

// inputs `a` (any format) and `b` (optional, same size as a); output `out` same size as a.
class Join : public TestPass {
public:
    void reflect(graph::Reflection& r) const override {
        r.input("a");
        r.input("b").sameAs("a").optional();
        r.output("out", kRgba32f).sameAs("a");
    }
};

// input `in` (any size), output `out` at half the render size.
class Half : public TestPass {
public:
    void reflect(graph::Reflection& r) const override {
        r.input("in");
        r.output("out", kRgba32f).scaled(0.5f);
    }
};

// input `in`, output `out` fixed 17x9.
class Fixed : public TestPass {
public:
    void reflect(graph::Reflection& r) const override {
        r.input("in");
        r.output("out", kRgba32f).fixed(17, 9);
    }
};

// input `in`, output `out` persistent (content survives between frames).
class Persist : public TestPass {
public:
    void reflect(graph::Reflection& r) const override {
        r.input("in");
        r.output("out", kRgba32f).sameAs("in").persistent();
    }
};

// input `in`, output `out`; a cacheable pass (its outputs must survive between frames).
class Cached : public TestPass {
public:
    void reflect(graph::Reflection& r) const override {
        r.input("in");
        r.output("out", kRgba32f).sameAs("in");
    }
    bool cacheable() const override { return true; }
};

// output `color`; needs scene geometry and emissive triangles.
class NeedsScene : public TestPass {
public:
    void reflect(graph::Reflection& r) const override { r.output("color", kRgba32f).screen(); }
    uint32_t sceneNeeds() const override { return graph::kSceneGeometry | graph::kSceneEmissive; }
};

// output `buf`: a 4096-byte storage buffer.
class BufferProducer : public TestPass {
public:
    void reflect(graph::Reflection& r) const override { r.output("buf", {}).buffer(4096); }
};

// input `buf` (a buffer), output `color` (screen image).
class BufferConsumer : public TestPass {
public:
    void reflect(graph::Reflection& r) const override {
        r.input("buf").buffer(4096);
        r.output("color", kRgba32f).screen();
    }
};

// input `in`, internal `scratch` (r32f, same size as in), output `out`.
class Internal : public TestPass {
public:
    void reflect(graph::Reflection& r) const override {
        r.input("in", kRgba32f);
        r.internal("scratch", vk::Format::eR32Sfloat).sameAs("in");
        r.output("out", kRgba32f).sameAs("in");
    }
};

// One parameter of every type, for ParamTests.
class AllParams : public TestPass {
public:
    void params(graph::ParamVisitor& v) override {
        v.add("enabled", enabled, true, "a boolean");
        v.add("count", count, 3, "an integer in 0..100", {0, 100});
        v.add("big", big, 0, "an integer without a declared range");
        v.add("gain", gain, 0.5f, "a float in -1..1", {-1, 1});
        v.add("free", freeFloat, 2.0f, "a float without a declared range");
        v.add("mode", mode, "fast", "a string with choices", {"fast", "exact", "off"});
        v.add("label", label, "none", "a free string");
        v.add("tint", tint, glm::vec3(1.0f, 0.5f, 0.25f), "a vec3 in 0..4", {0, 4});
    }
    void reflect(graph::Reflection& r) const override { r.output("color", kRgba32f); }

    bool enabled = false;
    int count = -1;
    int big = -1;
    float gain = -99.0f;
    float freeFloat = -99.0f;
    std::string mode, label;
    glm::vec3 tint{-1.0f};
};

// input `in`; output `out` keeping 2 previous frames, internal `state` keeping 1 (pass-declared
// history).
class Temporal : public TestPass {
public:
    void reflect(graph::Reflection& r) const override {
        r.input("in", kRgba32f);
        r.output("out", kRgba32f).sameAs("in").history(2);
        r.internal("state", vk::Format::eR32Sfloat).sameAs("in").history();
    }
};

// Parameters checked against each other and the edges (Pass::validate): lo <= hi, and
// useAux = true needs the optional input `aux` connected.
class Checked : public TestPass {
public:
    void params(graph::ParamVisitor& v) override {
        v.add("lo", lo, 0.0f, "lower bound", {0, 100});
        v.add("hi", hi, 1.0f, "upper bound; >= lo", {0, 100});
        v.add("useAux", useAux, false, "read `aux` (must then be connected)");
    }
    void reflect(graph::Reflection& r) const override {
        r.input("in", kRgba32f);
        r.input("aux", kRgba32f).optional();
        r.output("out", kRgba32f).sameAs("in");
    }
    void validate(const graph::ValidateContext& ctx) const override {
        if (hi < lo) ctx.fail("hi", "must be >= lo");
        if (useAux && !ctx.connected("aux")) ctx.fail("useAux", "needs the input 'aux'");
    }
    float lo = 0, hi = 0;
    bool useAux = false;
};

// Buffers sized by the render size: `list` 16 + 8 per pixel, `blocks` 384 per 32x32 block with
// one extra block per axis.
class SizedBuffers : public TestPass {
public:
    void reflect(graph::Reflection& r) const override {
        r.output("list", {}).bufferPerPixel(8, 16);
        r.output("blocks", {}).bufferPerBlock(32, 384, 0, 1);
    }
};

// Output `mask`: depends on the camera only (no scene geometry needed), cacheable.
class CameraOnly : public TestPass {
public:
    void reflect(graph::Reflection& r) const override { r.output("mask", kRgba32f).screen(); }
    bool usesCamera() const override { return true; }
    bool cacheable() const override { return true; }
};

// A mistake a pass author can make: history on an input.
class HistoryOnInput : public TestPass {
public:
    void reflect(graph::Reflection& r) const override {
        r.input("in", kRgba32f).history();
        r.output("out", kRgba32f);
    }
};

template <class T>
graph::PassTypeInfo testInfo(const char* type) {
    return {type, std::string("test pass ") + type, [] { return std::make_unique<T>(); }};
}

// A registry holding only the test pass types.
inline graph::PassRegistry testRegistry() {
    graph::PassRegistry r;
    r.add(testInfo<Src>("Src"));
    r.add(testInfo<LdrSrc>("LdrSrc"));
    r.add(testInfo<Filter>("Filter"));
    r.add(testInfo<Join>("Join"));
    r.add(testInfo<Half>("Half"));
    r.add(testInfo<Fixed>("Fixed"));
    r.add(testInfo<Persist>("Persist"));
    r.add(testInfo<Cached>("Cached"));
    r.add(testInfo<NeedsScene>("NeedsScene"));
    r.add(testInfo<BufferProducer>("BufferProducer"));
    r.add(testInfo<BufferConsumer>("BufferConsumer"));
    r.add(testInfo<Internal>("Internal"));
    r.add(testInfo<AllParams>("AllParams"));
    r.add(testInfo<Temporal>("Temporal"));
    r.add(testInfo<Checked>("Checked"));
    r.add(testInfo<SizedBuffers>("SizedBuffers"));
    r.add(testInfo<CameraOnly>("CameraOnly"));
    r.add(testInfo<HistoryOnInput>("HistoryOnInput"));
    return r;
}

}  // namespace fovea::testpasses
