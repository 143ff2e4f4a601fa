#include "core/scene/BuiltinScenes.h"

#include <cmath>
#include <functional>
#include <map>
#include <numbers>

#include "core/scene/BuiltinGeometry.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"

namespace fovea::scene {

namespace {

using glm::vec3;

Material diffuse(const std::string& name, const vec3& albedo, const vec3& emission = vec3(0.0f)) {
    Material m;
    m.name = name;
    m.baseColor = glm::vec4(albedo, 1.0f);
    m.emissive = emission;
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    return m;
}

uint32_t addMaterial(Scene& scene, Material material) {
    scene.materials.push_back(std::move(material));
    return uint32_t(scene.materials.size() - 1);
}

void finish(Scene& scene) {
    for (const vec3& p : scene.mesh.positions) scene.bounds.grow(p);
}

// The Cornell box, https://www.graphics.cornell.edu/online/box/data.html: every vertex below is
// the published one (mm). Reflectances and emission are the published spectra (400-700 nm)
// converted to linear sRGB; docs/scenes.md explains the conversion. The light fills a hole in the
// ceiling instead of lying on it: the data has both at y = 548.8, and coplanar surfaces would
// fight; the ring around the hole shares the light's edges, so the ceiling stays watertight.
Scene buildCornell() {
    Scene scene;
    scene.source = "builtin:cornell";
    uint32_t white = addMaterial(scene, diffuse("white", vec3(0.7377f, 0.7361f, 0.7374f)));
    uint32_t red = addMaterial(scene, diffuse("red", vec3(0.4718f, 0.0469f, 0.0489f)));
    uint32_t green = addMaterial(scene, diffuse("green", vec3(0.0879f, 0.3984f, 0.0844f)));
    uint32_t light =
        addMaterial(scene, diffuse("light", vec3(0.78f), vec3(17.1971f, 11.4744f, 3.0619f)));
    MeshBuilder b(scene.mesh);
    const vec3 inside(278.0f, 274.4f, 279.6f);  // the box centre: walls face it
    const vec3 below(278.0f, 0.0f, 279.5f);
    // Floor, back wall, right wall (green, x = 0), left wall (red, x ~ 550).
    b.quadFacing({552.8f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 559.2f},
                 {549.6f, 0.0f, 559.2f}, white, inside);
    b.quadFacing({549.6f, 0.0f, 559.2f}, {0.0f, 0.0f, 559.2f}, {0.0f, 548.8f, 559.2f},
                 {556.0f, 548.8f, 559.2f}, white, inside);
    b.quadFacing({0.0f, 0.0f, 559.2f}, {0.0f, 0.0f, 0.0f}, {0.0f, 548.8f, 0.0f},
                 {0.0f, 548.8f, 559.2f}, green, inside);
    b.quadFacing({552.8f, 0.0f, 0.0f}, {549.6f, 0.0f, 559.2f}, {556.0f, 548.8f, 559.2f},
                 {556.0f, 548.8f, 0.0f}, red, inside);
    // Ceiling (556.0 x 559.2 at y = 548.8) as a ring around the light (213..343 x 227..332).
    const vec3 outer[4] = {{556.0f, 548.8f, 0.0f},
                           {556.0f, 548.8f, 559.2f},
                           {0.0f, 548.8f, 559.2f},
                           {0.0f, 548.8f, 0.0f}};
    const vec3 hole[4] = {{343.0f, 548.8f, 227.0f},
                          {343.0f, 548.8f, 332.0f},
                          {213.0f, 548.8f, 332.0f},
                          {213.0f, 548.8f, 227.0f}};
    for (int i = 0; i < 4; ++i) {
        int j = (i + 1) % 4;
        b.quadFacing(outer[i], outer[j], hole[j], hole[i], white, below);
    }
    b.quadFacing(hole[0], hole[1], hole[2], hole[3], light, below);
    // Short block (165 mm) and tall block (330 mm): top face, then four sides.
    auto block = [&](const vec3(&top)[4], float height) {
        vec3 centre(0.0f);
        for (const vec3& p : top) centre += p / 4.0f;
        centre.y = 0.5f * height;
        vec3 away = centre;  // faces point away from the block centre
        auto facingOut = [&](const vec3& a, const vec3& c, const vec3& d, const vec3& e) {
            vec3 mid = (a + c + d + e) / 4.0f;
            b.quadFacing(a, c, d, e, white, mid + (mid - away));
        };
        facingOut(top[0], top[1], top[2], top[3]);
        for (int i = 0; i < 4; ++i) {
            const vec3& p = top[i];
            const vec3& q = top[(i + 1) % 4];
            facingOut({p.x, 0.0f, p.z}, p, q, {q.x, 0.0f, q.z});
        }
    };
    const vec3 shortTop[4] = {{130.0f, 165.0f, 65.0f},
                              {82.0f, 165.0f, 225.0f},
                              {240.0f, 165.0f, 272.0f},
                              {290.0f, 165.0f, 114.0f}};
    const vec3 tallTop[4] = {{423.0f, 330.0f, 247.0f},
                             {265.0f, 330.0f, 296.0f},
                             {314.0f, 330.0f, 456.0f},
                             {472.0f, 330.0f, 406.0f}};
    block(shortTop, 165.0f);
    block(tallTop, 330.0f);

    // Camera: position (278, 273, -800), looking +z, focal length 0.035 on a 0.025 film.
    CameraDesc camera;
    camera.name = "cornell";
    camera.position = vec3(278.0f, 273.0f, -800.0f);
    camera.target = vec3(278.0f, 273.0f, 0.0f);
    camera.up = vec3(0.0f, 1.0f, 0.0f);
    camera.yfov = float(2.0 * std::atan(0.5 * 0.025 / 0.035));
    camera.znear = 1.0f;
    scene.cameras.push_back(camera);
    finish(scene);
    return scene;
}

Scene buildPlane() {
    using namespace builtin;
    Scene scene;
    scene.source = "builtin:plane";
    uint32_t plane = addMaterial(scene, diffuse("plane", vec3(kPlaneAlbedo)));
    // The emitter reflects nothing, so the plane's radiance is exactly one bounce.
    uint32_t emitter = addMaterial(scene, diffuse("emitter", vec3(0.0f), vec3(kPlaneEmission)));
    MeshBuilder b(scene.mesh);
    float s = kPlaneHalfSize, l = kPlaneLightHalfSize, h = kPlaneLightHeight;
    b.quadFacing({-s, 0, -s}, {s, 0, -s}, {s, 0, s}, {-s, 0, s}, plane, vec3(0, 1, 0));
    b.quadFacing({-l, h, -l}, {l, h, -l}, {l, h, l}, {-l, h, l}, emitter, vec3(0, 0, 0));
    CameraDesc camera;  // between plane and emitter, looking straight down at the centre
    camera.name = "plane";
    camera.position = vec3(0.0f, 0.5f * h, 0.0f);
    camera.target = vec3(0.0f);
    camera.up = vec3(0.0f, 0.0f, -1.0f);
    camera.yfov = 0.5f;
    camera.znear = 1e-3f;
    scene.cameras.push_back(camera);
    finish(scene);
    return scene;
}

Scene buildFurnace() {
    using namespace builtin;
    Scene scene;
    scene.source = "builtin:furnace";
    Material wall = diffuse("furnace", vec3(kFurnaceAlbedo), vec3(kFurnaceEmission));
    wall.doubleSided = true;  // whichever side a path meets, the same Le and rho
    uint32_t material = addMaterial(scene, wall);
    MeshBuilder b(scene.mesh);
    float s = kFurnaceHalfSize;
    vec3 c[8];
    for (int i = 0; i < 8; ++i) c[i] = vec3(i & 1 ? s : -s, i & 2 ? s : -s, i & 4 ? s : -s);
    const int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
    for (const auto& f : faces) b.quadFacing(c[f[0]], c[f[1]], c[f[2]], c[f[3]], material, vec3(0));
    CameraDesc camera;
    camera.name = "furnace";
    camera.position = vec3(0.0f);
    camera.target = vec3(0.0f, 0.0f, -1.0f);
    camera.yfov = 1.2f;
    camera.znear = 1e-3f;
    scene.cameras.push_back(camera);
    finish(scene);
    return scene;
}

const std::map<std::string, std::function<Scene()>>& registry() {
    static const std::map<std::string, std::function<Scene()>> kScenes = {
        {"cornell", &buildCornell},
        {"forest", [] { return buildForestScene(); }},
        {"forest-10m",
         [] {
             return buildForestScene({"builtin:forest-10m", 1024, 80, 2});
         }},
        {"plane", &buildPlane},
        {"furnace", &buildFurnace},
        {"glossy", &buildGlossyScene}};
    return kScenes;
}

}  // namespace

double builtin::planeCenterRadiance() {
    // Form factor from a point to a parallel rectangle (a x b at height h) with one corner
    // straight above it; the centred square is four such rectangles.
    double x = double(kPlaneLightHalfSize) / double(kPlaneLightHeight), y = x;
    double sx = std::sqrt(1.0 + x * x), sy = std::sqrt(1.0 + y * y);
    double corner =
        (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * std::numbers::pi);
    return double(kPlaneAlbedo) * double(kPlaneEmission) * 4.0 * corner;
}

double builtin::furnaceRadiance(int bounces) {
    double rho = kFurnaceAlbedo, le = kFurnaceEmission;
    if (bounces < 0) return le / (1.0 - rho);
    return le * (1.0 - std::pow(rho, bounces + 1)) / (1.0 - rho);
}

std::vector<std::string> builtinSceneNames() {
    std::vector<std::string> names;
    for (const auto& [name, build] : registry()) names.push_back("builtin:" + name);
    return names;
}

Scene loadBuiltinScene(const std::string& spec) {
    const std::string prefix = "builtin:";
    std::string name = spec.rfind(prefix, 0) == 0 ? spec.substr(prefix.size()) : spec;
    auto it = registry().find(name);
    if (it == registry().end()) {
        std::vector<std::string> names;
        for (const auto& [known, build] : registry()) names.push_back(known);
        std::string list;
        for (const std::string& full : builtinSceneNames())
            list += (list.empty() ? "" : ", ") + full;
        throw InputError(prefix + name, "",
                         "unknown built-in scene '" + name + "'" + didYouMean(name, names) +
                             "; built-in scenes: " + list);
    }
    return it->second();
}

}  // namespace fovea::scene
