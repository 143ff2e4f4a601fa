#include "core/scene/gltf/GltfUsage.h"

#include <algorithm>
#include <charconv>
#include <glm/gtc/quaternion.hpp>

namespace fovea::scene::gltf {

namespace {

constexpr uint64_t kModeTriangles = 4;

const char* modeName(uint64_t mode) {
    static const char* kNames[] = {"POINTS",    "LINES",          "LINE_LOOP",   "LINE_STRIP",
                                   "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};
    return mode < 7 ? kNames[mode] : "unknown";
}

bool anyOf(const std::vector<char>& flags) {
    return std::any_of(flags.begin(), flags.end(), [](char c) { return c != 0; });
}

bool flagAt(const std::vector<char>& flags, uint64_t index) {
    return index < flags.size() && flags[index];
}

void mark(std::vector<char>& flags, std::optional<uint64_t> index) {
    if (index && *index < flags.size()) flags[*index] = 1;
}

std::vector<std::string_view> splitPointer(std::string_view pointer) {
    std::vector<std::string_view> segments;
    if (pointer.empty() || pointer == "/") return segments;
    size_t start = pointer[0] == '/' ? 1 : 0;
    while (start <= pointer.size()) {
        size_t slash = pointer.find('/', start);
        if (slash == std::string_view::npos) slash = pointer.size();
        segments.push_back(pointer.substr(start, slash - start));
        start = slash + 1;
    }
    return segments;
}

std::optional<uint64_t> parseIndex(std::string_view text) {
    uint64_t value = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
    return value;
}

// The node graph must be a forest (glTF 2.0 §3.5.1): each node has at most one parent and no
// node is its own ancestor. Returns the (first) parent of each node, -1 for roots.
std::vector<int64_t> checkNodeGraph(const GltfJson& gltf) {
    size_t count = gltf.count("nodes");
    std::vector<int64_t> parent(count, -1);
    for (size_t p = 0; p < count; ++p) {
        JsonView children = gltf.entity("nodes", p).silent().array("children");
        for (size_t k = 0; k < children.size(); ++k) {
            std::optional<uint64_t> c = children.uintAt(k);
            if (!c || *c >= count) continue;  // GltfValidate reports the reference
            if (*c == p) {
                gltf.issues().add(children.pointerTo(k),
                                  "node " + std::to_string(p) + " is its own child (a cycle)");
            } else if (parent[*c] >= 0) {
                gltf.issues().add(children.pointerTo(k),
                                  "node " + std::to_string(*c) + " already has parent node " +
                                      std::to_string(parent[*c]) + " (nodes must form trees)");
            } else {
                parent[*c] = int64_t(p);
            }
        }
    }
    // Walk up from every node; 0 = unknown, 1 = on the current walk, 2 = reaches a root.
    std::vector<uint8_t> state(count, 0);
    for (size_t start = 0; start < count; ++start) {
        std::vector<size_t> walk;
        int64_t n = int64_t(start);
        while (n >= 0 && state[size_t(n)] == 0) {
            state[size_t(n)] = 1;
            walk.push_back(size_t(n));
            n = parent[size_t(n)];
        }
        if (n >= 0 && state[size_t(n)] == 1) {
            // `n` is on the current walk: the nodes from n upwards form a cycle.
            std::string path = std::to_string(n);
            for (int64_t m = parent[size_t(n)]; m != n && m >= 0; m = parent[size_t(m)]) {
                path += " -> " + std::to_string(m);
                if (path.size() > 200) {
                    path += " -> ...";
                    break;
                }
            }
            gltf.issues().add("/nodes/" + std::to_string(n), "the node hierarchy has a cycle: " +
                                                                 path + " -> " + std::to_string(n));
        }
        for (size_t w : walk) state[w] = 2;
    }
    return parent;
}

}  // namespace

const std::vector<TextureSlot>& renderedTextureSlots() {
    static const std::vector<TextureSlot> kSlots = {
        {"pbrMetallicRoughness", "baseColorTexture"},
        {"pbrMetallicRoughness", "metallicRoughnessTexture"},
        {"", "emissiveTexture"},
        {"", "normalTexture"}};
    return kSlots;
}

uint64_t effectiveTexCoord(const JsonView& info) {
    JsonView silent(info.raw(), info.pointer(), nullptr);
    JsonView ext = silent.object("extensions").object("KHR_texture_transform");
    if (auto over = ext.uint("texCoord")) return *over;
    return silent.uint("texCoord").value_or(0);
}

glm::dmat4 nodeLocalTransform(const JsonView& node) {
    JsonView silent(node.raw(), node.pointer(), nullptr);
    if (auto m = silent.numbers("matrix", 16)) {
        glm::dmat4 matrix(1.0);
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) matrix[c][r] = (*m)[size_t(c * 4 + r)];
        }
        return matrix;
    }
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (auto v = silent.numbers("translation", 3)) {
        t[3] = glm::dvec4((*v)[0], (*v)[1], (*v)[2], 1.0);
    }
    if (auto q = silent.numbers("rotation", 4)) {
        glm::dquat rotation((*q)[3], (*q)[0], (*q)[1], (*q)[2]);  // glTF stores x, y, z, w
        double length = glm::length(rotation);
        // Non-unit quaternions are normalised (a rounding slip in the exporter); a zero one is
        // reported by GltfValidate.
        if (length > 0.0 && std::isfinite(length)) r = glm::mat4_cast(rotation / length);
    }
    if (auto v = silent.numbers("scale", 3)) {
        s[0][0] = (*v)[0];
        s[1][1] = (*v)[1];
        s[2][2] = (*v)[2];
    }
    return t * r * s;
}

