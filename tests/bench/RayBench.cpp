// fovea_raybench: how far fovea's compute-shader BVH traversal (shaders/common/bvh.glsl) is from
// the CPU ray-tracing limit. One set of rays of the documents' 1 spp configuration (P2 §3.1:
// primary ray, one shadow ray to a light, one cosine-weighted bounce) is built on the CPU for a
// scene and traced twice: by fovea's BVH on the Vulkan device (GPU timestamps around each
// dispatch) and by Embree 3 on the CPU (all hardware threads). It also checks that both find the
// same closest triangles. A benchmark, not a test: figures go to docs/benchmarks.md.
//
//   fovea_raybench [SCENE] [WIDTHxHEIGHT] [--repeats N] [--device D]
#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/scene/Camera.h"
#include "core/scene/SceneGpu.h"
#include "core/scene/SceneLoader.h"
#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Context.h"
#include "core/vk/Resources.h"
#include "core/vk/Timestamps.h"

using namespace fovea;

namespace {

struct BenchRay {
    glm::vec4 originTMin;
    glm::vec4 directionTMax;
};

struct RaySet {
    const char* name;
    bool occlusion;
    std::vector<BenchRay> rays;
};

// The primary ray of camera.glsl's cameraRay (pixel centre, no jitter), mono camera.
BenchRay primaryRay(const scene::FrameCamera& cam, uint32_t x, uint32_t y) {
    const scene::EyeView& eye = cam.eyes[0];
    const glm::mat3 toWorld(glm::inverse(eye.view));
    const float t = std::tan(0.5f * cam.yfov), aspect = float(cam.eyeWidth) / float(cam.height);
    const glm::vec2 ndc(2.0f * (float(x) + 0.5f) / float(cam.eyeWidth) - 1.0f,
                        1.0f - 2.0f * (float(y) + 0.5f) / float(cam.height));
    const glm::vec3 d = glm::normalize(toWorld * glm::vec3(ndc.x * t * aspect, ndc.y * t, -1.0f));
    return {glm::vec4(eye.position, 0.0f), glm::vec4(d, 1e30f)};
}

class EmbreeScene {
public:
    explicit EmbreeScene(const scene::TriangleMesh& mesh) {
        mDevice = rtcNewDevice(nullptr);
        if (!mDevice) throw RuntimeError("Embree: rtcNewDevice failed");
        // Embree reports every allocation it makes (BVH, its geometry buffers, build scratch):
        // the peak is its memory next to fovea's scene buffers.
        rtcSetDeviceMemoryMonitorFunction(mDevice, &EmbreeScene::monitor, this);
        mScene = rtcNewScene(mDevice);
        rtcSetSceneBuildQuality(mScene, RTC_BUILD_QUALITY_HIGH);
        RTCGeometry g = rtcNewGeometry(mDevice, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                              RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                              mesh.positions.size()));
        for (size_t i = 0; i < mesh.positions.size(); ++i)
            for (int c = 0; c < 3; ++c) v[3 * i + c] = mesh.positions[i][c];
        auto* idx = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    3 * sizeof(unsigned), mesh.triangles.size()));
        for (size_t i = 0; i < mesh.triangles.size(); ++i)
            for (int c = 0; c < 3; ++c) idx[3 * i + c] = mesh.triangles[i][c];
        rtcCommitGeometry(g);
        rtcAttachGeometry(mScene, g);
        rtcReleaseGeometry(g);
        auto t0 = std::chrono::steady_clock::now();
        rtcCommitScene(mScene);
        mBuildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                       .count();
    }
    ~EmbreeScene() {
        rtcReleaseScene(mScene);
        rtcReleaseDevice(mDevice);
    }
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;
    // Bytes Embree holds after the build, and the most it held at once (during the build).
    int64_t bytes() const { return mBytes; }
    int64_t peakBytes() const { return mPeakBytes; }

    // Closest hit: (t, mesh triangle or -1, u, v). Occlusion: x = 1 when occluded.
    glm::vec4 trace(const BenchRay& r, bool occlusion) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh{};
        rh.ray.org_x = r.originTMin.x;
        rh.ray.org_y = r.originTMin.y;
        rh.ray.org_z = r.originTMin.z;
        rh.ray.tnear = r.originTMin.w;
        rh.ray.dir_x = r.directionTMax.x;
        rh.ray.dir_y = r.directionTMax.y;
        rh.ray.dir_z = r.directionTMax.z;
        rh.ray.tfar = r.directionTMax.w;
        rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        if (occlusion) {
            rtcOccluded1(mScene, &context, &rh.ray);
            return glm::vec4(rh.ray.tfar < 0.0f ? 1.0f : 0.0f);  // Embree sets tfar = -inf
        }
        rtcIntersect1(mScene, &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {0.0f, -1.0f, 0.0f, 0.0f};
        return {rh.ray.tfar, float(rh.hit.primID), rh.hit.u, rh.hit.v};
    }
    double buildMs() const { return mBuildMs; }

