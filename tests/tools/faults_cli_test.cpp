// tests/tools/faults_cli_test.cpp: `affray render` under faults, end to end (issue 17): a render
// killed by SIGINT or SIGTERM writes no image and leaves no temporary file but its checkpoint,
// `--resume` then renders the missing tiles and writes the uninterrupted render's file byte for
// byte (after SIGKILL too, which only the checkpoint's tile-by-tile writes survive); a checkpoint
// of another scene, of other options, or damaged is refused; an output that cannot be written
// (missing directory, a directory, no permission, a read-only or full disk: a real 64 KiB tmpfs)
// is an error naming it, with nothing left behind.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <sstream>
#include <thread>

#include "renderer/checkpoint.h"
#include "tests/test_util.h"

using namespace affray;

namespace {

/// The CLI tests' scene at width x height, 3 x 3 samples.
std::string Scene(int width, int height, const char* color = "0.85 0.62 0.35") {
    return test::WaveSphereScene(width, height, "faults.exr", "PixelSamples 3 3\n", color);
}

/// A directory holding the scene (scene.rib) and its shader.
struct SceneDir {
    test::TempDir dir;
    explicit SceneDir(int width, int height) {
        dir.Write("scene.rib", Scene(width, height));
        std::filesystem::copy_file(test::SourceDir() + "/shaders/wave.sl", dir.Path("wave.sl"));
    }
    std::string Render(const std::string& output, const std::string& extra, int* status) const {
        test::CliOutput out = test::RunCli(
            "render " + test::Quote(dir.Path("scene.rib")) + " -o " + test::Quote(output) + " --quiet " + extra, true);
        *status = out.status;
        return out.out;
    }
};

/// The names in `dir` (not recursive), sorted, one per line.
std::string Listing(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
    std::string text;
    for (const std::string& name : names) text += name + "\n";
    return text;
}

bool HasTemporary(const std::string& dir) { return Listing(dir).find(".tmp.") != std::string::npos; }

/// Tiles in the checkpoint at `path` (-1 if it cannot be read yet).
int CheckpointTiles(const std::string& path) {
    renderer::CheckpointContents contents;
    std::string error;
    if (!renderer::ReadCheckpoint(path, &contents, &error)) return -1;
    return static_cast<int>(contents.tiles.size());
}

/// Starts `affray render SCENE -o OUTPUT --quiet --threads 1 [EXTRA]`, its output to `log`;
/// returns its pid.
pid_t Spawn(const std::string& scene, const std::string& output, const std::string& log,
            const std::string& extra = "") {
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) {
            ::dup2(fd, 1);
            ::dup2(fd, 2);
        }
        if (extra.empty())
            execl(AFFRAY_CLI, AFFRAY_CLI, "render", scene.c_str(), "-o", output.c_str(), "--quiet", "--threads", "1",
                  static_cast<char*>(nullptr));
        else
            execl(AFFRAY_CLI, AFFRAY_CLI, "render", scene.c_str(), "-o", output.c_str(), "--quiet", "--threads", "1",
                  extra.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    return pid;
}

/// Renders into `output` and stops the render with SIGTERM once its checkpoint holds `tiles`
/// tiles; returns whether it was stopped (a checkpoint is there).
bool Interrupted(const SceneDir& scene, const std::string& output, int tiles, const std::string& extra = "") {
    const std::string checkpoint = output + ".checkpoint";
    std::filesystem::remove(checkpoint);
    const pid_t pid = Spawn(scene.dir.Path("scene.rib"), output, scene.dir.Path("spawn.log"), extra);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (CheckpointTiles(checkpoint) < tiles && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    ::kill(pid, SIGTERM);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGTERM && std::filesystem::exists(checkpoint);
}

/// Kills a render with `signal` once its checkpoint holds 2 tiles at least; checks what is left,
/// then resumes it and checks the image equals `reference` (a file) byte for byte.
void KillAndResume(const SceneDir& scene, int signal, const std::string& reference) {
    const std::string output = scene.dir.Path("killed.exr"), checkpoint = output + ".checkpoint";
    const std::string log = scene.dir.Path("killed.log");
    const pid_t pid = Spawn(scene.dir.Path("scene.rib"), output, log);
    int tiles = -1;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while ((tiles = CheckpointTiles(checkpoint)) < 2 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    REQUIRE(::kill(pid, signal) == 0);
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    const std::string stderrText = test::ReadText(log);
    INFO("stderr: " << stderrText);
    REQUIRE(tiles >= 2);
    if (signal == SIGKILL) {
        // Killed outright: the tiles written before it are in the file all the same.
        REQUIRE(WIFSIGNALED(status));
    } else {
        // Stopped by the signal, not finished first (the scene is slow enough), nor killed by it.
        REQUIRE(WIFEXITED(status));
        CHECK(WEXITSTATUS(status) == 128 + signal);
        CHECK(stderrText.find(std::string("interrupted by ") + (signal == SIGINT ? "SIGINT" : "SIGTERM") +
                              ": no image written") != std::string::npos);
        CHECK(stderrText.find("--resume") != std::string::npos);
    }
    // No image and no temporary file; the checkpoint holds the finished tiles.
    CHECK_FALSE(std::filesystem::exists(output));
    CHECK_FALSE(HasTemporary(scene.dir.Path("")));
    const int kept = CheckpointTiles(checkpoint);
    CHECK(kept >= tiles);

    int resumed = 0;
    const std::string text = scene.Render(output, "--resume --threads 2", &resumed);
    INFO("resume: " << text);
    REQUIRE(resumed == 0);
    CHECK(text.find("resuming: " + std::to_string(kept) + " of ") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(checkpoint));
    CHECK_FALSE(HasTemporary(scene.dir.Path("")));
    CHECK(test::ReadText(output) == test::ReadText(reference));
    std::filesystem::remove(output);
}

}  // namespace

TEST_CASE("faults: SIGINT and SIGTERM stop a render, and --resume writes the uninterrupted image", "[tools][faults]") {
    // About 80 tiles of 32 x 32 pixels, a second or two on one thread.
    SceneDir scene(320, 240);
    int status = 0;
    const std::string reference = scene.dir.Path("reference.exr");
    INFO(scene.Render(reference, "--threads 2", &status));
    REQUIRE(status == 0);
    // An uninterrupted render leaves no checkpoint.
    CHECK_FALSE(std::filesystem::exists(reference + ".checkpoint"));
    KillAndResume(scene, SIGINT, reference);
    KillAndResume(scene, SIGTERM, reference);
    // SIGKILL cannot be caught: each tile is written as it finishes, so those are kept.
    KillAndResume(scene, SIGKILL, reference);
}

TEST_CASE("faults: --resume refuses the checkpoint of another scene, other options, or a damaged one",
          "[tools][faults]") {
    SceneDir scene(160, 120);
    const std::string output = scene.dir.Path("out.exr"), checkpoint = output + ".checkpoint";
    int status = 0;
    std::string text;
    // Stopped at its first tile, with a checkpoint of its header only.
    REQUIRE(Interrupted(scene, output, 0));
    CHECK_FALSE(std::filesystem::exists(output));

    SECTION("other options") {
        text = scene.Render(output, "--resume --samples 2 --tolerance 0.25", &status);
        INFO(text);
        CHECK(status == 1);
        CHECK(text.find("out.exr.checkpoint: error: --resume: the checkpoint was written by a render of other "
                        "options (samples, tolerance); render without --resume to start again") != std::string::npos);
        text = scene.Render(output, "--resume --crop 0,0.5,0,1", &status);
        CHECK(status == 1);
        CHECK(text.find("other options (crop)") != std::string::npos);
        CHECK_FALSE(std::filesystem::exists(output));
        CHECK(std::filesystem::exists(checkpoint));  // refused, not removed
    }
    SECTION("another scene") {
        scene.dir.Write("scene.rib", Scene(160, 120, "0.2 0.9 0.3"));
        text = scene.Render(output, "--resume", &status);
        INFO(text);
        CHECK(status == 1);
        CHECK(text.find("out.exr.checkpoint: error: --resume: the checkpoint was written by a render of another "
                        "scene") != std::string::npos);
        CHECK_FALSE(std::filesystem::exists(output));
        // Without --resume it is replaced (and removed once the image is written).
        text = scene.Render(output, "", &status);
        CHECK(status == 0);
        CHECK_FALSE(std::filesystem::exists(checkpoint));
    }
    SECTION("another shader") {
        scene.dir.Write("wave.sl", test::ReadText(test::SourceDir() + "/shaders/wave.sl") + "\n// edited\n");
        text = scene.Render(output, "--resume", &status);
        INFO(text);
        CHECK(status == 1);
        CHECK(text.find("a render of another scene") != std::string::npos);
    }
    SECTION("damaged") {
        std::string bytes = test::ReadText(checkpoint);
        bytes[20] ^= 0x55;  // inside the identity
        scene.dir.Write("out.exr.checkpoint", bytes);
        text = scene.Render(output, "--resume", &status);
        INFO(text);
        CHECK(status == 1);
        CHECK(text.find("out.exr.checkpoint: error: --resume: cannot use the checkpoint: damaged") !=
              std::string::npos);
        scene.dir.Write("out.exr.checkpoint", "not a checkpoint");
        text = scene.Render(output, "--resume", &status);
        CHECK(status == 1);
        CHECK(text.find("cannot use the checkpoint: not an affray checkpoint") != std::string::npos);
        CHECK_FALSE(std::filesystem::exists(output));
    }
}

TEST_CASE("faults: a checkpoint whose last tile is cut short resumes without it, to the same image",
          "[tools][faults]") {
    SceneDir scene(160, 120);
    const std::string output = scene.dir.Path("out.exr"), checkpoint = output + ".checkpoint";
    int status = 0;
    const std::string reference = scene.dir.Path("reference.exr");
    REQUIRE(scene.Render(reference, "", &status).empty());
    REQUIRE(status == 0);
    if (!Interrupted(scene, output, 3)) {
        WARN(
            "skipped: "
            "the render finished before the signal");
        return;
    };
    const int tiles = CheckpointTiles(checkpoint);
    REQUIRE(tiles >= 3);
    // As a power cut while the last tile was written would leave it: a record cut short.
    std::filesystem::resize_file(checkpoint, std::filesystem::file_size(checkpoint) - 5);
    CHECK(CheckpointTiles(checkpoint) == tiles - 1);
    // A record damaged in the middle of the file is refused, though.
    std::string bytes = test::ReadText(checkpoint);
    std::string damaged = bytes;
    damaged[damaged.size() / 2] ^= 0x01;
    scene.dir.Write("out.exr.checkpoint", damaged);
    std::string text = scene.Render(output, "--resume", &status);
    CHECK(status == 1);
    CHECK(text.find("damaged: a bad checksum in tile record") != std::string::npos);
    scene.dir.Write("out.exr.checkpoint", bytes);
    text = scene.Render(output, "--resume --threads 3", &status);
    INFO(text);
    REQUIRE(status == 0);
    CHECK(text.find("its last tile was cut short") != std::string::npos);
    CHECK(text.find("resuming: " + std::to_string(tiles - 1) + " of ") != std::string::npos);
    CHECK(test::ReadText(output) == test::ReadText(reference));
    CHECK_FALSE(std::filesystem::exists(checkpoint));
}

TEST_CASE("faults: an output that cannot be written is an error naming it, before the render, with nothing left",
          "[tools][faults]") {
    SceneDir scene(24, 16);
    int status = 0;
    SECTION("a missing directory") {
        const std::string text = scene.Render(scene.dir.Path("missing/out.exr"), "", &status);
        CHECK(status == 3);
        CHECK(text.find("missing/out.exr: error: cannot write file: directory '") != std::string::npos);
        CHECK(text.find("does not exist") != std::string::npos);
    }
    SECTION("a directory") {
        std::filesystem::create_directory(scene.dir.Path("out.exr"));
        const std::string text = scene.Render(scene.dir.Path("out.exr"), "", &status);
        CHECK(status == 3);
        CHECK(text.find("out.exr: error: cannot write file: '") != std::string::npos);
        CHECK(text.find("out.exr' is a directory") != std::string::npos);
        CHECK(std::filesystem::is_empty(scene.dir.Path("out.exr")));
    }
    SECTION("a preview in a missing directory") {
        const std::string text =
            scene.Render(scene.dir.Path("out.exr"), "--png " + test::Quote(scene.dir.Path("no/p.png")), &status);
        CHECK(status == 3);
        CHECK(text.find("no/p.png: error: cannot write file: directory") != std::string::npos);
    }
    SECTION("a directory without write permission") {
        if (::geteuid() == 0) {
            WARN(
                "skipped: "
                "root may write anywhere");
            return;
        };
        std::filesystem::create_directory(scene.dir.Path("ro"));
        std::filesystem::permissions(scene.dir.Path("ro"),
                                     std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
        const std::string text = scene.Render(scene.dir.Path("ro/out.exr"), "", &status);
        CHECK(status == 3);
        CHECK(text.find("ro/out.exr: error: cannot write file: Permission denied") != std::string::npos);
        std::filesystem::permissions(scene.dir.Path("ro"), std::filesystem::perms::owner_all);
    }
    // Nothing but the scene, its shader and whatever the section made.
    const std::string listing = Listing(scene.dir.Path(""));
    CHECK(listing.find(".tmp.") == std::string::npos);
    CHECK(listing.find(".checkpoint") == std::string::npos);
    const bool noImage = listing.find("out.exr\n") == std::string::npos;
    CHECK((noImage || std::filesystem::is_directory(scene.dir.Path("out.exr"))));
}

TEST_CASE("faults: a full disk is an error naming the output, with nothing left on it", "[tools][faults]") {
    // A real full disk: a 64 KiB tmpfs in a private mount namespace (unshare -rm, as any user where
    // user namespaces are allowed). The image with its AOVs needs far more.
    SceneDir scene(96, 72);
    const std::string disk = scene.dir.Path("disk");
    std::filesystem::create_directory(disk);
    const std::string script = "mount -t tmpfs -o size=64k tmpfs " + test::Quote(disk) + " || exit 99; " + AFFRAY_CLI +
                               " render " + test::Quote(scene.dir.Path("scene.rib")) + " -o " +
                               test::Quote(disk + "/out.exr") + " --quiet --png " + test::Quote(disk + "/p.png") +
                               "; status=$?; echo \"listing:$(ls -A " + test::Quote(disk) + ")\"; exit $status";
    const test::CliOutput full = test::RunShell("unshare -rm sh -c " + test::Quote(script) + " 2>&1");
    INFO(full.out);
    if (full.status == -1 || full.status == 99 || full.out.find("unshare:") != std::string::npos) {
        WARN(
            "skipped: "
            "cannot mount a tmpfs here");
        return;
    };
    CHECK(full.status == 3);
    CHECK(full.out.find("out.exr: error: cannot write file: No space left on device") != std::string::npos);
    // The checkpoint could not be written either: a warning, and the render went on.
    CHECK(full.out.find("out.exr.checkpoint: warning: cannot write the checkpoint: No space left on device") !=
          std::string::npos);
    CHECK(full.out.find("listing:\n") != std::string::npos);

    // A read-only file system: refused before the render, as a directory without permission is.
    const std::string readOnly = "mount -t tmpfs -o ro tmpfs " + test::Quote(disk) + " || exit 99; " + AFFRAY_CLI +
                                 " render " + test::Quote(scene.dir.Path("scene.rib")) + " -o " +
                                 test::Quote(disk + "/out.exr") + " --quiet; status=$?; echo \"listing:$(ls -A " +
                                 test::Quote(disk) + ")\"; exit $status";
    const test::CliOutput ro = test::RunShell("unshare -rm sh -c " + test::Quote(readOnly) + " 2>&1");
    INFO(ro.out);
    CHECK(ro.status == 3);
    CHECK(ro.out.find("out.exr: error: cannot write file: Read-only file system") != std::string::npos);
    CHECK(ro.out.find("listing:\n") != std::string::npos);
}
