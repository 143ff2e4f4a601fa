// Graph file -> GraphDesc, with the structural checks of docs/graph-format.md. Checks run in file
// order and stop at the first error, so the message points at the earliest mistake.
#include <map>

#include "core/graph/GraphDesc.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"
#include "core/util/JsonUtil.h"

namespace fovea::graph {

namespace {

const std::vector<std::string> kTopFields = {
    "version", "name", "description", "defaults", "passes", "edges", "order", "outputs", "editor"};
const std::vector<std::string> kDefaultsFields = {"size",   "frames", "seed",        "scene",
                                                  "camera", "stereo", "camera_model"};
const std::vector<std::string> kPassFields = {"name", "type", "params", "enabled"};
const std::vector<std::string> kEdgeFields = {"from", "to", "delay"};
const std::vector<std::string> kOrderFields = {"before", "after"};
const std::vector<std::string> kOutputFields = {"source"};

class GraphParser {
public:
    GraphParser(const nlohmann::json& root, const std::string& file) : mTop(root, file) {
        mGraph.file = file;
    }

    GraphDesc parse() {
        if (!mTop.value().is_object()) {
            mTop.fail("the top level must be an object, got " + jsonTypeName(mTop.value()));
        }
        // The version comes before everything else: a newer file may use fields we do not know.
        JsonNode version = mTop.require("version");
        int64_t number = version.asInt();
        if (number != kGraphFormatVersion) {
            version.fail("unsupported graph format version " + std::to_string(number) +
                         " (this fovea reads version " + std::to_string(kGraphFormatVersion) + ")");
        }
        mGraph.version = kGraphFormatVersion;
        mTop.checkFields(kTopFields);
        if (auto name = mTop.find("name")) mGraph.name = name->asString();
        if (auto description = mTop.find("description")) {
            mGraph.description = description->asString();
        }
        if (auto defaults = mTop.find("defaults")) parseDefaults(*defaults);
        parsePasses(mTop.require("passes"));
        if (auto edges = mTop.find("edges")) {
            for (const JsonNode& edge : edges->elements()) parseEdge(edge);
        }
        if (auto order = mTop.find("order")) {
            for (const JsonNode& entry : order->elements()) parseOrder(entry);
        }
        if (auto outputs = mTop.find("outputs")) {
            for (const JsonNode& entry : outputs->elements()) parseOutput(entry);
        }
        if (auto editor = mTop.find("editor")) mGraph.editor = editor->expectObject().value();
        return std::move(mGraph);
    }

private:
    void parseDefaults(const JsonNode& node) {
        node.checkFields(kDefaultsFields);
        if (auto size = node.find("size")) {
            if (!size->value().is_array() || size->value().size() != 2) {
                std::string got = size->value().is_array()
                                      ? std::to_string(size->value().size()) + " elements"
                                      : jsonTypeName(size->value());
                size->fail("expected an array of two integers [width, height], got " + got);
            }
            std::array<uint32_t, 2> extent{};
            for (size_t i = 0; i < 2; ++i) {
                extent[i] = static_cast<uint32_t>(size->at(i).asInt(1, kMaxImageSize));
            }
            mGraph.defaults.size = extent;
        }
        if (auto frames = node.find("frames")) {
            mGraph.defaults.frames =
                static_cast<uint32_t>(frames->asInt(1, std::numeric_limits<uint32_t>::max()));
        }
        if (auto seed = node.find("seed")) mGraph.defaults.seed = seed->asUnsigned();
        if (auto scene = node.find("scene")) mGraph.defaults.scene = scene->asString();
        if (auto camera = node.find("camera")) {
            mGraph.defaults.camera = camera->asString();
            // A camera path is made for one scene; without a default scene it was ignored in
            // silence (with --scene it is dropped anyway), so any text passed (issue 33).
            if (!mGraph.defaults.scene || *mGraph.defaults.scene == "none")
                camera->fail(
                    "a default camera needs a default scene ('scene' in 'defaults'): "
                    "the camera path is made for that scene");
        }
        if (auto stereo = node.find("stereo")) mGraph.defaults.stereo = stereo->asBool();
        if (auto model = node.find("camera_model")) {
            mGraph.defaults.cameraModel = model->asString();
            if (*mGraph.defaults.cameraModel != "perspective" &&
                *mGraph.defaults.cameraModel != "equirect")
                model->fail("expected \"perspective\" or \"equirect\"");
        }
    }

