#version 460
// GBuffer: primary visibility by ray casting in compute over the scene BVH - seed 000 §3.1 (the
// pre-pass: one ray per pixel for both eyes, shading data of the first hit stored in G-buffers)
// and §4.1 (one program for both screens: the right eye is the same dispatch with the pixel
// offset by the left screen's width; camera.glsl's cameraEyeOf/cameraRay do that mapping).
// Works over the full grid or over a sample layout (seed 000 §3.2's coordinates buffer, whose
// entries §3.3/§4.1 map to launch coordinates; ours already hold side-by-side coordinates); with
// a layout the pass first runs this shader with `clearPass` = 1 so unlisted pixels read invalid.
// Output encodings: docs/passes/GBuffer.md.
#extension GL_GOOGLE_include_directive : require

// Before the includes: sample_layout.glsl reads gl_WorkGroupSize, which is 1 x 1 x 1 until the
// local size is declared.
layout(local_size_x = 8, local_size_y = 8) in;

#include "../common/bvh.glsl"
#include "../common/camera.glsl"
#include "../common/random.glsl"  // the alpha test's seed
#include "../common/sample_layout.glsl"
#include "../common/scene_sample.glsl"
#define VISUAL_POLAR_PARAMS
#include "../common/visual_polar.glsl"

layout(rgba32ui) uniform writeonly uimage2D visibility;
layout(rgba32f) uniform writeonly image2D position;
layout(rgba16f) uniform writeonly image2D normal;
layout(r32f) uniform writeonly image2D depth;
layout(rgba16f) uniform writeonly image2D albedo;
layout(rg16f) uniform writeonly image2D motion;
layout(r32ui) uniform writeonly uimage2D material;
layout(rg16f) uniform writeonly image2D roughness_metallic;
layout(rgba16f) uniform writeonly image2D emission;
// VisualPolarWarp coords (seed 003 P5 §3.2): xy screen position, z 1 = traced, w eye.
uniform sampler2D coords;

layout(push_constant) uniform Params {
    uvec2 size;      // the outputs' size (the whole side-by-side image)
    uint useLayout;  // 1: trace the entries of sample_layout; 0: every pixel
    uint clearPass;  // 1: only write the invalid marker to every pixel (before a layout trace)
    uint useJitter;  // 1: offset rays by the camera's sub-pixel jitter
    uint useCoords;  // 1: trace the Visual-Polar grid of `coords` (outputs at its size)
    uint useVp;      // 1 (with useCoords): motion in Visual-Polar texels through the `vp` block
} pc;

const uint kFlagTraced = 1u;
const uint kFlagHit = 2u;
const uint kFlagClipped = 4u;  // a Visual-Polar texel that is never traced

// The "nothing here" value of every output: untraced pixels (visibility.w bit0 clear) and, except
// for visibility's flags, misses.
void writeEmpty(ivec2 p, uvec4 vis) {
    imageStore(visibility, p, vis);
    imageStore(position, p, vec4(0.0));
    imageStore(normal, p, vec4(0.0));
    imageStore(depth, p, vec4(0.0));
    imageStore(albedo, p, vec4(0.0));
    imageStore(motion, p, vec4(0.0));
    imageStore(material, p, uvec4(0u));
    imageStore(roughness_metallic, p, vec4(0.0));
    imageStore(emission, p, vec4(0.0));
}

// fp16 outputs: clamp to the half range so a huge (but finite) value never becomes Inf.
vec4 toHalf(vec4 v) { return clamp(v, vec4(-65504.0), vec4(65504.0)); }

