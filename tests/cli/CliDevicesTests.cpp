// `fovea devices` (scripts/gpu-check.sh records it first): the list --device indexes, and the
// default device opened for real.
#include "tests/cli/CliTestUtil.h"

namespace fovea::clitest {
namespace {

TEST(CliDevices, ListsTheDevicesAndTheDefaultOne) {
    const Result r = cli({"devices", "--json"});
    ASSERT_EQ(r.code, 0) << r.describe();
    const json out = json::parse(r.out);
    ASSERT_FALSE(out["devices"].empty()) << r.out;
    const std::string name = out["default"]["name"];
    ASSERT_FALSE(name.empty()) << r.out;
    // The default is one of the listed devices ("0: llvmpipe (...) [cpu]").
    bool listed = false;
    for (const auto& d : out["devices"]) listed = listed || contains(d.get<std::string>(), name);
    EXPECT_TRUE(listed) << r.out;
    EXPECT_TRUE(contains(out["default"]["api_version"].get<std::string>(), "1.")) << r.out;
    const Result text = cli({"devices"});
    ASSERT_EQ(text.code, 0) << text.describe();
    EXPECT_TRUE(contains(text.out, "default: " + name)) << text.out;
}

}  // namespace
}  // namespace fovea::clitest
