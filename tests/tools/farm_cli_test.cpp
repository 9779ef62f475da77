// tests/tools/farm_cli_test.cpp: `affray split` and `affray merge` end to end, without a scheduler
// (tools/slurm-local.sh runs them on a real Slurm cluster). The tiles of a split, rendered by
// separate processes and merged, make the file a single process writes, byte for byte, with every
// AOV; merge refuses a missing tile, overlapping tiles, tiles of another scene or other options
// and images that are no tiles, each with its named error, exit 1 and nothing written. The Slurm
// scripts of a multi-frame split, run task by task as Slurm would, do the same for every frame.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>

#include "image/exr_writer.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
using namespace affray;

namespace {

/// Runs `command` (with `affray` standing for the program) in `dir`; stdout and stderr together.
test::CliOutput RunIn(const test::TempDir& dir, const std::string& command) {
    std::string line = command;
    if (line.rfind("affray ", 0) == 0) line = std::string(AFFRAY_CLI) + line.substr(6);
    return test::RunShell("cd " + test::Quote(dir.Path("")) + " && " + line + " 2>&1");
}

std::vector<std::string> Lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) lines.push_back(line);
    return lines;
}

/// The crop argument of a render command line.
std::string CropOf(const std::string& command) {
    const size_t at = command.find("--crop ");
    REQUIRE(at != std::string::npos);
    return command.substr(at + 7, command.find(' ', at + 7) - at - 7);
}

/// Files in `dir` that a failed write could leave behind.
bool LeftoversIn(const test::TempDir& dir) {
    for (const auto& entry : fs::directory_iterator(dir.Path("")))
        if (entry.path().filename().string().find(".tmp.") != std::string::npos) return true;
    return false;
}

void RequireSameFile(const std::string& a, const std::string& b) {
    INFO(a << " against " << b);
    const std::string ta = test::ReadText(a), tb = test::ReadText(b);
    REQUIRE(!ta.empty());
    REQUIRE(ta.size() == tb.size());
    REQUIRE(ta == tb);
}

}  // namespace