bool GltfUsage::isUsed(std::string_view pointer) const {
    std::vector<std::string_view> seg = splitPointer(pointer);
    if (seg.empty()) return true;
    auto flag = [&](const std::vector<char>& flags) {
        if (seg.size() < 2) return anyOf(flags);
        std::optional<uint64_t> index = parseIndex(seg[1]);
        return index ? flagAt(flags, *index) : anyOf(flags);
    };
    std::string_view name = seg[0];
    if (name == "nodes") return flag(nodes);
    if (name == "accessors") return flag(accessors);
    if (name == "bufferViews") return flag(bufferViews);
    if (name == "buffers") return flag(buffers);
    if (name == "materials") return flag(materials);
    if (name == "textures") return flag(textures);
    if (name == "images") return flag(images);
    if (name == "samplers") return flag(samplers);
    if (name == "cameras") return flag(cameras);
    if (name == "animations" || name == "skins" || name == "extras") return false;
    if (name == "scenes") {
        if (seg.size() < 2) return scene >= 0;
        std::optional<uint64_t> index = parseIndex(seg[1]);
        return !index || (scene >= 0 && *index == uint64_t(scene));
    }
    if (name == "meshes") {
        if (seg.size() >= 4 && seg[2] == "primitives") {
            std::optional<uint64_t> m = parseIndex(seg[1]), p = parseIndex(seg[3]);
            if (m && p) return *m < primitives.size() && flagAt(primitives[*m], *p);
        }
        return flag(meshes);
    }
    if (name == "extensions") {
        if (seg.size() < 2 || seg[1] != "KHR_lights_punctual") return seg.size() < 2;
        if (seg.size() >= 4 && seg[2] == "lights") {
            std::optional<uint64_t> index = parseIndex(seg[3]);
            return index ? flagAt(lights, *index) : anyOf(lights);
        }
        return anyOf(lights);
    }
    return true;  // /asset, /scene, /extensionsUsed, /extensionsRequired and the unknown
}

std::vector<std::string> GltfUsage::pointers() const {
    std::vector<std::string> out;
    if (scene >= 0) out.push_back("/scenes/" + std::to_string(scene));
    auto list = [&](const char* name, const std::vector<char>& flags) {
        for (size_t i = 0; i < flags.size(); ++i) {
            if (flags[i]) out.push_back(std::string(name) + std::to_string(i));
        }
    };
    list("/nodes/", nodes);
    for (size_t m = 0; m < primitives.size(); ++m) {
        for (size_t p = 0; p < primitives[m].size(); ++p) {
            if (primitives[m][p]) {
                out.push_back("/meshes/" + std::to_string(m) + "/primitives/" + std::to_string(p));
            }
        }
    }
    list("/accessors/", accessors);
    list("/bufferViews/", bufferViews);
    list("/buffers/", buffers);
    list("/materials/", materials);
    list("/textures/", textures);
    list("/images/", images);
    list("/samplers/", samplers);
    list("/cameras/", cameras);
    list("/extensions/KHR_lights_punctual/lights/", lights);
    return out;
}

