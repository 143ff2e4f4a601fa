// core/util/UserFile.h: every file a user names is read only if it is a regular file (links
// followed) within its size limit; FIFOs, devices and directories are refused before opening,
// so nothing blocks or grows without bound (issue 33, class 1). The readers that use it (graph,
// camera path, images) refuse the same files with an InputError naming them.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "core/graph/GraphDesc.h"
#include "core/image/ImageIO.h"
#include "core/scene/CameraPath.h"
#include "core/util/Error.h"
#include "core/util/UserFile.h"
#include "tests/unit/InputErrorOf.h"

using namespace fovea;
namespace fs = std::filesystem;

using fovea::test::inputErrorOf;

namespace {

class UserFileTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::random_device random;
        mDir = fs::temp_directory_path() / ("fovea_userfile_" + std::to_string(random()));
        fs::create_directories(mDir);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(mDir, ec);
    }
    fs::path mDir;
};

TEST_F(UserFileTest, ReadsRegularFilesAndLinksToThem) {
    const fs::path file = mDir / "a.json";
    std::ofstream(file) << "{\"x\": 1}";
    fs::create_symlink(file, mDir / "link.json");
    EXPECT_EQ(readUserTextFile(file, kMaxJsonFileBytes, "file"), "{\"x\": 1}");
    EXPECT_EQ(readUserTextFile(mDir / "link.json", kMaxJsonFileBytes, "file"), "{\"x\": 1}");
    EXPECT_EQ(regularFileProblem(file), "");
}

TEST_F(UserFileTest, RefusesWhatIsNotARegularFileBeforeOpeningIt) {
    const fs::path fifo = mDir / "pipe";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);  // opening it for reading would block
    fs::create_symlink("/dev/zero", mDir / "zero");
    for (const fs::path& p : {fs::path("/dev/zero"), fifo, mDir / "zero"}) {
        const std::string message = inputErrorOf([&] { readUserTextFile(p, 100, "graph file"); });
        EXPECT_EQ(message.rfind(p.string() + ": cannot read graph file: not a regular file", 0), 0u)
            << message;
        EXPECT_NE(inputErrorOf([&] { requireRegularFile(p, "image"); }), "");
    }
    EXPECT_EQ(regularFileProblem(mDir), "is a directory, not a file");
    EXPECT_EQ(regularFileProblem(mDir / "missing"), "file not found");
    fs::create_symlink(mDir / "missing", mDir / "dangling");
    EXPECT_EQ(regularFileProblem(mDir / "dangling"), "file not found");
}

TEST_F(UserFileTest, RefusesFilesOverTheLimitWithoutReadingThem) {
    const fs::path big = mDir / "big.json";
    std::ofstream(big).close();
    fs::resize_file(big, kMaxJsonFileBytes + 1);  // sparse: no 64 MB written
    const std::string message =
        inputErrorOf([&] { readUserTextFile(big, kMaxJsonFileBytes, "camera path file"); });
    EXPECT_NE(message.find("more than the limit of " + std::to_string(kMaxJsonFileBytes)),
              std::string::npos)
        << message;
}

TEST_F(UserFileTest, ReadersOfGraphsCameraPathsAndImagesRefuseDevices) {
    const fs::path fifo = mDir / "pipe.json";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    for (const fs::path& p : {fs::path("/dev/zero"), fifo}) {
        const std::string graph = inputErrorOf([&] { graph::parseGraphFile(p); });
        const std::string camera = inputErrorOf([&] { scene::CameraPath::load(p); });
        const std::string image = inputErrorOf([&] { image::readImage(p); });
        for (const std::string& m : {graph, camera, image}) {
            EXPECT_EQ(m.rfind(p.string() + ": ", 0), 0u) << m;
            EXPECT_NE(m.find("not a regular file"), std::string::npos) << m;
        }
    }
}

}  // namespace

namespace {

TEST_F(UserFileTest, ImageWritesOnAFullDiskAreErrorsNamingTheFile) {
    // Issue 33, class 3: a write that fails (here every write: the files are links to /dev/full,
    // which answers ENOSPC) must be an error naming its own file, for PNG as for EXR.
    image::ImageRGBA img;
    img.width = img.height = 64;
    img.pixels.assign(64 * 64 * 4, 0.5f);
    for (const char* name : {"full.png", "full.exr"}) {
        const fs::path link = mDir / name;
        fs::create_symlink("/dev/full", link);
        std::string message = "(no error)";
        try {
            if (link.extension() == ".png")
                image::writePng(link, img);
            else
                image::writeExr(link, img);
        } catch (const std::exception& e) {
            message = e.what();
        }
        EXPECT_EQ(message.rfind(link.string() + ": ", 0), 0u) << message;
    }
}

}  // namespace

// Issue 33, class 2, in OpenEXR: a 541-byte file (found by the image fuzz target) whose string
// attribute claims 842 MB made OpenEXR allocate and clear that much before any check of ours.
// Every header attribute must now fit in the file; the file is refused before OpenEXR sees it.
TEST(ExrHeaderSizes, AnAttributeLargerThanTheFileIsRefusedBeforeOpenExrReadsIt) {
    const fs::path file = fs::path(FOVEA_TEST_DIR) / "fuzz" / "regressions" / "image" /
                          "exr_string_attribute_claims_842MB.exr";
    const std::string message = inputErrorOf([&] { image::readImageSize(file); });
    EXPECT_NE(message.find("attribute 'capDate' claims 842399763 bytes"), std::string::npos)
        << message;
    EXPECT_NE(message.find("the file has 541"), std::string::npos) << message;
    // A valid EXR passes the same check.
    const auto size = image::readImageSize(fs::path(FOVEA_TEST_DIR) / "goldens" /
                                           "cornell_pathtrace" / "pt.radiance.exr");
    EXPECT_GT(size.width, 0u);
}