    void parsePasses(const JsonNode& node) {
        if (node.size() == 0) node.fail("a graph needs at least one pass (got an empty array)");
        for (const JsonNode& entry : node.elements()) {
            entry.checkFields(kPassFields);
            PassDesc pass;
            pass.pointer = entry.pointer();
            JsonNode name = entry.require("name");
            pass.name = name.asString();
            if (!isValidPassName(pass.name)) {
                name.fail("invalid pass name '" + pass.name +
                          "' (use letters, digits and '_', not starting with a digit)");
            }
            auto [it, inserted] = mPassPointers.emplace(pass.name, pass.pointer);
            if (!inserted) {
                name.fail("duplicate pass name '" + pass.name + "' (first defined at " +
                          it->second + ")");
            }
            JsonNode type = entry.require("type");
            pass.type = type.asString();
            if (pass.type.empty()) type.fail("pass type must not be empty");
            if (auto params = entry.find("params")) pass.params = params->expectObject().value();
            if (auto enabled = entry.find("enabled")) pass.enabled = enabled->asBool();
            mGraph.passes.push_back(std::move(pass));
        }
    }

    // A pass name that must name a pass of this graph.
    void checkPassExists(const JsonNode& node, const std::string& name) {
        if (mPassPointers.count(name)) return;
        node.fail("unknown pass '" + name + "'" + didYouMean(name, mGraph.passNames()));
    }

    Endpoint parseEndpointNode(const JsonNode& node) {
        std::string text = node.asString();
        std::optional<Endpoint> endpoint = parseEndpoint(text);
        if (!endpoint) node.fail("expected \"pass.field\", got '" + text + "'");
        checkPassExists(node, endpoint->pass);
        return *endpoint;
    }

    void parseEdge(const JsonNode& entry) {
        entry.checkFields(kEdgeFields);
        EdgeDesc edge;
        edge.pointer = entry.pointer();
        edge.from = parseEndpointNode(entry.require("from"));
        JsonNode to = entry.require("to");
        edge.to = parseEndpointNode(to);
        if (auto delay = entry.find("delay")) {
            edge.delay = static_cast<uint32_t>(delay->asInt(0, kMaxEdgeDelay));
        }
        // An input has exactly one source; a second edge is a mistake whatever its delay.
        auto [it, inserted] = mInputEdges.emplace(edge.to.str(), edge.pointer);
        if (!inserted) {
            to.fail("input '" + edge.to.str() + "' already has an edge (from " + it->second + ")");
        }
        mGraph.edges.push_back(std::move(edge));
    }

    void parseOrder(const JsonNode& entry) {
        entry.checkFields(kOrderFields);
        OrderDesc order;
        order.pointer = entry.pointer();
        JsonNode before = entry.require("before");
        order.before = before.asString();
        checkPassExists(before, order.before);
        JsonNode after = entry.require("after");
        order.after = after.asString();
        checkPassExists(after, order.after);
        if (order.before == order.after) {
            entry.fail("pass '" + order.before + "' cannot be ordered before itself");
        }
        mGraph.order.push_back(std::move(order));
    }

    // "tm.output" or, equivalently, { "source": "tm.output" } (room for per-output options).
    void parseOutput(const JsonNode& entry) {
        OutputDesc output;
        output.pointer = entry.pointer();
        if (entry.value().is_object()) {
            entry.checkFields(kOutputFields);
            output.source = parseEndpointNode(entry.require("source"));
        } else if (entry.value().is_string()) {
            output.source = parseEndpointNode(entry);
        } else {
            entry.fail("expected a string \"pass.field\", got " + jsonTypeName(entry.value()));
        }
        auto [it, inserted] = mOutputs.emplace(output.source.str(), output.pointer);
        if (!inserted) {
            entry.fail("duplicate output '" + output.source.str() + "' (first listed at " +
                       it->second + ")");
        }
        mGraph.outputs.push_back(std::move(output));
    }

    JsonNode mTop;
    GraphDesc mGraph;
    std::map<std::string, std::string> mPassPointers;  // name -> pointer of its definition
    std::map<std::string, std::string> mInputEdges;    // "pass.field" -> pointer of its edge
    std::map<std::string, std::string> mOutputs;       // "pass.field" -> pointer of the entry
};

}  // namespace

GraphDesc parseGraphJson(const nlohmann::json& root, const std::string& fileLabel) {
    return GraphParser(root, fileLabel).parse();
}

GraphDesc parseGraphText(std::string_view text, const std::string& fileLabel) {
    nlohmann::json root = parseJsonText(text, fileLabel);
    return parseGraphJson(root, fileLabel);
}

}  // namespace fovea::graph