namespace {

// Marks a drawn mesh, its rendered primitives and what they reference.
void useMesh(const GltfJson& gltf, uint64_t mesh, GltfUsage& usage, std::vector<char>& warnedMeshes,
             std::vector<std::string>& warnings) {
    usage.meshes[mesh] = 1;
    JsonView meshView(gltf.entity("meshes", mesh).raw(), "/meshes/" + std::to_string(mesh),
                      nullptr);
    JsonView primitives = meshView.array("primitives");
    usage.primitives[mesh].assign(primitives.size(), 0);
    bool warn = !warnedMeshes[mesh];
    warnedMeshes[mesh] = 1;
    for (size_t p = 0; p < primitives.size(); ++p) {
        JsonView prim = primitives.element(p);
        if (!prim.isObject()) continue;
        uint64_t mode = prim.uint("mode").value_or(kModeTriangles);
        JsonView attributes = prim.object("attributes");
        if (mode != kModeTriangles || !attributes.has("POSITION")) {
            if (warn) {
                warnings.push_back(prim.pointer() + ": " +
                                   (mode != kModeTriangles
                                        ? "mode " + std::to_string(mode) + " (" + modeName(mode) +
                                              ") is not rendered (only TRIANGLES)"
                                        : std::string("no POSITION attribute")) +
                                   "; primitive skipped");
            }
            continue;
        }
        usage.primitives[mesh][p] = 1;
        mark(usage.accessors, attributes.uint("POSITION"));
        mark(usage.accessors, attributes.uint("NORMAL"));
        mark(usage.accessors, attributes.uint("TEXCOORD_0"));
        mark(usage.accessors, attributes.uint("COLOR_0"));
        mark(usage.accessors, attributes.uint("TANGENT"));
        mark(usage.accessors, prim.uint("indices"));
        mark(usage.materials, prim.uint("material"));
        if (warn && prim.array("targets").size() > 0) {
            warnings.push_back(prim.pointer() +
                               ": morph targets are not supported; the base shape is drawn");
        }
    }
}

// Marks what one used node references.
void useNode(const GltfJson& gltf, NodeInstance& instance, GltfUsage& usage,
             std::vector<char>& warnedMeshes, std::vector<std::string>& warnings) {
    JsonView node(gltf.entity("nodes", uint64_t(instance.node)).raw(),
                  "/nodes/" + std::to_string(instance.node), nullptr);
    usage.nodes[size_t(instance.node)] = 1;
    mark(usage.cameras, node.uint("camera"));
    mark(usage.lights, node.object("extensions").object("KHR_lights_punctual").uint("light"));
    if (node.has("skin")) {
        warnings.push_back(node.pointer() +
                           ": skins are not supported; the mesh is drawn in its bind pose");
    }
    std::optional<uint64_t> mesh = node.uint("mesh");
    if (!mesh || *mesh >= usage.meshes.size()) return;
    instance.mesh = int64_t(*mesh);
    useMesh(gltf, *mesh, usage, warnedMeshes, warnings);
}

void useMaterials(const GltfJson& gltf, GltfUsage& usage, std::vector<std::string>& warnings) {
    for (size_t m = 0; m < usage.materials.size(); ++m) {
        if (!usage.materials[m]) continue;
        JsonView material(gltf.entity("materials", m).raw(), "/materials/" + std::to_string(m),
                          nullptr);
        for (const TextureSlot& slot : renderedTextureSlots()) {
            JsonView owner = *slot.owner ? material.object(slot.owner) : material;
            JsonView info = owner.object(slot.name);
            if (!info.isObject()) continue;
            const uint64_t texCoord = effectiveTexCoord(info);
            if (texCoord != 0) {
                warnings.push_back(info.pointer() + ": uses TEXCOORD_" + std::to_string(texCoord) +
                                   "; only TEXCOORD_0 is supported, the texture is ignored");
                continue;
            }
            mark(usage.textures, info.uint("index"));
        }
    }
    for (size_t t = 0; t < usage.textures.size(); ++t) {
        if (!usage.textures[t]) continue;
        JsonView texture(gltf.entity("textures", t).raw(), "", nullptr);
        mark(usage.images, texture.uint("source"));
        mark(usage.samplers, texture.uint("sampler"));
    }
}

void useData(const GltfJson& gltf, GltfUsage& usage) {
    for (size_t a = 0; a < usage.accessors.size(); ++a) {
        if (!usage.accessors[a]) continue;
        JsonView accessor(gltf.entity("accessors", a).raw(), "", nullptr);
        mark(usage.bufferViews, accessor.uint("bufferView"));
        JsonView sparse = accessor.object("sparse");
        mark(usage.bufferViews, sparse.object("indices").uint("bufferView"));
        mark(usage.bufferViews, sparse.object("values").uint("bufferView"));
    }
    for (size_t i = 0; i < usage.images.size(); ++i) {
        if (usage.images[i]) {
            mark(usage.bufferViews,
                 JsonView(gltf.entity("images", i).raw(), "", nullptr).uint("bufferView"));
        }
    }
    for (size_t v = 0; v < usage.bufferViews.size(); ++v) {
        if (usage.bufferViews[v]) {
            mark(usage.buffers,
                 JsonView(gltf.entity("bufferViews", v).raw(), "", nullptr).uint("buffer"));
        }
    }
}

// The root nodes to draw: those of the chosen scene, or every parentless node without scenes.
std::vector<uint64_t> sceneRoots(const GltfJson& gltf, const std::vector<int64_t>& parent,
                                 GltfUsage& usage, std::vector<std::string>& warnings) {
    size_t sceneCount = gltf.count("scenes");
    std::optional<uint64_t> chosen =
        JsonView(&gltf.root(), "", nullptr).uint("scene");  // GltfValidate checks the range
    if (chosen && *chosen >= sceneCount) return {};
    if (!chosen && sceneCount > 0) chosen = 0;
    std::vector<uint64_t> roots;
    if (!chosen) {
        for (size_t n = 0; n < parent.size(); ++n) {
            if (parent[n] < 0) roots.push_back(n);
        }
        if (!parent.empty()) {
            warnings.push_back("the file defines no scenes; drawing all " +
                               std::to_string(roots.size()) + " root nodes");
        }
        return roots;
    }
    usage.scene = int64_t(*chosen);
    JsonView nodes = gltf.entity("scenes", *chosen).silent().array("nodes");
    std::vector<char> listed(parent.size(), 0);
    for (size_t k = 0; k < nodes.size(); ++k) {
        std::optional<uint64_t> n = nodes.uintAt(k);
        if (!n || *n >= parent.size()) continue;
        if (listed[*n]) {
            gltf.issues().add(nodes.pointerTo(k),
                              "node " + std::to_string(*n) + " is listed twice in the scene");
            continue;
        }
        listed[*n] = 1;
        if (parent[*n] >= 0) {
            gltf.issues().add(nodes.pointerTo(k), "node " + std::to_string(*n) +
                                                      " is not a root: it is a child of node " +
                                                      std::to_string(parent[*n]));
        }
        roots.push_back(*n);
    }
    return roots;
}

}  // namespace

