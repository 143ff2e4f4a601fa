// Texture views (core/scene/TextureView.h, TextureSampling.h): KHR_texture_transform's matrix,
// the sampler's wrap modes and filters on the CPU, what the glTF loader reads into a material,
// and the validator's errors. The direction of the rotation is pinned by the Khronos sample
// model TextureTransformTest (../shared/scenes/assimp-khronos-samples/textureTransform), whose
// quads carry markers where the transformed arrow must point: green = correct, yellow = the
// transform ignored, red = rotated the wrong way. CPU only (sanitizer suite).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "core/scene/TextureSampling.h"
#include "tests/unit/SceneLoadTestUtil.h"

using namespace fovea;
using namespace fovea::scene;
using namespace fovea::scenetest;

namespace {

const Material* materialNamed(const Scene& s, const std::string& name) {
    for (const Material& m : s.materials)
        if (m.name == name) return &m;
    return nullptr;
}

// Centres of the quads drawn with material `name` (two triangles each, grouped by distance).
std::vector<glm::vec3> quadCentres(const Scene& s, const std::string& name) {
    std::vector<glm::vec3> centres;
    std::vector<int> counts;
    for (size_t t = 0; t < s.mesh.triangleCount(); ++t) {
        if (s.materials[s.mesh.materialIds[t]].name != name) continue;
        const glm::uvec3 tri = s.mesh.triangles[t];
        glm::vec3 c(0.0f);
        for (int k = 0; k < 3; ++k) c += s.mesh.positions[tri[k]] / 3.0f;
        size_t i = 0;
        while (i < centres.size() && glm::distance(centres[i] / float(counts[i]), c) > 0.2f) ++i;
        if (i == centres.size()) {
            centres.push_back(glm::vec3(0.0f));
            counts.push_back(0);
        }
        centres[i] += c;
        ++counts[i];
    }
    for (size_t i = 0; i < centres.size(); ++i) centres[i] /= float(counts[i]);
    return centres;
}

// The affine map from a quad's surface uv to world space, from one of its triangles.
struct UvFrame {
    glm::vec3 origin, du, dv;  // world = origin + u du + v dv
    glm::vec3 at(glm::vec2 uv) const { return origin + uv.x * du + uv.y * dv; }
    // uv of world point p (in the quad's plane): least squares on the two edge vectors.
    glm::vec2 uvOf(glm::vec3 p) const {
        const glm::vec3 d = p - origin;
        const float a = glm::dot(du, du), b = glm::dot(du, dv), c = glm::dot(dv, dv);
        const float x = glm::dot(d, du), y = glm::dot(d, dv), det = a * c - b * b;
        return {(c * x - b * y) / det, (a * y - b * x) / det};
    }
};
UvFrame uvFrame(const Scene& s, const std::string& material) {
    for (size_t t = 0; t < s.mesh.triangleCount(); ++t) {
        if (s.materials[s.mesh.materialIds[t]].name != material) continue;
        const glm::uvec3 tri = s.mesh.triangles[t];
        const glm::vec3 p0 = s.mesh.positions[tri[0]], p1 = s.mesh.positions[tri[1]],
                        p2 = s.mesh.positions[tri[2]];
        const glm::vec2 t0 = s.mesh.uvs[tri[0]], t1 = s.mesh.uvs[tri[1]], t2 = s.mesh.uvs[tri[2]];
        // Solve [du dv] * [t1 - t0, t2 - t0] = [p1 - p0, p2 - p0].
        const glm::mat2 uvEdges(t1 - t0, t2 - t0);
        const glm::mat2 inverse = glm::inverse(uvEdges);
        const glm::vec3 e1 = p1 - p0, e2 = p2 - p0;
        UvFrame f;
        f.du = inverse[0][0] * e1 + inverse[0][1] * e2;
        f.dv = inverse[1][0] * e1 + inverse[1][1] * e2;
        f.origin = p0 - t0.x * f.du - t0.y * f.dv;
        return f;
    }
    ADD_FAILURE() << "no triangle with material " << material;
    return {};
}

// The inverse of a transform's affine map.
glm::vec2 inverseApply(const TextureTransform& t, glm::vec2 target) {
    const glm::vec3 r0 = t.row0(), r1 = t.row1();
    const glm::mat2 m(glm::vec2(r0.x, r1.x), glm::vec2(r0.y, r1.y));  // columns
    return glm::inverse(m) * (target - glm::vec2(r0.z, r1.z));
}

}  // namespace

