// tests/renderer/checkpoint_test.cpp: the checkpoint file (renderer/checkpoint.*) and the render
// loop's TileStore, stop flag and tile options (renderer/render.*), in process: tiles written are
// read back bit for bit, a record cut short is dropped and any other damage refused, and a
// render stopped part way then resumed from its checkpoint, with other threads and another tile
// order, gives the uninterrupted image bit for bit in every channel.
#include "renderer/checkpoint.h"

#include <catch2/catch.hpp>

#include <bit>
#include <filesystem>

#include "rib/rib.h"
#include "tests/test_util.h"

using namespace affray;
using namespace affray::renderer;

namespace {

constexpr const char* kScene = R"(Format 48 32 1
Projection "perspective" "fov" [40]
Display "cp.exr" "file" "rgba,Z,N,st,cost,err"
Translate 0 0 3.1
Rotate -130 1 0 0
WorldBegin
  LightSource "distantlight" 1 "intensity" [1.1] "from" [-3 1.5 1.1] "to" [0 0 0]
  Displacement "wave" "Km" [0.06] "frequency" [6] "decay" [2.5]
  Patch "bilinear" "P" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]
WorldEnd
)";

PreparedScene Prepare(const test::TempDir& dir, const std::string& rib = kScene) {
    diag::Report error;
    std::optional<SceneDesc> desc = rib::ParseRib(rib, dir.Write("scene.rib", rib), &error);
    INFO(error);
    REQUIRE(desc);
    PreparedScene prepared;
    const bool ok =
        Renderer(Options{.shaderPaths = {test::SourceDir() + "/shaders"}}).Prepare(*desc, &prepared, &error);
    INFO(error);
    REQUIRE(ok);
    return prepared;
}

bool SameBits(const image::ImageBuffer& a, const image::ImageBuffer& b) {
    auto same = [](const std::vector<float>& x, const std::vector<float>& y) {
        return std::equal(x.begin(), x.end(), y.begin(), y.end(),
                          [](float p, float q) { return std::bit_cast<uint32_t>(p) == std::bit_cast<uint32_t>(q); });
    };
    if (a.width != b.width || a.height != b.height || !same(a.rgba, b.rgba)) return false;
    if (a.extraChannels.size() != b.extraChannels.size()) return false;
    for (size_t c = 0; c < a.extraChannels.size(); ++c)
        if (a.extraChannels[c].first != b.extraChannels[c].first ||
            !same(a.extraChannels[c].second, b.extraChannels[c].second))
            return false;
    return true;
}

/// Passes tiles to a checkpoint and raises `stop` after `limit` of them.
class StopAfter : public TileStore {
  public:
    StopAfter(TileStore* inner, int limit, std::atomic<bool>* stop) : m_inner(inner), m_limit(limit), m_stop(stop) {}
    bool Restore(const PixelRange& tile, image::ImageBuffer* image) override { return m_inner->Restore(tile, image); }
    void Finished(const PixelRange& tile, const image::ImageBuffer& image) override {
        m_inner->Finished(tile, image);
        if (++m_count >= m_limit) *m_stop = true;
    }

  private:
    TileStore* m_inner;
    int m_limit;
    std::atomic<bool>* m_stop;
    std::atomic<int> m_count{0};
};

}  // namespace

TEST_CASE("checkpoint: a render stopped part way and resumed equals the uninterrupted one bit for bit",
          "[renderer][checkpoint]") {
    test::TempDir dir;
    const PreparedScene scene = Prepare(dir);
    Options options;
    options.threads = 2;
    const RenderControl eight{.tileSize = 8};
    image::ImageBuffer whole;
    RenderStats stats;
    Renderer(options).Render(scene, &whole, &stats, eight);
    REQUIRE_FALSE(stats.stopped);
    REQUIRE(whole.extraChannels.size() == 8);  // Z, N (3), st (2), cost and err, as the mode asks

    // Stopped after 5 of the 24 tiles.
    const std::string path = dir.Path("cp.exr.checkpoint");
    const RenderIdentity identity = IdentifyRender(scene, options);
    std::string error;
    std::unique_ptr<CheckpointFile> file = CheckpointFile::Create(path, identity, 48, 32, 8, &error);
    REQUIRE(file);
    std::atomic<bool> stop{false};
    StopAfter store(file.get(), 5, &stop);
    RenderControl first = eight;
    first.stop = &stop;
    first.tileStore = &store;
    image::ImageBuffer partial;
    Renderer(options).Render(scene, &partial, &stats, first);
    CHECK(stats.stopped);
    const int kept = file->tiles();
    CHECK(kept >= 5);
    CHECK(kept < 24);
    CHECK_FALSE(SameBits(partial, whole));
    file.reset();

    // Read back: the header and every tile written.
    CheckpointContents contents;
    REQUIRE(ReadCheckpoint(path, &contents, &error));
    CHECK(contents.identityHash == identity.Hash());
    CHECK(contents.identity.scene == identity.scene);
    CHECK(contents.identity.options == identity.options);
    CHECK(contents.tileSize == 8);
    CHECK(int(contents.tiles.size()) == kept);
    CHECK(contents.channels == 4 + 8);
    CHECK_FALSE(contents.droppedTail);

    // Resumed with other threads and the other tile order: only the missing tiles are rendered.
    file = CheckpointFile::Resume(path, std::move(contents), &error);
    REQUIRE(file);
    Options second = options;
    second.threads = 3;
    second.reverseTileOrder = true;
    RenderControl fromFile = eight;
    fromFile.tileStore = file.get();
    image::ImageBuffer resumed;
    Renderer(second).Render(scene, &resumed, &stats, fromFile);
    CHECK(stats.tilesRestored == kept);
    CHECK(file->tiles() == 24);
    CHECK(SameBits(resumed, whole));
    file->Remove();
    CHECK_FALSE(std::filesystem::exists(path));
}