GltfUsage computeUsage(const GltfJson& gltf, std::vector<std::string>& warnings,
                       bool drawEveryMesh) {
    GltfUsage usage;
    size_t nodeCount = gltf.count("nodes");
    usage.nodes.assign(nodeCount, 0);
    usage.meshes.assign(gltf.count("meshes"), 0);
    usage.primitives.assign(usage.meshes.size(), {});
    usage.accessors.assign(gltf.count("accessors"), 0);
    usage.bufferViews.assign(gltf.count("bufferViews"), 0);
    usage.buffers.assign(gltf.count("buffers"), 0);
    usage.materials.assign(gltf.count("materials"), 0);
    usage.textures.assign(gltf.count("textures"), 0);
    usage.images.assign(gltf.count("images"), 0);
    usage.samplers.assign(gltf.count("samplers"), 0);
    usage.cameras.assign(gltf.count("cameras"), 0);
    usage.lights.assign(gltf.lightCount(), 0);

    std::vector<int64_t> parent = checkNodeGraph(gltf);
    std::vector<uint64_t> roots = sceneRoots(gltf, parent, usage, warnings);

    // Iterative depth-first walk (a chain of 100k nodes must not overflow the stack); `visited`
    // makes every node count once even when the file has cycles or shared children.
    std::vector<char> visited(nodeCount, 0), warnedMeshes(usage.meshes.size(), 0);
    std::vector<NodeInstance> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
        stack.push_back({int64_t(*it), -1, glm::dmat4(1.0)});
    }
    while (!stack.empty()) {
        NodeInstance top = stack.back();
        stack.pop_back();
        if (visited[size_t(top.node)]) continue;
        visited[size_t(top.node)] = 1;
        JsonView node = gltf.entity("nodes", uint64_t(top.node)).silent();
        top.world = top.world * nodeLocalTransform(node);
        useNode(gltf, top, usage, warnedMeshes, warnings);
        usage.instances.push_back(top);
        JsonView children = node.array("children");
        for (size_t k = children.size(); k-- > 0;) {
            std::optional<uint64_t> c = children.uintAt(k);
            if (c && *c < nodeCount && !visited[*c]) {
                stack.push_back({int64_t(*c), -1, top.world});
            }
        }
    }
    if (drawEveryMesh) {
        for (size_t m = 0; m < usage.meshes.size(); ++m) {
            if (usage.meshes[m]) continue;
            usage.instances.push_back({-1, int64_t(m), glm::dmat4(1.0)});
            useMesh(gltf, m, usage, warnedMeshes, warnings);
        }
    }
    useMaterials(gltf, usage, warnings);
    useData(gltf, usage);
    return usage;
}

}  // namespace fovea::scene::gltf