// The 2x3 rows equal T * R * S with R's rows [cos sin; -sin cos] (the extension's README).
TEST(TextureView, TransformIsTranslationRotationScale) {
    TextureTransform t;
    EXPECT_TRUE(t.isIdentity());
    EXPECT_EQ(t.apply({0.3f, -1.7f}), glm::vec2(0.3f, -1.7f));
    t.offset = {0.25f, -0.5f};
    t.rotation = 0.7f;
    t.scale = {2.0f, 0.5f};
    EXPECT_FALSE(t.isIdentity());
    const float c = std::cos(0.7f), s = std::sin(0.7f);
    for (glm::vec2 uv :
         {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(0, 1), glm::vec2(0.3f, 2.1f)}) {
        const glm::vec2 scaled = uv * t.scale;
        const glm::vec2 rotated(c * scaled.x + s * scaled.y, -s * scaled.x + c * scaled.y);
        const glm::vec2 expected = rotated + t.offset;
        EXPECT_NEAR(t.apply(uv).x, expected.x, 1e-6f);
        EXPECT_NEAR(t.apply(uv).y, expected.y, 1e-6f);
    }
}

TEST(TextureView, WrapModes) {
    // Texel indices -3 .. 6 of a 4-texel row (OpenGL 4.6 §8.14.2).
    const std::vector<int> repeat = {1, 2, 3, 0, 1, 2, 3, 0, 1, 2};
    const std::vector<int> clamp = {0, 0, 0, 0, 1, 2, 3, 3, 3, 3};
    const std::vector<int> mirror = {2, 1, 0, 0, 1, 2, 3, 3, 2, 1};  // period 0 1 2 3 3 2 1 0
    for (int i = -3; i <= 6; ++i) {
        const size_t k = size_t(i + 3);
        EXPECT_EQ(wrapTexel(i, 4, TextureWrap::Repeat), repeat[k]) << i;
        EXPECT_EQ(wrapTexel(i, 4, TextureWrap::ClampToEdge), clamp[k]) << i;
        EXPECT_EQ(wrapTexel(i, 4, TextureWrap::MirroredRepeat), mirror[k]) << i;
    }
}

// A 2x1 texture black | white: NEAREST gives exactly one texel per half (bilinear blends them,
// as every file was drawn before samplers were read); wrap modes outside [0, 1].
TEST(TextureView, NearestAndWrapOnTwoTexels) {
    Texture t;
    t.width = 2;
    t.height = 1;
    t.rgba8 = {0, 0, 0, 255, 255, 255, 255, 255};
    TextureView nearest;
    nearest.sampler.nearest = true;
    EXPECT_EQ(sampleTexture(t, nearest, {0.3f, 0.5f}, false).r, 0.0f);
    EXPECT_EQ(sampleTexture(t, nearest, {0.7f, 0.5f}, false).r, 1.0f);
    const TextureView bilinear;
    EXPECT_NEAR(sampleTexture(t, bilinear, {0.5f, 0.5f}, false).r, 0.5f, 1e-6f);
    nearest.sampler.wrapS = TextureWrap::ClampToEdge;
    EXPECT_EQ(sampleTexture(t, nearest, {-3.2f, 0.5f}, false).r, 0.0f);
    EXPECT_EQ(sampleTexture(t, nearest, {7.9f, 0.5f}, false).r, 1.0f);
    nearest.sampler.wrapS = TextureWrap::MirroredRepeat;
    EXPECT_EQ(sampleTexture(t, nearest, {1.3f, 0.5f}, false).r, 1.0f);  // mirrored: white first
    EXPECT_EQ(sampleTexture(t, nearest, {1.7f, 0.5f}, false).r, 0.0f);
    nearest.sampler.wrapS = TextureWrap::Repeat;
    EXPECT_EQ(sampleTexture(t, nearest, {1.3f, 0.5f}, false).r, 0.0f);
    EXPECT_EQ(sampleTexture(t, nearest, {1e9f + 0.25f, 0.5f}, false).a, 1.0f);  // no overflow
}

