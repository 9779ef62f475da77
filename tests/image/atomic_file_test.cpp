// tests/image/atomic_file_test.cpp: the one atomic writer (image/atomic_file.*)
// and the image writers built on it: a missing directory, a directory as the target and a
// failing write (injected: the Nth byte fails with ENOSPC, as on a full disk) are errors naming
// the file, and leave no temporary file and the old file, if any, untouched.
#include "image/atomic_file.h"

#include <catch2/catch.hpp>

#include <cerrno>
#include <filesystem>

#include "image/exr_writer.h"
#include "image/png_writer.h"
#include "tests/test_util.h"

using namespace affray;
using namespace affray::image;

namespace {

ImageBuffer SmallImage() {
    ImageBuffer image;
    image.width = 16;
    image.height = 8;
    image.rgba.assign(16 * 8 * 4, 0.5f);
    image.extraChannels.push_back({"Z", std::vector<float>(16 * 8, 2.0f)});
    return image;
}

size_t Entries(const test::TempDir& dir) {
    size_t n = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.Path(""))) ++n;
    return n;
}

/// Clears the injected fault at the end of a test.
struct FaultGuard {
    ~FaultGuard() { InjectWriteFaultForTesting(-1, 0); }
};

}  // namespace

TEST_CASE("atomic file: written whole, or an error with nothing left behind", "[image][faults]") {
    test::TempDir dir;
    FaultGuard guard;
    std::string reason;
    const std::string path = dir.Path("a.bin");
    REQUIRE(WriteFileAtomically(path, "first", &reason));
    CHECK(test::ReadText(path) == "first");

    CHECK_FALSE(WriteFileAtomically(dir.Path("missing/a.bin"), "x", &reason));
    CHECK(reason == "directory '" + dir.Path("missing") + "' does not exist");
    CHECK_FALSE(CheckWritable(dir.Path("missing/a.bin"), &reason));

    std::filesystem::create_directory(dir.Path("d"));
    CHECK_FALSE(WriteFileAtomically(dir.Path("d"), "x", &reason));
    CHECK(reason == "'" + dir.Path("d") + "' is a directory");
    CHECK_FALSE(CheckWritable(dir.Path("d"), &reason));
    CHECK(CheckWritable(path, &reason));

    // A full disk at byte 3 of the next write: the old file stays as it was.
    InjectWriteFaultForTesting(3, ENOSPC);
    CHECK_FALSE(WriteFileAtomically(path, "second", &reason));
    CHECK(reason == "No space left on device");
    CHECK(test::ReadText(path) == "first");
    CHECK(Entries(dir) == 2);  // a.bin and d: no temporary file
}

TEST_CASE("atomic file: EXR and PNG writers fail on a full disk naming the file, leaving nothing", "[image][faults]") {
    test::TempDir dir;
    FaultGuard guard;
    const ImageBuffer image = SmallImage();
    // The PNG of this flat image is about 90 bytes, the EXR about 500.
    for (int64_t failAt : {int64_t(0), int64_t(1), int64_t(40), int64_t(400)}) {
        INFO("failing byte " << failAt);
        InjectWriteFaultForTesting(failAt, ENOSPC);
        diag::Report report;
        CHECK_FALSE(WriteExr(dir.Path("out.exr"), image, &report));
        CHECK(test::LastMessage(report) == dir.Path("out.exr") + ": error: cannot write file: No space left on device");
        InjectWriteFaultForTesting(failAt % 80, ENOSPC);
        diag::Report png;
        CHECK_FALSE(WritePngPreview(dir.Path("p.png"), image, &png));
        CHECK(test::LastMessage(png) == dir.Path("p.png") + ": error: cannot write file: No space left on device");
        CHECK(Entries(dir) == 0);
    }
    // Without the fault both are written, and the EXR reads back.
    InjectWriteFaultForTesting(-1, 0);
    diag::Report report;
    REQUIRE(WriteExr(dir.Path("out.exr"), image, &report));
    REQUIRE(WritePngPreview(dir.Path("p.png"), image, &report));
    ImageBuffer back;
    REQUIRE(ReadExrRgba(dir.Path("out.exr"), &back, &report));
    CHECK(back.extraChannels.at(0).second == image.extraChannels[0].second);
    CHECK(Entries(dir) == 2);
}