private:
    // RTCMemoryMonitorFunction: called before an allocation (bytes > 0) and after a release
    // (bytes < 0); true lets the allocation go ahead. Embree calls it from its build threads.
    static bool monitor(void* self, ssize_t bytes, bool /*post*/) {
        auto* s = static_cast<EmbreeScene*>(self);
        const int64_t now = s->mBytes.fetch_add(int64_t(bytes)) + int64_t(bytes);
        int64_t peak = s->mPeakBytes.load();
        while (now > peak && !s->mPeakBytes.compare_exchange_weak(peak, now)) {
        }
        return true;
    }
    RTCDevice mDevice = nullptr;
    RTCScene mScene = nullptr;
    double mBuildMs = 0.0;
    std::atomic<int64_t> mBytes{0}, mPeakBytes{0};
};

// Traces `rays` on all hardware threads; returns (results, milliseconds).
std::pair<std::vector<glm::vec4>, double> traceEmbree(const EmbreeScene& s, const RaySet& set) {
    std::vector<glm::vec4> out(set.rays.size());
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    auto t0 = std::chrono::steady_clock::now();
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            for (size_t i = t; i < set.rays.size(); i += threads)
                out[i] = s.trace(set.rays[i], set.occlusion);
        });
    for (auto& th : pool) th.join();
    return {
        out,
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()};
}

std::pair<std::vector<glm::vec4>, double> traceGpu(gpu::Context& ctx, const scene::SceneGpu& s,
                                                   const RaySet& set) {
    // The scene's defines with the alpha test off: Embree traces geometry only, so both sides
    // treat FlightHelmet's BLEND lenses as opaque (and opaque scenes run the plain traversal).
    gpu::ShaderDefines defines = s.defines();
    for (auto& [name, value] : defines)
        if (name == "SCENE_HAS_ALPHA") value = "0";
    defines.emplace_back("OCCLUSION", set.occlusion ? "1" : "0");
    gpu::ComputePipeline pipe(ctx, "bench/ray_query.comp", defines);
    const auto n = uint32_t(set.rays.size());
    gpu::Buffer rays(ctx, n * sizeof(BenchRay));
    gpu::Buffer results(ctx, n * sizeof(glm::vec4));
    rays.upload(ctx, set.rays.data(), n * sizeof(BenchRay));
    s.bind(pipe);
    pipe.bind("bench_rays", rays).bind("bench_results", results).set("count", n);
    gpu::TimestampPool timestamps(ctx, 2);
    ctx.submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        timestamps.reset(cmd);
        timestamps.write(cmd, 0);
        pipe.dispatch(cmd, n);
        timestamps.write(cmd, 1);
    });
    auto ticks = timestamps.readTicks(2);
    return {results.downloadAs<glm::vec4>(ctx), timestamps.ticksToMs(ticks[1] - ticks[0])};
}

glm::vec3 cosineDirection(const glm::vec3& n, float u1, float u2) {
    const float r = std::sqrt(u1), phi = 6.2831853f * u2;
    const glm::vec3 a = std::abs(n.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 t = glm::normalize(glm::cross(a, n)), b = glm::cross(n, t);
    return glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * b +
                          std::sqrt(std::max(0.0f, 1.0f - u1)) * n);
}

