#include "core/scene/gltf/GltfLoader.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "core/scene/gltf/GltfDocument.h"
#include "core/scene/gltf/GltfMaterials.h"
#include "core/scene/gltf/GltfMesh.h"
#include "core/scene/gltf/GltfTextures.h"
#include "core/scene/gltf/GltfTiny.h"
#include "core/scene/gltf/GltfUsage.h"
#include "core/scene/gltf/GltfValidate.h"
#include "core/util/Error.h"

namespace fovea::scene {

namespace {

using gltf::GltfUsage;
using gltf::NodeInstance;

// Issues in what the scene uses are fatal: the first one is thrown (with a count of the rest,
// so a user fixing files sees the scale); the others become warnings.
void classifyIssues(const std::string& file, const gltf::Issues& issues, const GltfUsage& usage,
                    std::vector<std::string>& warnings) {
    std::set<std::pair<std::string, std::string>> seen;  // the same value may be read twice
    const gltf::Issue* first = nullptr;
    size_t fatal = 0;
    for (const gltf::Issue& issue : issues.list()) {
        if (!seen.insert({issue.pointer, issue.message}).second) continue;
        if (usage.isUsed(issue.pointer)) {
            if (!first) first = &issue;
            ++fatal;
        } else {
            warnings.push_back(issue.pointer + ": " + issue.message + " (unused, ignored)");
        }
    }
    if (first) {
        std::string more =
            fatal > 1 ? " (and " + std::to_string(fatal - 1) + " more problems)" : std::string();
        throw InputError(file, first->pointer, first->message + more);
    }
}

// The world-space frame of a node: origin, -Z (where glTF cameras look and lights shine) and +Y.
struct Frame {
    glm::vec3 position, forward, up;
};

Frame nodeFrame(const NodeInstance& instance, const std::string& file) {
    glm::dmat3 linear(instance.world);
    glm::dvec3 forward = linear * glm::dvec3(0.0, 0.0, -1.0);
    glm::dvec3 up = linear * glm::dvec3(0.0, 1.0, 0.0);
    double length = glm::length(forward);
    if (!(length > 0.0 && std::isfinite(length))) {
        throw InputError(file, "/nodes/" + std::to_string(instance.node),
                         "the node's transform collapses its -Z axis (zero scale?); a camera or "
                         "light cannot be placed on it");
    }
    forward /= length;
    up -= forward * glm::dot(up, forward);  // a sheared frame still gets a perpendicular up
    double upLength = glm::length(up);
    up = upLength > 1e-12 && std::isfinite(upLength) ? up / upLength : glm::dvec3(0.0, 1.0, 0.0);
    return {glm::vec3(instance.world[3]), glm::vec3(forward), glm::vec3(up)};
}

void addCamera(const tinygltf::Model& model, const NodeInstance& instance, int index,
               const std::string& file, Scene& scene) {
    const tinygltf::Camera& camera = model.cameras.at(size_t(index));
    if (camera.type != "perspective") {
        scene.warnings.push_back("/cameras/" + std::to_string(index) + ": " + camera.type +
                                 " cameras are not supported; skipped");
        return;
    }
    Frame frame = nodeFrame(instance, file);
    CameraDesc desc;
    desc.name = !camera.name.empty() ? camera.name : model.nodes.at(size_t(instance.node)).name;
    if (desc.name.empty()) desc.name = "camera " + std::to_string(index);
    desc.position = frame.position;
    desc.target = frame.position + frame.forward;
    desc.up = frame.up;
    desc.yfov = float(camera.perspective.yfov);
    desc.znear = float(camera.perspective.znear);
    scene.cameras.push_back(desc);
}

void addLight(const tinygltf::Model& model, const NodeInstance& instance, int index,
              const std::string& file, Scene& scene) {
    const tinygltf::Light& src = model.lights.at(size_t(index));
    Light light;
    light.name = !src.name.empty() ? src.name : "light " + std::to_string(index);
    light.type = src.type == "spot"          ? Light::Type::Spot
                 : src.type == "directional" ? Light::Type::Directional
                                             : Light::Type::Point;
    Frame frame = nodeFrame(instance, file);
    light.position = frame.position;
    light.direction = frame.forward;
    if (src.color.size() == 3) light.color = glm::vec3(src.color[0], src.color[1], src.color[2]);
    light.intensity = float(src.intensity);
    light.range = float(src.range);
    if (light.type == Light::Type::Spot) {
        light.innerConeAngle = float(src.spot.innerConeAngle);
        light.outerConeAngle = float(src.spot.outerConeAngle);
    }
    scene.lights.push_back(light);
}

void buildScene(const gltf::GltfDocument& doc, const tinygltf::Model& model, const GltfUsage& usage,
                Scene& scene) {
    gltf::MaterialTable materials(doc, model, scene, scene.warnings);
    std::set<std::string> meshWarnings;
    for (const NodeInstance& instance : usage.instances) {
        if (instance.mesh >= 0) {
            size_t mesh = size_t(instance.mesh);
            const auto& primitives = usage.primitives.at(mesh);
            for (size_t p = 0; p < primitives.size(); ++p) {
                if (!primitives[p]) continue;
                const tinygltf::Primitive& prim = model.meshes.at(mesh).primitives.at(p);
                uint32_t material = materials.idFor(prim.material);
                gltf::JsonView raw(&doc.json.at("meshes").at(mesh).at("primitives").at(p), "",
                                   nullptr);
                std::optional<uint64_t> index = raw.uint("indices");
                int64_t indices = index ? int64_t(*index) : -1;
                gltf::appendPrimitive(model, mesh, p, indices, instance.world, material,
                                      scene.materials[material].normalTexture >= 0, doc.file,
                                      scene.mesh, meshWarnings);
            }
        }
        if (instance.node < 0) continue;
        const tinygltf::Node& node = model.nodes.at(size_t(instance.node));
        if (node.camera >= 0) addCamera(model, instance, node.camera, doc.file, scene);
        gltf::JsonView raw(&doc.json.at("nodes").at(size_t(instance.node)), "", nullptr);
        std::optional<uint64_t> light =
            raw.object("extensions").object("KHR_lights_punctual").uint("light");
        if (light) addLight(model, instance, int(*light), doc.file, scene);
    }
    scene.warnings.insert(scene.warnings.end(), meshWarnings.begin(), meshWarnings.end());
}

}  // namespace

Scene loadGltf(const std::filesystem::path& path, const GltfLoadOptions& options,
               GltfLoadReport* report) {
    gltf::GltfDocument doc = gltf::readGltfDocument(path);
    doc.allowExternalUris = options.allowExternalUris;
    Scene scene;
    scene.source = doc.file;
    scene.warnings = doc.warnings;
    gltf::Issues issues;
    gltf::GltfJson json(doc.json, issues);
    gltf::validateStructure(json, doc, scene.warnings);
    gltf::validateData(json, doc);
    GltfUsage usage = gltf::computeUsage(json, scene.warnings, options.drawEveryMesh);
    if (report) report->usedPointers = usage.pointers();
    classifyIssues(doc.file, issues, usage, scene.warnings);
    gltf::probeUnusedImages(doc, usage, scene.warnings);

    tinygltf::Model model = gltf::loadTinyGltf(doc, usage);
    buildScene(doc, model, usage, scene);
    if (scene.mesh.triangles.empty()) {
        std::string where = usage.scene >= 0 ? "/scenes/" + std::to_string(usage.scene) : "";
        size_t nodes = size_t(std::count(usage.nodes.begin(), usage.nodes.end(), 1));
        throw InputError(doc.file, where,
                         "nothing to render: the scene has no triangles (" + std::to_string(nodes) +
                             " nodes visited)");
    }
    for (const glm::vec3& p : scene.mesh.positions) scene.bounds.grow(p);
    return scene;
}

}  // namespace fovea::scene