TEST_CASE("checkpoint: a record cut short is dropped, other damage is refused", "[renderer][checkpoint]") {
    test::TempDir dir;
    const std::string path = dir.Path("x.checkpoint");
    const RenderIdentity identity{"00112233445566778899aabbccddeeff", "samples=2x2\n"};
    std::string error;
    std::unique_ptr<CheckpointFile> file = CheckpointFile::Create(path, identity, 4, 4, 2, &error);
    REQUIRE(file);
    image::ImageBuffer image;
    image.width = image.height = 4;
    image.rgba.resize(64);
    for (size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = float(i) * 0.25f - 3;
    image.rgba[5] = -0.0f;
    image.extraChannels.push_back({"Z", std::vector<float>(16, 1e30f)});
    file->Finished({0, 2, 0, 2}, image);
    file->Finished({2, 4, 2, 4}, image);
    CHECK(file->error().empty());
    file.reset();
    const std::string bytes = test::ReadText(path);

    CheckpointContents contents;
    REQUIRE(ReadCheckpoint(path, &contents, &error));
    REQUIRE(contents.tiles.size() == 2);
    CHECK(contents.validBytes == bytes.size());
    // Restored pixels are the written ones, -0 included; other pixels are untouched.
    file = CheckpointFile::Resume(path, contents, &error);
    REQUIRE(file);
    image::ImageBuffer restored = image;
    std::fill(restored.rgba.begin(), restored.rgba.end(), 7.0f);
    std::fill(restored.extraChannels[0].second.begin(), restored.extraChannels[0].second.end(), 7.0f);
    CHECK(file->Restore({0, 2, 0, 2}, &restored));
    CHECK(file->Restore({2, 4, 2, 4}, &restored));
    CHECK_FALSE(file->Restore({2, 4, 0, 2}, &restored));
    CHECK(std::bit_cast<uint32_t>(restored.rgba[5]) == std::bit_cast<uint32_t>(-0.0f));
    CHECK(restored.rgba[0] == image.rgba[0]);
    CHECK(restored.rgba[(1 * 4 + 1) * 4 + 2] == image.rgba[(1 * 4 + 1) * 4 + 2]);
    CHECK(restored.rgba[(0 * 4 + 2) * 4] == 7.0f);  // tile [2,4)x[0,2) was never written
    CHECK(restored.extraChannels[0].second[15] == 1e30f);
    file.reset();

    // Cut anywhere inside the last record: that record is dropped.
    for (size_t cut : {size_t(1), size_t(8), size_t(30), size_t(100)}) {
        dir.Write("cut.checkpoint", bytes.substr(0, bytes.size() - cut));
        REQUIRE(ReadCheckpoint(dir.Path("cut.checkpoint"), &contents, &error));
        CHECK(contents.tiles.size() == 1);
        CHECK(contents.droppedTail);
    }
    // A flipped bit in the first record, or in the header, is refused.
    std::string damaged = bytes;
    damaged[bytes.size() - 200] ^= 0x04;
    dir.Write("bad.checkpoint", damaged);
    CHECK_FALSE(ReadCheckpoint(dir.Path("bad.checkpoint"), &contents, &error));
    CHECK(error == "damaged: a bad checksum in tile record 1");
    damaged = bytes;
    damaged[20] ^= 0x01;  // inside the identity
    dir.Write("bad.checkpoint", damaged);
    CHECK_FALSE(ReadCheckpoint(dir.Path("bad.checkpoint"), &contents, &error));
    CHECK(error == "damaged: bad header");
    dir.Write("bad.checkpoint", bytes.substr(0, 20));
    CHECK_FALSE(ReadCheckpoint(dir.Path("bad.checkpoint"), &contents, &error));
    CHECK(error == "damaged: its header is cut short");
    dir.Write("bad.checkpoint", "AFRAYBC");
    CHECK_FALSE(ReadCheckpoint(dir.Path("bad.checkpoint"), &contents, &error));
    CHECK(error == "not an affray checkpoint");
}

TEST_CASE("checkpoint: the render identity changes with the scene, the shader and the options that change pixels",
          "[renderer][checkpoint]") {
    // FNV-1a 128 test vectors.
    CHECK(HashHex("") == "6c62272e07bb014262b821756295c58d");
    CHECK(HashHex("a") == "d228cb696f1a8caf78912b704e4a8964");

    test::TempDir dir;
    const PreparedScene scene = Prepare(dir);
    Options options;
    const RenderIdentity base = IdentifyRender(scene, options);
    CHECK(base.scene.size() == 32);
    CHECK(base.Hash().size() == 32);
    CHECK(IdentifyRender(Prepare(dir), options).Hash() == base.Hash());  // the same scene again
    // The same scene in another directory (a farm machine's mount, another working directory).
    test::TempDir elsewhere;
    CHECK(IdentifyRender(Prepare(elsewhere), options).Hash() == base.Hash());

    // Options that do not change pixels do not change it.
    Options same = options;
    same.threads = 7;
    same.cacheBytes = 1 << 16;
    same.tileSize = 16;
    same.reverseTileOrder = true;
    CHECK(IdentifyRender(scene, same).Hash() == base.Hash());

    Options other = options;
    other.tolerancePixels = 0.25;
    other.bounds = BoundMode::Interval;
    const RenderIdentity changed = IdentifyRender(scene, other);
    CHECK(changed.scene == base.scene);
    CHECK(changed.Hash() != base.Hash());
    CHECK(DifferingOptions(base.options, changed.options) == "bounds, tolerance");
    CHECK(DifferingOptions(base.options, base.options).empty());

    // Another shader parameter, another light: another scene.
    std::string rib = kScene;
    rib.replace(rib.find("\"Km\" [0.06]"), 11, "\"Km\" [0.07]");
    CHECK(IdentifyRender(Prepare(dir, rib), options).scene != base.scene);
    rib = kScene;
    rib.replace(rib.find("[1.1]"), 5, "[1.2]");
    CHECK(IdentifyRender(Prepare(dir, rib), options).scene != base.scene);
}

TEST_CASE(
    "checkpoint: the render identity follows each primitive's texture files, the mesh's faces after the first too",
    "[renderer][checkpoint]") {
    // Consecutive primitives with the same programs add them once (InputsDigest); two patches whose
    // programs differ only in their map must still each bring their map's stamp.
    test::TempDir dir;
    namespace fs = std::filesystem;
    const std::string maps = test::SourceDir() + "/shaders/maps/tiles.exr";
    fs::copy_file(maps, dir.Path("a.exr"));
    fs::copy_file(maps, dir.Path("b.exr"));
    std::string rib = kScene;
    const std::string patch = "  Patch \"bilinear\" \"P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n";
    rib.replace(rib.find("  Displacement"), rib.find("WorldEnd") - rib.find("  Displacement"),
                "  Displacement \"texmap\" \"mapname\" [\"" + dir.Path("a.exr") + "\"]\n" + patch +
                    "  Displacement \"texmap\" \"mapname\" [\"" + dir.Path("b.exr") + "\"]\n" + patch + patch);
    Options options;
    const std::string base = IdentifyRender(Prepare(dir, rib), options).Hash();
    CHECK(IdentifyRender(Prepare(dir, rib), options).Hash() == base);
    for (const char* name : {"a.exr", "b.exr"}) {
        const fs::path file = dir.Path(name);
        fs::last_write_time(file, fs::last_write_time(file) + std::chrono::seconds(10));
        INFO(name);
        CHECK(IdentifyRender(Prepare(dir, rib), options).Hash() != base);
        fs::last_write_time(file, fs::last_write_time(file) - std::chrono::seconds(10));
        CHECK(IdentifyRender(Prepare(dir, rib), options).Hash() == base);
    }
}

TEST_CASE("checkpoint: the render identity follows the surface and light shaders' sources", "[renderer][checkpoint]") {
    // A scene whose surface and light come from .sl files of its own directory: editing either
    // changes the identity (a resumed render must not mix the two).
    test::TempDir dir;
    const std::string surface =
        "surface mine(float Kd = 1) { Oi = Os; Ci = Os * Cs * Kd * diffuse(faceforward(normalize(N), I)); }\n";
    const std::string light = "light lamp(float intensity = 1) { solar (vector(0, 0, -1), 0) Cl = intensity; }\n";
    dir.Write("mine.sl", surface);
    dir.Write("lamp.sl", light);
    std::string rib = kScene;
    rib.replace(rib.find("WorldBegin"), 10, "Option \"searchpath\" \"shader\" [\"" + dir.Path("") + "\"]\nWorldBegin");
    rib.replace(rib.find("LightSource \"distantlight\""), 26, "LightSource \"lamp\"");
    rib.replace(rib.find("  Displacement"), 0, "  Surface \"mine\"\n");
    Options options;
    const std::string base = IdentifyRender(Prepare(dir, rib), options).Hash();
    CHECK(IdentifyRender(Prepare(dir, rib), options).Hash() == base);
    dir.Write("mine.sl", surface + "// edited\n");
    CHECK(IdentifyRender(Prepare(dir, rib), options).Hash() != base);
    dir.Write("mine.sl", surface);
    CHECK(IdentifyRender(Prepare(dir, rib), options).Hash() == base);
    dir.Write("lamp.sl", light + "// edited\n");
    CHECK(IdentifyRender(Prepare(dir, rib), options).Hash() != base);
}
