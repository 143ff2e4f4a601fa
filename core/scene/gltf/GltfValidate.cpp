#include "core/scene/gltf/GltfValidate.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <set>
#include <sstream>

#include "core/scene/gltf/GltfUsage.h"

namespace fovea::scene::gltf {

namespace {

std::string quote(const std::string& s) {
    return "'" + s + "'";
}

// A reference property: a non-negative integer below the size of its collection.
void checkRef(const JsonView& owner, const char* key, size_t size, const char* collection) {
    std::optional<uint64_t> index = owner.uint(key);
    if (index && *index >= size) {
        owner.issueAt(key, "refers to " + std::string(collection) + "[" + std::to_string(*index) +
                               "], but the file has " + std::to_string(size));
    }
}

void checkRefAt(const JsonView& array, size_t k, size_t size, const char* collection) {
    std::optional<uint64_t> index = array.uintAt(k);
    if (index && *index >= size) {
        array.element(k).issue("refers to " + std::string(collection) + "[" +
                               std::to_string(*index) + "], but the file has " +
                               std::to_string(size));
    }
}

bool allFinite(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

std::string formatNumber(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

// A number in [lo, hi]; `rule` describes the range for the message ("in [0, 1]").
void checkRange(const JsonView& owner, const char* key, double lo, double hi, const char* rule) {
    std::optional<double> v = owner.number(key);
    if (v && !(std::isfinite(*v) && *v >= lo && *v <= hi)) {
        owner.issueAt(key, "value " + formatNumber(*v) + " must be " + rule);
    }
}

// KHR_texture_transform on a texture info: `offset` and `scale` two finite numbers, `rotation`
// a finite number (radians), `texCoord` a non-negative integer (the extension's README schema).
void validateTextureTransform(const JsonView& transform) {
    if (!transform.isObject()) return;
    for (const char* key : {"offset", "scale"}) {
        if (auto v = transform.numbers(key, 2)) {
            if (!std::isfinite((*v)[0]) || !std::isfinite((*v)[1]))
                transform.issueAt(key, "must be finite numbers");
        }
    }
    checkRange(transform, "rotation", -HUGE_VAL, HUGE_VAL, "finite");
    transform.uint("texCoord");
}

// glTF 2.0 §5.26: the sampler enums by value (GL constants).
void validateSamplers(const GltfJson& gltf) {
    const auto checkEnum = [](const JsonView& sampler, const char* key,
                              std::initializer_list<uint64_t> allowed) {
        std::optional<uint64_t> v = sampler.uint(key);
        if (v && std::find(allowed.begin(), allowed.end(), *v) == allowed.end())
            sampler.issueAt(key, "invalid value " + std::to_string(*v));
    };
    for (size_t i = 0; i < gltf.count("samplers"); ++i) {
        JsonView sampler = gltf.entity("samplers", i);
        checkEnum(sampler, "magFilter", {9728, 9729});
        checkEnum(sampler, "minFilter", {9728, 9729, 9984, 9985, 9986, 9987});
        checkEnum(sampler, "wrapS", {33071, 33648, 10497});
        checkEnum(sampler, "wrapT", {33071, 33648, 10497});
    }
}

// "2.0" -> {2, 0}; nullopt unless it is <major>.<minor> with digits only.
std::optional<std::pair<int, int>> parseVersion(const std::string& text) {
    size_t dot = text.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == text.size() || text.size() > 12) {
        return std::nullopt;
    }
    auto digits = [](const std::string& s) {
        return !s.empty() &&
               std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    std::string major = text.substr(0, dot), minor = text.substr(dot + 1);
    if (!digits(major) || !digits(minor)) return std::nullopt;
    std::pair<int, int> version;
    auto parse = [](const std::string& s, int& out) {  // false on overflow ("99999999999")
        auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
        return ec == std::errc() && end == s.data() + s.size();
    };
    if (!parse(major, version.first) || !parse(minor, version.second)) return std::nullopt;
    return version;
}

void validateAsset(const GltfJson& gltf) {
    JsonView root = gltf.rootView();
    if (!root.require("asset")) return;
    JsonView asset = root.object("asset");
    if (!asset.require("version")) return;
    std::optional<std::string> version = asset.string("version");
    if (!version) return;
    auto parsed = parseVersion(*version);
    if (!parsed) {
        asset.issueAt("version", "invalid version " + quote(*version) + " (expected e.g. 2.0)");
        return;
    }
    if (parsed->first != 2) {
        asset.issueAt("version", "glTF " + *version + " is not supported (only 2.x)");
    }
    if (std::optional<std::string> min = asset.string("minVersion")) {
        auto minParsed = parseVersion(*min);
        if (!minParsed || *minParsed > *parsed) {
            asset.issueAt("minVersion", "invalid minVersion " + quote(*min));
        } else if (*minParsed > std::make_pair(2, 0)) {
            asset.issueAt("minVersion", "the file requires glTF " + *min +
                                            ", which is not supported (fovea reads 2.0)");
        }
    }
}

void validateExtensions(const GltfJson& gltf, std::vector<std::string>& warnings) {
    JsonView root = gltf.rootView();
    std::set<std::string> used;
    JsonView usedList = root.array("extensionsUsed");
    for (size_t i = 0; i < usedList.size(); ++i) {
        std::optional<std::string> name = usedList.stringAt(i);
        if (!name) continue;
        if (!used.insert(*name).second) {
            usedList.element(i).issue("extension " + quote(*name) + " is listed twice");
            continue;
        }
        const auto& supported = supportedExtensions();
        if (std::find(supported.begin(), supported.end(), *name) == supported.end()) {
            warnings.push_back(usedList.element(i).pointer() + ": optional extension " +
                               quote(*name) + " is not supported and is ignored");
        }
    }
    JsonView required = root.array("extensionsRequired");
    std::set<std::string> seen;
    for (size_t i = 0; i < required.size(); ++i) {
        std::optional<std::string> name = required.stringAt(i);
        if (!name) continue;
        JsonView element = required.element(i);
        if (!seen.insert(*name).second) {
            element.issue("extension " + quote(*name) + " is listed twice");
            continue;
        }
        const auto& supported = supportedExtensions();
        if (std::find(supported.begin(), supported.end(), *name) == supported.end()) {
            std::string list;
            for (const std::string& s : supported) list += (list.empty() ? "" : ", ") + s;
            element.issue("required extension " + quote(*name) +
                          " is not supported (fovea supports " + list + ")");
        } else if (!used.count(*name)) {
            element.issue("required extension " + quote(*name) + " is missing from extensionsUsed");
        }
    }
}

void validateReferences(const GltfJson& gltf) {
    size_t nodes = gltf.count("nodes"), meshes = gltf.count("meshes");
    size_t accessors = gltf.count("accessors"), views = gltf.count("bufferViews");
    size_t textures = gltf.count("textures");
    checkRef(gltf.rootView(), "scene", gltf.count("scenes"), "scenes");
    for (size_t s = 0; s < gltf.count("scenes"); ++s) {
        JsonView list = gltf.entity("scenes", s).array("nodes");
        for (size_t k = 0; k < list.size(); ++k) checkRefAt(list, k, nodes, "nodes");
    }
    for (size_t n = 0; n < nodes; ++n) {
        JsonView node = gltf.entity("nodes", n);
        JsonView children = node.array("children");
        for (size_t k = 0; k < children.size(); ++k) checkRefAt(children, k, nodes, "nodes");
        checkRef(node, "mesh", meshes, "meshes");
        checkRef(node, "camera", gltf.count("cameras"), "cameras");
        JsonView lights = node.object("extensions").object("KHR_lights_punctual");
        if (lights.isObject()) {
            lights.require("light");
            checkRef(lights, "light", gltf.lightCount(), "KHR_lights_punctual lights");
        }
    }
    for (size_t m = 0; m < meshes; ++m) {
        JsonView primitives = gltf.entity("meshes", m).array("primitives");
        for (size_t p = 0; p < primitives.size(); ++p) {
            JsonView prim = primitives.element(p);
            JsonView attributes = prim.object("attributes");
            for (const char* semantic :
                 {"POSITION", "NORMAL", "TEXCOORD_0", "COLOR_0", "TANGENT"}) {
                checkRef(attributes, semantic, accessors, "accessors");
            }
            checkRef(prim, "indices", accessors, "accessors");
            checkRef(prim, "material", gltf.count("materials"), "materials");
        }
    }
    for (size_t m = 0; m < gltf.count("materials"); ++m) {
        JsonView material = gltf.entity("materials", m);
        for (const TextureSlot& slot : renderedTextureSlots()) {
            JsonView owner = *slot.owner ? material.object(slot.owner) : material;
            JsonView info = owner.object(slot.name);
            if (!info.isObject()) continue;
            info.require("index");
            checkRef(info, "index", textures, "textures");
            info.uint("texCoord");
            validateTextureTransform(info.object("extensions").object("KHR_texture_transform"));
        }
    }
    for (size_t t = 0; t < textures; ++t) {
        JsonView texture = gltf.entity("textures", t);
        checkRef(texture, "source", gltf.count("images"), "images");
        checkRef(texture, "sampler", gltf.count("samplers"), "samplers");
    }
    for (size_t i = 0; i < gltf.count("images"); ++i) {
        checkRef(gltf.entity("images", i), "bufferView", views, "bufferViews");
    }
    for (size_t a = 0; a < accessors; ++a) {
        JsonView accessor = gltf.entity("accessors", a);
        checkRef(accessor, "bufferView", views, "bufferViews");
        JsonView sparse = accessor.object("sparse");
        checkRef(sparse.object("indices"), "bufferView", views, "bufferViews");
        checkRef(sparse.object("values"), "bufferView", views, "bufferViews");
    }
    for (size_t v = 0; v < views; ++v) {
        checkRef(gltf.entity("bufferViews", v), "buffer", gltf.count("buffers"), "buffers");
    }
}

void validateNodes(const GltfJson& gltf) {
    for (size_t n = 0; n < gltf.count("nodes"); ++n) {
        JsonView node = gltf.entity("nodes", n);
        auto matrix = node.numbers("matrix", 16);
        auto translation = node.numbers("translation", 3);
        auto rotation = node.numbers("rotation", 4);
        auto scale = node.numbers("scale", 3);
        for (const auto& [key, values] :
             {std::pair{"matrix", &matrix}, std::pair{"translation", &translation},
              std::pair{"rotation", &rotation}, std::pair{"scale", &scale}}) {
            if (*values && !allFinite(**values)) node.issueAt(key, "has a non-finite value");
        }
        if (node.has("matrix") &&
            (node.has("translation") || node.has("rotation") || node.has("scale"))) {
            node.issueAt("matrix", "a node must not have both a matrix and TRS properties");
        }
        if (rotation && allFinite(*rotation)) {
            double length2 = 0.0;
            for (double v : *rotation) length2 += v * v;
            if (!(length2 > 1e-12)) node.issueAt("rotation", "is a zero quaternion");
        }
    }
}

void validateMaterials(const GltfJson& gltf) {
    for (size_t m = 0; m < gltf.count("materials"); ++m) {
        JsonView material = gltf.entity("materials", m);
        JsonView pbr = material.object("pbrMetallicRoughness");
        if (auto color = pbr.numbers("baseColorFactor", 4)) {
            for (size_t i = 0; i < 4; ++i) {
                double v = (*color)[i];
                // A hair above 1 is float rounding in an exporter; clearly more is an error.
                if (!(std::isfinite(v) && v >= 0.0 && v <= 1.0 + 1e-4)) {
                    pbr.issueAt("baseColorFactor", "component " + std::to_string(i) + " = " +
                                                       formatNumber(v) + " is outside [0, 1]");
                    break;
                }
            }
        }
        checkRange(material.object("normalTexture"), "scale", -HUGE_VAL, HUGE_VAL, "finite");
        checkRange(pbr, "metallicFactor", 0.0, 1.0 + 1e-4, "in [0, 1]");
        checkRange(pbr, "roughnessFactor", 0.0, 1.0 + 1e-4, "in [0, 1]");
        if (auto emissive = material.numbers("emissiveFactor", 3)) {
            // Above 1 is out of the glTF range but common (HDR emitters): kept, see the loader.
            for (double v : *emissive) {
                if (!(std::isfinite(v) && v >= 0.0)) {
                    material.issueAt("emissiveFactor", "must be finite and non-negative");
                    break;
                }
            }
        }
        JsonView strength = material.object("extensions").object("KHR_materials_emissive_strength");
        checkRange(strength, "emissiveStrength", 0.0, HUGE_VAL, "finite and non-negative");
        material.boolean("doubleSided");
        if (auto mode = material.string("alphaMode")) {
            if (*mode != "OPAQUE" && *mode != "MASK" && *mode != "BLEND") {
                material.issueAt("alphaMode", "invalid alpha mode " + quote(*mode));
            }
        }
        // Schema minimum 0 (§3.9.4: texels with alpha >= cutoff are opaque); no maximum, a cutoff
        // above 1 hides the whole material.
        checkRange(material, "alphaCutoff", 0.0, HUGE_VAL, "finite and non-negative");
    }
}

void validateImages(const GltfJson& gltf) {
    for (size_t i = 0; i < gltf.count("images"); ++i) {
        JsonView image = gltf.entity("images", i);
        std::optional<std::string> uri = image.string("uri");
        std::optional<std::string> mime = image.string("mimeType");
        bool hasView = image.has("bufferView");
        if (image.has("uri") == hasView) {
            image.issue(hasView ? "has both 'uri' and 'bufferView'"
                                : "has neither 'uri' nor 'bufferView'");
        }
        if (hasView && !image.has("mimeType")) {
            image.issueAt("bufferView", "an image in a buffer view needs a 'mimeType'");
        }
        if (mime && *mime != "image/png" && *mime != "image/jpeg") {
            image.issueAt("mimeType", "unsupported image type " + quote(*mime) +
                                          " (PNG and JPEG are supported)");
        }
        if (uri && uri->rfind("data:", 0) == 0) {
            if (uri->rfind("data:image/png;base64,", 0) != 0 &&
                uri->rfind("data:image/jpeg;base64,", 0) != 0) {
                image.issueAt("uri",
                              "unsupported data URI (expected data:image/png;base64, or "
                              "data:image/jpeg;base64,)");
            } else {
                uint64_t size = 0;
                if (!base64DecodedSize(uri->substr(uri->find(',') + 1), size) || size == 0) {
                    image.issueAt("uri", "the data URI is not valid base64");
                }
            }
        } else if (uri && hasUriScheme(*uri)) {
            image.issueAt("uri", "unsupported URI " + quote(uri->substr(0, 60)) +
                                     " (only relative paths and data URIs are loaded)");
        }
        if (std::optional<uint64_t> view = image.uint("bufferView");
            view && *view < gltf.count("bufferViews") &&
            gltf.entity("bufferViews", *view).has("byteStride")) {
            image.issueAt("bufferView", "an image's buffer view must not have a byteStride");
        }
    }
}

void validateCameras(const GltfJson& gltf) {
    for (size_t c = 0; c < gltf.count("cameras"); ++c) {
        JsonView camera = gltf.entity("cameras", c);
        camera.require("type");
        std::optional<std::string> type = camera.string("type");
        if (camera.has("perspective") && camera.has("orthographic")) {
            camera.issue("has both 'perspective' and 'orthographic'");
        }
        if (type && *type != "perspective" && *type != "orthographic") {
            camera.issueAt("type", "invalid camera type " + quote(*type));
            continue;
        }
        if (!type) continue;
        if (!camera.require(*type)) continue;
        JsonView p = camera.object(*type);
        std::optional<double> znear, zfar = p.number("zfar");
        if (*type == "perspective") {
            p.require("yfov");
            p.require("znear");
            std::optional<double> yfov = p.number("yfov");
            if (yfov && !(std::isfinite(*yfov) && *yfov > 0.0 && *yfov < std::numbers::pi)) {
                p.issueAt("yfov", "must be in (0, pi)");
            }
            znear = p.number("znear");
            if (znear && !(std::isfinite(*znear) && *znear > 0.0)) {
                p.issueAt("znear", "must be positive and finite");
            }
            std::optional<double> aspect = p.number("aspectRatio");
            if (aspect && !(std::isfinite(*aspect) && *aspect > 0.0)) {
                p.issueAt("aspectRatio", "must be positive and finite");
            }
        } else {
            for (const char* key : {"xmag", "ymag", "zfar", "znear"}) p.require(key);
            for (const char* key : {"xmag", "ymag"}) {
                std::optional<double> v = p.number(key);
                if (v && !(std::isfinite(*v) && *v != 0.0)) p.issueAt(key, "must be non-zero");
            }
            znear = p.number("znear");
            if (znear && !(std::isfinite(*znear) && *znear >= 0.0)) {
                p.issueAt("znear", "must be non-negative and finite");
            }
        }
        if (znear && zfar && !(std::isfinite(*zfar) && *zfar > *znear)) {
            p.issueAt("zfar", "must be greater than znear");
        }
    }
}

void validateLights(const GltfJson& gltf) {
    for (size_t l = 0; l < gltf.lightCount(); ++l) {
        JsonView light = gltf.light(l);
        light.require("type");
        std::optional<std::string> type = light.string("type");
        if (type && *type != "point" && *type != "spot" && *type != "directional") {
            light.issueAt("type", "invalid light type " + quote(*type));
        }
        if (auto color = light.numbers("color", 3)) {
            for (double v : *color) {
                if (!(std::isfinite(v) && v >= 0.0)) {
                    light.issueAt("color", "must be finite and non-negative");
                    break;
                }
            }
        }
        checkRange(light, "intensity", 0.0, HUGE_VAL, "finite and non-negative");
        if (std::optional<double> range = light.number("range");
            range && !(std::isfinite(*range) && *range > 0.0)) {
            light.issueAt("range", "must be positive and finite");
        }
        if (type && *type == "spot" && light.require("spot")) {
            JsonView spot = light.object("spot");
            double inner = spot.number("innerConeAngle").value_or(0.0);
            double outer = spot.number("outerConeAngle").value_or(std::numbers::pi / 4.0);
            if (!(std::isfinite(outer) && outer > 0.0 && outer <= std::numbers::pi / 2.0)) {
                spot.issueAt("outerConeAngle", "must be in (0, pi/2]");
            } else if (!(std::isfinite(inner) && inner >= 0.0 && inner < outer)) {
                spot.issueAt("innerConeAngle", "must be in [0, outerConeAngle)");
            }
        }
    }
}

}  // namespace

const std::vector<std::string>& supportedExtensions() {
    static const std::vector<std::string> kSupported = {
        "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_mesh_quantization",
        "KHR_texture_transform"};
    return kSupported;
}

bool hasUriScheme(const std::string& uri) {
    // RFC 3986: scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":" before any '/', '?', '#'.
    size_t colon = uri.find(':');
    if (colon == std::string::npos || colon == 0) return false;
    if (uri.find_first_of("/?#") < colon) return false;
    return std::all_of(uri.begin(), uri.begin() + std::ptrdiff_t(colon), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.';
    });
}

bool base64DecodedSize(const std::string& payload, uint64_t& size) {
    if (payload.size() % 4 != 0) return false;
    size_t padding = 0;
    for (size_t i = 0; i < payload.size(); ++i) {
        char c = payload[i];
        bool alnum = std::isalnum(static_cast<unsigned char>(c)) != 0;
        if (c == '=') {
            if (i + 2 < payload.size()) return false;  // '=' only in the last two places
            ++padding;
        } else if (!(alnum || c == '+' || c == '/') || padding > 0) {
            return false;
        }
    }
    size = payload.size() / 4 * 3 - padding;
    return true;
}

void validateStructure(const GltfJson& gltf, const GltfDocument& doc,
                       std::vector<std::string>& warnings) {
    (void)doc;
    gltf.checkCollections();
    validateAsset(gltf);
    validateExtensions(gltf, warnings);
    validateReferences(gltf);
    validateNodes(gltf);
    validateMaterials(gltf);
    validateImages(gltf);
    validateSamplers(gltf);
    validateCameras(gltf);
    validateLights(gltf);
}

}  // namespace fovea::scene::gltf