// The loader reads the sample model's transforms and its clamp sampler, and the arrow points at
// the green marker: the arrow's tip, where the yellow marker sits in texture space (uv (0.778,
// 0.778) of the untransformed quad), lands on the green marker after the inverse transform and
// is far from the red one. Also sampled: the texture along the way to the green marker is the
// arrow (dark), the way to the red one is background (white).
TEST(TextureView, SampleModelArrowPointsAtTheGreenMarker) {
    REQUIRE_SCENES();
    const Scene s = load("assimp-khronos-samples/textureTransform/TextureTransformTest.gltf");
    const Material* rotation = materialNamed(s, "Rotation");
    const Material* scale = materialNamed(s, "Scale");
    const Material* all = materialNamed(s, "All");
    const Material* offsetU = materialNamed(s, "Offset U");
    ASSERT_TRUE(rotation && scale && all && offsetU);
    EXPECT_NEAR(rotation->baseColorView.transform.rotation, 0.39269908f, 1e-6f);
    EXPECT_EQ(scale->baseColorView.transform.scale, glm::vec2(1.5f));
    EXPECT_EQ(offsetU->baseColorView.transform.offset, glm::vec2(0.5f, 0.0f));
    EXPECT_EQ(all->baseColorView.transform.offset, glm::vec2(-0.2f, -0.1f));
    EXPECT_EQ(rotation->baseColorView.sampler.wrapS, TextureWrap::ClampToEdge);
    EXPECT_EQ(rotation->baseColorView.sampler.wrapT, TextureWrap::ClampToEdge);
    EXPECT_FALSE(rotation->baseColorView.sampler.nearest);  // LINEAR
    EXPECT_TRUE(materialNamed(s, "Correct")->baseColorView.transform.isIdentity());

    const std::vector<glm::vec3> green = quadCentres(s, "Correct"), red = quadCentres(s, "Error");
    auto nearestTo = [](const std::vector<glm::vec3>& points, glm::vec3 p) {
        float best = std::numeric_limits<float>::max();
        for (const glm::vec3& q : points) best = std::min(best, glm::distance(p, q));
        return best;
    };
    const glm::vec2 tipInTexture(0.778f, 0.778f);
    for (const char* name : {"Rotation", "Scale", "All"}) {
        const Material* m = materialNamed(s, name);
        const UvFrame frame = uvFrame(s, name);
        const glm::vec3 tip = frame.at(inverseApply(m->baseColorView.transform, tipInTexture));
        EXPECT_LT(nearestTo(green, tip), 0.06f) << name << ": the arrow misses the green marker";
        if (std::string(name) == "Rotation") {
            EXPECT_GT(nearestTo(red, tip), 0.3f) << "rotated the wrong way";
        }
    }
    // Along the way from the uv origin to each marker of the rotation quad: dark = the arrow.
    const UvFrame frame = uvFrame(s, "Rotation");
    const Texture& arrow = s.textures[size_t(rotation->baseColorTexture)];
    auto darkness = [&](const std::vector<glm::vec3>& markers) {
        glm::vec3 marker = markers[0];
        for (const glm::vec3& q : markers)
            if (glm::distance(q, frame.at({0.5f, 0.5f})) <
                glm::distance(marker, frame.at({0.5f, 0.5f})))
                marker = q;
        const glm::vec2 target = frame.uvOf(marker);
        double sum = 0.0;
        int n = 0;
        for (float f = 0.3f; f <= 0.8f; f += 0.05f, ++n)
            sum += 1.0 - sampleTexture(arrow, rotation->baseColorView, target * f, true).g;
        return sum / n;
    };
    const double toGreen = darkness(green), toRed = darkness(red);
    // Near the corner the thick shaft covers both directions; further out only the right one.
    EXPECT_GT(toGreen, 0.6) << "the rotated arrow does not lie towards the green marker";
    EXPECT_GT(toGreen, toRed + 0.3) << toGreen << " vs " << toRed;
}

// Bad KHR_texture_transform values and sampler enums are errors naming the pointer: the sample
// model copied to a temporary folder with one value replaced at a time.
TEST(TextureView, ValidatorNamesBadTransformsAndSamplers) {
    REQUIRE_SCENES();
    const fs::path source = scenesDir() / "assimp-khronos-samples/textureTransform";
    const fs::path dir = fs::temp_directory_path() /
                         ("fovea_texture_view_" + std::to_string(std::random_device{}()));
    fs::create_directories(dir);
    for (const auto& entry : fs::directory_iterator(source))
        fs::copy_file(entry.path(), dir / entry.path().filename());
    std::ifstream in(source / "TextureTransformTest.gltf");
    const nlohmann::json original = nlohmann::json::parse(in);
    const std::string ext =
        "/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform";
    const std::vector<std::pair<std::string, nlohmann::json>> cases = {
        {"/materials/0" + ext + "/offset", nlohmann::json::array({0.5})},
        {"/materials/3" + ext + "/rotation", "left"},
        {"/materials/4" + ext + "/scale/1", "wide"},
        {"/materials/5" + ext + "/texCoord", -1},
        {"/samplers/0/wrapS", 1234},
        {"/samplers/0/magFilter", 9984},
    };
    for (const auto& [pointer, value] : cases) {
        nlohmann::json edited = original;
        edited[nlohmann::json::json_pointer(pointer)] = value;
        const fs::path file = dir / "edited.gltf";
        std::ofstream(file) << edited.dump();
        const InputError e = loadError(file);
        EXPECT_EQ(e.pointer(), pointer) << e.what();
    }
    // texCoord 1 through the extension's override: that texture is ignored, with a warning.
    nlohmann::json edited = original;
    edited[nlohmann::json::json_pointer("/materials/5" + ext + "/texCoord")] = 1;
    std::ofstream(dir / "override.gltf") << edited.dump();
    const Scene s = loadScene((dir / "override.gltf").string());
    EXPECT_TRUE(anyWarningContains(s, "TEXCOORD_1")) << "no warning for the override";
    EXPECT_EQ(materialNamed(s, "All")->baseColorTexture, -1);
    fs::remove_all(dir);
}