TEST_CASE("farm cli: split --shell tiles merge into the single render byte for byte, and merge refuses bad tiles",
          "[tools]") {
    test::TempDir dir;
    fs::copy_file(test::SourceDir() + "/shaders/wave.sl", dir.Path("wave.sl"));
    dir.Write("scene.rib", test::WaveSphereScene(67, 41, "farm.exr"));

    // 7 tiles of an awkward size: one command per tile on stdout, the merge on stderr.
    const test::CliOutput split =
        test::RunShell("cd " + test::Quote(dir.Path("")) + " && " + AFFRAY_CLI +
                       " split scene.rib --tiles 7 --shell -o out.exr 2>" + test::Quote(dir.Path("split.err")));
    INFO(split.out);
    REQUIRE(split.status == 0);
    const std::vector<std::string> commands = Lines(split.out);
    REQUIRE(commands.size() == 7);
    std::vector<std::string> tiles;
    for (size_t i = 0; i < commands.size(); ++i) {
        INFO(commands[i]);
        CHECK(commands[i].rfind("affray render scene.rib --crop ", 0) == 0);
        CHECK(commands[i].find(" -o out.tile" + std::to_string(i) + ".exr") != std::string::npos);
        CHECK(commands[i].find("--threads 1 --quiet --resume") != std::string::npos);
        const test::CliOutput r = RunIn(dir, commands[i]);
        INFO(r.out);
        REQUIRE(r.status == 0);
        tiles.push_back("out.tile" + std::to_string(i) + ".exr");
    }
    std::string tileList;
    for (const std::string& tile : tiles) tileList += " " + tile;
    CHECK(test::ReadText(dir.Path("split.err")).find("note: then: affray merge out.exr" + tileList) !=
          std::string::npos);

    // Merged in any order, the tiles are the single render's file.
    std::string reversed;
    for (auto it = tiles.rbegin(); it != tiles.rend(); ++it) reversed += " " + *it;
    test::CliOutput merged = RunIn(dir, "affray merge merged.exr" + reversed);
    INFO(merged.out);
    REQUIRE(merged.status == 0);
    REQUIRE(RunIn(dir, "affray render scene.rib -o single.exr --quiet").status == 0);
    RequireSameFile(dir.Path("merged.exr"), dir.Path("single.exr"));
    image::ImageBuffer image;
    REQUIRE(image::ReadExrRgba(dir.Path("merged.exr"), &image, nullptr));
    CHECK(image.extraChannels.size() == 11);  // Z, N.X N.Y N.Z, P.X P.Y P.Z, st.s st.t, cost, err
    CHECK(image.attributes.at("affray:pixels") == "0,67,0,41");

    // Each refusal: its named error, exit 1, no image and no temporary file.
    auto refused = [&](const std::string& args, const std::string& message) {
        const test::CliOutput r = RunIn(dir, "affray merge refused.exr " + args);
        INFO(args << "\n" << r.out);
        CHECK(r.status == 1);
        CHECK(r.out.find(message) != std::string::npos);
        CHECK(r.out.find("nothing written") != std::string::npos);
        CHECK_FALSE(fs::exists(dir.Path("refused.exr")));
        CHECK_FALSE(LeftoversIn(dir));
    };
    SECTION("a missing tile") {
        std::string six;
        for (size_t i = 0; i + 1 < tiles.size(); ++i) six += " " + tiles[i];
        refused(six, "refused.exr: error: missing tile: ");
    }
    SECTION("overlapping tiles") {
        REQUIRE(RunIn(dir, "affray render scene.rib --quiet --crop 0,0.6,0,0.6 -o extra.exr").status == 0);
        refused(tileList + " extra.exr", "extra.exr: error: overlapping tiles: extra.exr and out.tile");
    }
    SECTION("a tile of another scene") {
        dir.Write("other.rib", test::WaveSphereScene(67, 41, "farm.exr", "", "0.2 0.3 0.4"));
        REQUIRE(RunIn(dir, "affray render other.rib --quiet --crop " + CropOf(commands[0]) + " -o other.exr").status ==
                0);
        std::string list = " other.exr";
        for (size_t i = 1; i < tiles.size(); ++i) list += " " + tiles[i];
        refused(list,
                "error: tiles of different scenes: out.tile1.exr and other.exr were rendered from different "
                "scenes");
    }
    SECTION("a tile of other options") {
        REQUIRE(
            RunIn(dir, "affray render scene.rib --quiet --samples 1 --crop " + CropOf(commands[6]) + " -o coarse.exr")
                .status == 0);
        std::string list;
        for (size_t i = 0; i + 1 < tiles.size(); ++i) list += " " + tiles[i];
        refused(list + " coarse.exr",
                "coarse.exr: error: tiles of different options: coarse.exr and out.tile0.exr were rendered with "
                "different samples");
    }
    SECTION("an image that is no tile") {
        image::ImageBuffer plain{67, 41, std::vector<float>(67 * 41 * 4, 0.5f), {}, {}};
        REQUIRE(image::WriteExr(dir.Path("plain.exr"), plain, nullptr));
        refused(tileList + " plain.exr", "plain.exr: error: not a tile: its header has no affray:version attribute");
    }
}

