// Sample layouts (docs/sample-layouts.md): the optional `layout` input of GBuffer and PathTrace,
// seed 000's "coordinates buffer" (§3.2, §4.1) - the pixels of the whole side-by-side stereo
// image that get rays, with a sample count each. Mirrors core/scene/SampleLayout.h (std430):
//     uint count; uint maxSamples; uint pad0; uint pad1;  then  uvec2 entries[]
//     entries[i].x = x | (y << 16), entries[i].y = samples (>= 1; 0 = ignored)
//
// The graph field is `layout`, a GLSL keyword, so the block instance is `sample_layout` and the
// pass binds it itself (scene::SampleLayoutInput; pass scene::kSampleLayoutBinding as an extra
// resource to createPipeline). An open input gets a zeroed buffer: count 0.
//
// How a pass uses it: dispatch threads over the image (width x height, 2D) in both modes and
// call sampleLayoutWorkItem with a push constant `useLayout` (= ctx.connected("layout")):
//   - full grid (useLayout == 0): thread (x, y) is pixel (x, y) with `defaultSamples`;
//   - layout: each workgroup takes a chunk of consecutive entries (one per lane), and chunks
//     are numbered down the workgroup columns (chunk = wx * groupsY + wy), so the workgroups that
//     hold entries are spread over the whole dispatch; at most width * height entries are read
//     (a layout lists each pixel at most once); invalid entries return false.
//   Why column order: llvmpipe hands each CPU thread one contiguous range of the row-major
//   workgroup index, so with row-major chunks a list shorter than the image (issue 15's sparse
//   periphery) put all its work in the first threads' ranges and left the others idle: PathTrace
//   got 1.83x from 2 threads on a full list but 1.11x at 66 % of the pixels. A GPU schedules
//   workgroups dynamically and does not care; lanes still get consecutive (row-ordered) entries.
// With a layout, pixels not listed must be cleared to the pass's invalid marker first.
//
// Include it AFTER the shader's `layout(local_size_x = ...) in;`: sampleLayoutWorkItem reads
// gl_WorkGroupSize, which glslang takes as 1 x 1 x 1 before that declaration (a shader that
// includes this first reads only the first entries; GBufferTest.LayoutTracesOnlyListedPixels).
//
// Define SAMPLE_LAYOUT_WRITE before including to get a writable block (the SampleList pass).
#ifndef FOVEA_SAMPLE_LAYOUT_GLSL
#define FOVEA_SAMPLE_LAYOUT_GLSL

#ifdef SAMPLE_LAYOUT_WRITE
#define SAMPLE_LAYOUT_ACCESS
#else
#define SAMPLE_LAYOUT_ACCESS readonly
#endif

layout(std430) SAMPLE_LAYOUT_ACCESS buffer SampleLayout {
    uint count;
    uint maxSamples;
    uint pad0;
    uint pad1;
    uvec2 entries[];
} sample_layout;

const uint kSampleLayoutMaxCoordinate = 0xFFFFu;

uint sampleLayoutPack(uvec2 pixel) { return (pixel.x & 0xFFFFu) | (pixel.y << 16); }
uvec2 sampleLayoutUnpack(uint packed) { return uvec2(packed & 0xFFFFu, packed >> 16); }

// Entries a reader may touch: the header's count, clamped to what the bound buffer holds (a
// short or zeroed buffer never leads to an out-of-bounds read).
uint sampleLayoutCount() {
    return min(sample_layout.count, uint(sample_layout.entries.length()));
}

// Entry i with its pixel checked against `imageSize`. False (and samples 0) for i beyond the
// count, a sample count of 0 or a pixel outside the image: such entries are ignored.
bool sampleLayoutEntry(uint i, uvec2 imageSize, out uvec2 pixel, out uint samples) {
    pixel = uvec2(0u);
    samples = 0u;
    if (i >= sampleLayoutCount()) return false;
    uvec2 e = sample_layout.entries[i];
    pixel = sampleLayoutUnpack(e.x);
    samples = e.y;
    if (samples == 0u || any(greaterThanEqual(pixel, imageSize))) {
        samples = 0u;
        return false;
    }
    return true;
}

// The work of thread `thread` (gl_GlobalInvocationID.xy of a width x height dispatch): which
// pixel to trace and with how many samples. False = nothing to do for this thread.
bool sampleLayoutWorkItem(bool useLayout, uvec2 thread, uvec2 imageSize, uint defaultSamples,
                          out uvec2 pixel, out uint samples) {
    pixel = thread;
    samples = 0u;
    if (!useLayout) {
        if (any(greaterThanEqual(thread, imageSize))) return false;
        samples = defaultSamples;
        return defaultSamples > 0u;
    }
    // Chunks of gl_WorkGroupSize.x * y entries, numbered down the workgroup columns (see above).
    // Capacity: groups * lanes >= width * height >= any valid count, so every entry has a lane
    // (lanes of edge workgroups outside the image take entries too).
    const uint lanes = gl_WorkGroupSize.x * gl_WorkGroupSize.y;
    uint chunk = gl_WorkGroupID.x * gl_NumWorkGroups.y + gl_WorkGroupID.y;
    uint entry = chunk * lanes + gl_LocalInvocationIndex;
    if (entry >= imageSize.x * imageSize.y) return false;  // the documented cap, as before
    return sampleLayoutEntry(entry, imageSize, pixel, samples);
}

#endif