void main() {
    uvec2 thread = gl_GlobalInvocationID.xy;
    if (pc.clearPass != 0u) {
        if (all(lessThan(thread, pc.size))) writeEmpty(ivec2(thread), uvec4(0u));
        return;
    }
    uvec2 pixel;
    uint samples;
    if (!sampleLayoutWorkItem(pc.useLayout != 0u, thread, pc.size, 1u, pixel, samples)) return;
    ivec2 p = ivec2(pixel);

    uint eye = cameraEyeOf(pixel.x);
    // The ray's image position; the same point is "now" for the motion vector below, so a static
    // camera gives exactly zero motion with or without jitter.
    vec2 now = vec2(pixel) + 0.5 + (pc.useJitter != 0u ? camera_info.jitter.xy : vec2(0.0));
    if (pc.useCoords != 0u) {
        // A regular (rho, phi) grid (P5 §3.2): the texel's ray goes through its screen position
        // (no jitter: the grid is fixed per gaze). Motion stays in screen pixels.
        vec4 c = texelFetch(coords, p, 0);
        eye = min(uint(max(c.w, 0.0)), cameraEyeCount() - 1u);
        if (c.z < 0.5) {
            writeEmpty(p, uvec4(0u, 0u, 0u, kFlagClipped | (eye << 8)));
            return;
        }
        now = c.xy;
    }
    vec3 origin, dir;
    cameraRay(eye, now, origin, dir);

    uint flags = kFlagTraced | (eye << 8);
    BvhHit hit;
    // BLEND's stochastic decisions (bvh.glsl): new per pixel and frame, the same on a rerun.
#if SCENE_HAS_ALPHA
    uint alphaSeed = hashCombine(pcgHash(camera_info.frame.x), uint(p.y) * pc.size.x + uint(p.x));
#else
    const uint alphaSeed = 0u;  // unused: nothing is alpha-tested
#endif
    if (!bvhClosestHit(origin, dir, 0.0, kSceneInfiniteDistance, alphaSeed, hit)) {
        if (!sceneHasEnvironment()) {
            writeEmpty(p, uvec4(0u, 0u, 0u, flags));
            return;
        }
        // The background: the environment's radiance as `emission` (Remodulate and the
        // denoisers add it back), the ray direction (octahedral) in visibility.yz for PathTrace.
        vec2 oct = octahedralEncode(dir);
        writeEmpty(p, uvec4(0u, floatBitsToUint(oct.x), floatBitsToUint(oct.y), flags));
        imageStore(emission, p, toHalf(vec4(sceneEnvironmentRadiance(dir), 0.0)));
        return;
    }

    SceneSurface s = sceneSurface(hit.triangle, hit.barycentrics);
    sceneApplyNormalMap(s);  // glTF §3.9.3: the denoisers' guide normal is the mapped one
    bool frontFacing = dot(s.geometricNormal, dir) < 0.0;
    // Shading normal flipped with the face the ray sees (not per pixel against the view vector:
    // interpolated normals may legitimately tilt away at silhouettes).
    vec3 n = frontFacing ? s.normal : -s.normal;
    SceneMaterialSample m = sceneSurfaceMaterial(s);

    // A camera that did not move gives exactly zero (not a rounding residue of the two camera
    // representations), so temporal passes can rely on "no motion" for a still view.
    CameraEye ce = camera_info.eyes[eye];
    vec2 previous = now;
    bool hasPrevious = true;
    if (ce.prevViewProj != ce.viewProj)
        hasPrevious = cameraPreviousPixel(eye, s.position, previous);
    vec2 mv = hasPrevious ? previous - now : vec2(0.0);
    // P5 §3.3: a gaze move re-centres the Visual-Polar grid, so even a still camera sees its
    // texels move (camera.glsl: gaze.zw is the previous frame's gaze).
    bool gazeMoved = any(notEqual(ce.gaze.zw, ce.gaze.xy));
    if (pc.useCoords != 0u && pc.useVp != 0u && hasPrevious && (mv != vec2(0.0) || gazeMoved)) {
        // P5 §3.3: world position -> previous screen position -> previous Visual-Polar texel,
        // mapped with the PREVIOUS frame's gaze (the grid's size and fovea do not depend on it).
        // x in columns; y in rows of the texel's column, wrapped to the shorter way round phi so
        // the seam never shows as a jump.
        VisualPolarMap m = vpMapOfEye(eye);
        VisualPolarMap prev = vpWithGaze(m, clamp(ce.gaze.zw, 0.0, 1.0) * m.screen);
        vec2 rt = vpToVisualPolar(prev, previous - vec2(float(eye * cameraEyeSize().x), 0.0));
        uint column = uint(p.x) - min(eye * m.width, uint(p.x));
        float n = float(vpRows(m, min(column, m.width - 1u)));  // >= 1
        float dRow = rt.y * n - 0.5 - float(p.y);
        dRow -= n * round(dRow / n);
        mv = vec2(rt.x * float(m.width) - 0.5 - float(column), dRow);
    }

    imageStore(visibility, p,
               uvec4(hit.triangle + 1u, floatBitsToUint(hit.barycentrics.x),
                     floatBitsToUint(hit.barycentrics.y), flags | kFlagHit));
    imageStore(position, p, vec4(s.position, 1.0));
    imageStore(normal, p, vec4(n, 1.0));
    imageStore(depth, p, vec4(cameraViewDepth(eye, s.position)));
    imageStore(albedo, p, toHalf(vec4(m.baseColor, 1.0)));
    imageStore(motion, p, toHalf(vec4(mv, 0.0, 0.0)));
    imageStore(material, p, uvec4(s.material + 1u));
    imageStore(roughness_metallic, p, vec4(m.roughness, m.metallic, 0.0, 0.0));
    imageStore(emission, p, toHalf(vec4(sceneEmission(s.material, s.uv, frontFacing), 1.0)));
}