TEST_CASE("farm cli: the Slurm scripts of a multi-frame split, run task by task, merge into each frame", "[tools]") {
    test::TempDir dir;
    fs::copy_file(test::SourceDir() + "/shaders/wave.sl", dir.Path("wave.sl"));
    const std::string world = R"(
  WorldBegin
    LightSource "distantlight" 1 "intensity" [1.1] "from" [-3 1.5 1.1] "to" [0 0 0]
    Surface "plastic"
    Displacement "wave" "Km" [0.06] "frequency" [6] "decay" [2.5]
    Patch "bilinear" "P" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]
  WorldEnd
)";
    dir.Write("anim.rib",
              "Format 30 22 1\nProjection \"perspective\" \"fov\" [40]\n"
              "FrameBegin 1\n  Display \"anim.exr\" \"file\" \"rgba,Z,N\"\n  Translate 0 0 3.1\n"
              "  Rotate -130 1 0 0" +
                  world +
                  "FrameEnd\nFrameBegin 2\n  Display \"anim.exr\" \"file\" \"rgba,Z,N\"\n"
                  "  Translate 0 0 3.6\n  Rotate -120 1 0 0" +
                  world + "FrameEnd\n");
    const test::CliOutput split = RunIn(dir, "affray split anim.rib --tiles 3 -o out.exr --samples 3");
    INFO(split.out);
    REQUIRE(split.status == 0);
    CHECK(split.out.find("note: 6 tasks; submit them with") != std::string::npos);
    const std::string render = test::ReadText(dir.Path("out.render.sbatch"));
    const std::string merge = test::ReadText(dir.Path("out.merge.sbatch"));
    const std::string submit = test::ReadText(dir.Path("out.submit.sh"));
    INFO(render << merge << submit);
    for (const char* line :
         {"#SBATCH --array=0-5\n", "#SBATCH --cpus-per-task=1\n", "$SLURM_ARRAY_TASK_ID", " --frame 1 --crop ",
          " --frame 2 --crop ", "out.0002.tile2.exr --samples 3 ;;", "--quiet --resume\n"})
        CHECK(render.find(line) != std::string::npos);
    CHECK(merge.find("#SBATCH --kill-on-invalid-dep=yes\n") != std::string::npos);
    CHECK(merge.find("out.0001.exr " + dir.Path("out.0001.tile0.exr")) != std::string::npos);
    CHECK(merge.find("out.0002.exr " + dir.Path("out.0002.tile0.exr")) != std::string::npos);
    CHECK(submit.find("sbatch --parsable --dependency=afterok:$render ") != std::string::npos);

    // As Slurm runs them, from another directory (the scripts hold absolute paths).
    for (int task = 0; task < 6; ++task) {
        const test::CliOutput r = test::RunShell("cd / && SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " bash " +
                                                 test::Quote(dir.Path("out.render.sbatch")) + " 2>&1");
        INFO("task " << task << ": " << r.out);
        REQUIRE(r.status == 0);
    }
    const test::CliOutput merged =
        test::RunShell("cd / && bash " + test::Quote(dir.Path("out.merge.sbatch")) + " 2>&1");
    INFO(merged.out);
    REQUIRE(merged.status == 0);
    REQUIRE(RunIn(dir, "affray render anim.rib -o single.exr --quiet --samples 3").status == 0);
    RequireSameFile(dir.Path("out.0001.exr"), dir.Path("single.0001.exr"));
    RequireSameFile(dir.Path("out.0002.exr"), dir.Path("single.0002.exr"));
}

TEST_CASE("farm cli: split and merge usage errors", "[tools]") {
    test::TempDir dir;
    fs::copy_file(test::SourceDir() + "/shaders/wave.sl", dir.Path("wave.sl"));
    dir.Write("scene.rib", test::WaveSphereScene(4, 3, "tiny.exr"));
    auto usage = [&](const std::string& args, const std::string& message) {
        const test::CliOutput r = RunIn(dir, "affray " + args);
        INFO(args << "\n" << r.out);
        CHECK(r.status == 2);
        CHECK(r.out.find(message) != std::string::npos);
    };
    usage("split scene.rib", "split: missing --tiles N");
    usage("split scene.rib --tiles 2 --crop 0,1,0,1", "split: --crop is not an option of split");
    usage("split scene.rib --tiles 13 --shell", "--tiles 13: a 4x3 frame cannot be cut into so many tiles");
    usage("split scene.rib --tiles 2 -o out.png", "-o writes OpenEXR");
    usage("merge out.exr", "merge takes OUT.exr and at least one TILE.exr");
    CHECK_FALSE(fs::exists(dir.Path("scene.render.sbatch")));
}