// Secondary rays from the primary hits: a cosine bounce and a shadow ray to a random point of a
// random emissive triangle (or towards a fixed sun direction when the scene has no emitter).
void makeSecondaryRays(const scene::Scene& sc, const RaySet& primary,
                       const std::vector<glm::vec4>& hits, RaySet& bounce, RaySet& shadow) {
    std::vector<uint32_t> emitters;
    for (uint32_t t = 0; t < sc.mesh.triangles.size(); ++t)
        if (sc.materials[sc.mesh.materialIds[t]].isEmissive()) emitters.push_back(t);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float eps = 1e-4f * glm::length(sc.bounds.max - sc.bounds.min);
    for (size_t i = 0; i < hits.size(); ++i) {
        if (hits[i].y < 0.0f) continue;
        const glm::uvec3 tri = sc.mesh.triangles[uint32_t(hits[i].y)];
        const glm::vec3 p0 = sc.mesh.positions[tri.x], p1 = sc.mesh.positions[tri.y],
                        p2 = sc.mesh.positions[tri.z];
        glm::vec3 n = glm::cross(p1 - p0, p2 - p0);
        if (glm::dot(n, n) < 1e-30f) continue;  // degenerate: no normal to bounce around
        n = glm::normalize(n);
        const glm::vec3 dir(primary.rays[i].directionTMax);
        if (glm::dot(n, dir) > 0.0f) n = -n;
        const glm::vec3 p = glm::vec3(primary.rays[i].originTMin) + hits[i].x * dir + eps * n;
        bounce.rays.push_back(
            {glm::vec4(p, 0.0f), glm::vec4(cosineDirection(n, unit(rng), unit(rng)), 1e30f)});
        if (emitters.empty()) {
            shadow.rays.push_back({glm::vec4(p, 0.0f),
                                   glm::vec4(glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f)), 1e30f)});
            continue;
        }
        const glm::uvec3 e = sc.mesh.triangles[emitters[rng() % emitters.size()]];
        float a = unit(rng), b = unit(rng);
        if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
        const glm::vec3 q = sc.mesh.positions[e.x] +
                            a * (sc.mesh.positions[e.y] - sc.mesh.positions[e.x]) +
                            b * (sc.mesh.positions[e.z] - sc.mesh.positions[e.x]);
        const float dist = glm::length(q - p);
        if (dist < 1e-6f) continue;  // the point is on the light: nothing to trace
        shadow.rays.push_back(
            {glm::vec4(p, 0.0f), glm::vec4((q - p) / dist, dist * (1.0f - 1e-4f))});
    }
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];  // v is never empty (repeats >= 1)
}

}  // namespace

int main(int argc, char** argv) {
    std::string sceneSpec = "builtin:cornell", size = "640x360", device;
    int repeats = 3;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--repeats" && i + 1 < argc)
            repeats = std::max(1, std::atoi(argv[++i]));
        else if (a == "--device" && i + 1 < argc)
            device = argv[++i];
        else if (a.find('x') != std::string::npos && std::isdigit(unsigned(a[0])))
            size = a;
        else if (a.rfind("--", 0) == 0) {
            std::fprintf(stderr,
                         "usage: fovea_raybench [SCENE] [WxH] [--repeats N] [--device D]\n");
            return 2;
        } else
            sceneSpec = a;
    }
    try {
        unsigned width = 0, height = 0;
        if (std::sscanf(size.c_str(), "%ux%u", &width, &height) != 2 || !width || !height)
            throw InputError("size", "", "expected WIDTHxHEIGHT, got '" + size + "'");
        scene::Scene sc = scene::loadScene(sceneSpec);
        gpu::ContextOptions options;
        options.device = device;
        gpu::Context ctx(options);
        scene::SceneGpu gpuScene(ctx, sc);
        EmbreeScene embree(sc.mesh);
        const scene::CameraDesc camDesc = sc.cameras.empty() ? sc.defaultCamera() : sc.cameras[0];
        const scene::FrameCamera cam =
            scene::makeFrameCamera(camDesc, width, height, {}, 0, nullptr, nullptr);

        RaySet primary{"primary", false, {}}, bounce{"bounce", false, {}},
            shadow{"shadow", true, {}};
        for (uint32_t y = 0; y < height; ++y)
            for (uint32_t x = 0; x < width; ++x) primary.rays.push_back(primaryRay(cam, x, y));
        auto [primaryHits, ignored] = traceEmbree(embree, primary);
        (void)ignored;
        makeSecondaryRays(sc, primary, primaryHits, bounce, shadow);

        std::printf("scene %s: %zu triangles, device %s, %u CPU threads for Embree\n",
                    sceneSpec.c_str(), sc.mesh.triangles.size(), ctx.deviceName().c_str(),
                    std::max(1u, std::thread::hardware_concurrency()));
        std::printf("BVH build: fovea %.1f ms (%u nodes), Embree %.1f ms\n",
                    gpuScene.bvhStats().buildMs, gpuScene.bvhStats().nodeCount, embree.buildMs());
        // What each traces from: fovea's scene buffers on the device (geometry, BVH, materials,
        // lights) against Embree's allocations (BVH and its copy of the geometry).
        const double triangles = double(std::max<size_t>(sc.mesh.triangles.size(), 1));
        std::printf(
            "memory: fovea GPU %.1f MB (%.0f B/triangle), Embree %.1f MB after the build "
            "(%.0f B/triangle), %.1f MB at its peak\n",
            double(gpuScene.totalBytes()) / 1e6, double(gpuScene.totalBytes()) / triangles,
            double(embree.bytes()) / 1e6, double(embree.bytes()) / triangles,
            double(embree.peakBytes()) / 1e6);
        std::printf("%-8s %9s %12s %12s %12s %12s %7s %9s\n", "rays", "count", "fovea ms",
                    "Embree ms", "fovea Mray/s", "Embree Mray/s", "ratio", "agree %");
        double totalRays = 0, totalFovea = 0, totalEmbree = 0;
        for (const RaySet* set : {&primary, &shadow, &bounce}) {
            if (set->rays.empty()) continue;
            std::vector<double> foveaMs, embreeMs;
            std::vector<glm::vec4> foveaOut, embreeOut;
            for (int r = 0; r < repeats; ++r) {
                auto [g, gms] = traceGpu(ctx, gpuScene, *set);
                auto [e, ems] = traceEmbree(embree, *set);
                foveaMs.push_back(gms);
                embreeMs.push_back(ems);
                foveaOut = std::move(g);
                embreeOut = std::move(e);
            }
            // Agreement: same occlusion answer, or the same mesh triangle for closest hits.
            size_t agree = 0;
            for (size_t i = 0; i < set->rays.size(); ++i) {
                if (set->occlusion) {
                    agree += foveaOut[i].x == embreeOut[i].x;
                    continue;
                }
                uint32_t g = glm::floatBitsToUint(foveaOut[i].y);
                int64_t fMesh = g == 0xFFFFFFFFu ? -1 : int64_t(gpuScene.triangleOrder()[g]);
                agree += fMesh == int64_t(embreeOut[i].y);
            }
            const double n = double(set->rays.size()), fm = median(foveaMs), em = median(embreeMs);
            totalRays += n;
            totalFovea += fm;
            totalEmbree += em;
            std::printf("%-8s %9zu %12.2f %12.2f %12.2f %12.2f %7.2f %9.3f\n", set->name,
                        set->rays.size(), fm, em, n / fm / 1e3, n / em / 1e3, fm / em,
                        100.0 * double(agree) / n);
        }
        std::printf("%-8s %9.0f %12.2f %12.2f %12.2f %12.2f %7.2f\n", "all", totalRays, totalFovea,
                    totalEmbree, totalRays / totalFovea / 1e3, totalRays / totalEmbree / 1e3,
                    totalFovea / totalEmbree);
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
