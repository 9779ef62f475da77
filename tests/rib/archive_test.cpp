// tests/rib/archive_test.cpp: requests that bring in other requests (rib/archive.cpp): ReadArchive
// (relative paths, the archive search path, cycles, missing files, diagnostics located in the
// archive), Procedural "DelayedReadArchive", and retained objects (ObjectBegin/End/Instance by
// number and by name, the instance's transform and attributes), parsed and rendered; and the
// named spaces a shader sees from CoordinateSystem and ScopedCoordinateSystem, rendered.
#include <zlib.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <string>
#include <vector>

#include "renderer/film.h"
#include "renderer/renderer.h"
#include "rib/rib.h"
#include "tests/test_util.h"

using namespace affray;
using namespace affray::renderer;
using affray::rib::ParseRib;
using affray::rib::ReadRib;

namespace {

// A diagnostic as "file:line:col: kind: message", the file cut to its name.
std::string Line(const diag::Diagnostic& d) {
    static const char* const kKind[] = {"error", "warning", "note"};
    return std::filesystem::path(d.where.file).filename().string() + ":" + std::to_string(d.where.line) + ":" +
           std::to_string(d.where.column) + ": " + kKind[static_cast<int>(d.severity)] + ": " + d.message;
}

// The directory of the scene `dir` holds, as the reader names it in messages.
std::string SceneDir(const test::TempDir& dir) {
    return std::filesystem::path(dir.Path("scene.rib")).parent_path().string();
}

std::vector<std::string> Lines(const diag::Report& report) {
    std::vector<std::string> out;
    for (const diag::Diagnostic& d : report.all()) {
        out.push_back(Line(d));
        for (const diag::Diagnostic& note : d.notes) out.push_back(Line(note));
    }
    return out;
}

// An orthographic camera over [-2, 2]^2 looking down -z, 8 x 8 pixels of half a unit, one
// sample at each pixel centre (Hider jitter 0).
const char* const kCamera = R"(Format 8 8 1
Projection "orthographic"
ScreenWindow -2 2 -2 2
PixelSamples 1 1
PixelFilter "box" 1 1
Hider "hidden" "jitter" [0]
Scale 1 1 -1
Translate 0 0 -5
)";

// A unit square in z = 0 with its lower left corner at the origin.
const char* const kSquare = "Patch \"bilinear\" \"P\" [0 0 0  1 0 0  0 1 0  1 1 0]\n";

image::ImageBuffer Render(const SceneDesc& desc, const std::string& shaders = test::SourceDir() + "/shaders") {
    diag::Report error;
    PreparedScene prepared;
    const bool ok = Renderer(Options{.shaderPaths = {shaders}}).Prepare(desc, &prepared, &error);
    INFO(error);
    REQUIRE(ok);
    Options options;
    options.threads = 2;
    image::ImageBuffer image;
    RenderStats stats;
    Renderer(options).Render(prepared, &image, &stats);
    return image;
}

// The diagnostics of a RIB text that must fail to parse, one line each.
std::vector<std::string> ErrorsOf(const std::string& rib) {
    diag::Report report;
    CHECK_FALSE(ParseRib(rib, "t.rib", &report));
    return Lines(report);
}

// The alpha channel as 8 rows of '#' (covered) and '.' (empty), top row first.
std::string Coverage(const image::ImageBuffer& image) {
    std::string text;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const float a = image.rgba[(size_t(y) * image.width + x) * 4 + 3];
            text += a == 1 ? '#' : a == 0 ? '.' : '?';
        }
        text += '\n';
    }
    return text;
}

}  // namespace

TEST_CASE("ReadArchive reads a file in place, relative to the file that reads it", "[renderer][rib]") {
    test::TempDir dir;
    dir.Write("parts/square.rib", std::string("# the square\nColor 0 1 0\n") + kSquare);
    dir.Write("parts/twice.rib", "ReadArchive \"square.rib\"\nTranslate -2 -2 0\nReadArchive \"square.rib\"\n");
    const std::string scene =
        dir.Write("scene.rib", std::string(kCamera) + "WorldBegin\nReadArchive \"parts/twice.rib\"\nWorldEnd\n");
    diag::Report report;
    std::optional<SceneDesc> desc = ReadRib(scene, &report);
    INFO(report);
    REQUIRE(desc);
    CHECK(report.all().empty());
    REQUIRE(desc->primitives.size() == 2);
    CHECK(desc->primitives[0].color == glm::dvec3(0, 1, 0));
    CHECK(desc->primitives[1].base.patch().corners[0] == glm::dvec3(-2, -2, 0));
    // The square at the origin covers pixels 4-5 across and rows 2-3; the moved one the corner.
    CHECK(Coverage(Render(*desc)) ==
          "........\n"
          "........\n"
          "....##..\n"
          "....##..\n"
          "........\n"
          "........\n"
          "##......\n"
          "##......\n");
}

TEST_CASE("ReadArchive searches Option searchpath archive, relative to the scene", "[renderer][rib]") {
    test::TempDir dir;
    dir.Write("lib/a/square.rib", kSquare);
    const std::string body = "WorldBegin\nReadArchive \"square.rib\"\nWorldEnd\n";
    diag::Report report;
    CHECK(ParseRib("Option \"searchpath\" \"archive\" \"none:lib/a\"\n" + body, dir.Path("scene.rib"), &report));
    // '&' keeps the previous path.
    CHECK(ParseRib("Option \"searchpath\" \"archive\" \"lib/a\"\nOption \"searchpath\" \"archive\" \"x:&\"\n" + body,
                   dir.Path("scene.rib"), &report));
    CHECK(ParseRib("Option \"searchpath\" \"archive\" \"" + dir.Path("lib/a") + "\"\n" + body, "/elsewhere/s.rib",
                   &report));
    CHECK(report.all().empty());
    // Without the search path it is not found; the error lists where it looked.
    CHECK_FALSE(ParseRib(body, dir.Path("scene.rib"), &report));
    REQUIRE(report.all().size() == 1);
    CHECK(Line(report.all()[0]) ==
          "scene.rib:2:13: error: archive 'square.rib' not found (searched " + SceneDir(dir) + ")");
}

TEST_CASE("ReadArchive errors name the archive's own file, line and column", "[renderer][rib]") {
    test::TempDir dir;
    SECTION("an error inside an archive") {
        dir.Write("bad.rib", "Color 1 0 0\n  Sphere 1 -1\n");
        const std::string scene = dir.Write("scene.rib", "WorldBegin\nReadArchive \"bad.rib\"\nWorldEnd\n");
        diag::Report report;
        CHECK_FALSE(ReadRib(scene, &report));
        REQUIRE(report.all().size() == 1);
        CHECK(Line(report.all()[0]) ==
              "bad.rib:2:3: error: 'Sphere' expects 4 numbers (radius zmin zmax thetamax), got 2");
        CHECK(report.all()[0].where.text == "  Sphere 1 -1");
    }
    SECTION("warnings inside an archive, and the scene goes on after it") {
        dir.Write("warn.rib", "\nShadingRate 2\nAttribute \"identifier\" \"name\" \"a\"\n");
        const std::string scene = dir.Write(
            "scene.rib", "WorldBegin\nReadArchive \"warn.rib\"\nShadingRate 3\n" + std::string(kSquare) + "WorldEnd\n");
        diag::Report report;
        std::optional<SceneDesc> desc = ReadRib(scene, &report);
        REQUIRE(desc);
        CHECK(desc->primitives.size() == 1);
        CHECK(desc->primitives[0].attr().line == 4);
        CHECK(Lines(report) ==
              std::vector<std::string>{
                  "warn.rib:2:1: note: 'ShadingRate' 2: the primitives that follow are certified to 0.707107 "
                  "pixels, not 0.5 (unless --tolerance is given)",
                  "warn.rib:3:1: warning: 'Attribute \"identifier\"' does not apply to affray; ignored",
                  "scene.rib:3:1: note: 'ShadingRate' 3: the primitives that follow are certified to 0.866025 "
                  "pixels, not 0.5 (unless --tolerance is given)"});
    }
    SECTION("an unterminated block in an archive") {
        dir.Write("open.rib", "AttributeBegin\n");
        const std::string scene = dir.Write("scene.rib", "WorldBegin\nReadArchive \"open.rib\"\nWorldEnd\n");
        diag::Report report;
        CHECK_FALSE(ReadRib(scene, &report));
        CHECK(Lines(report) == std::vector<std::string>{
                                   "scene.rib:3:1: error: 'WorldEnd' does not match 'AttributeBegin' on line 1 of " +
                                   dir.Path("open.rib")});
    }
    SECTION("a missing archive and a directory") {
        std::filesystem::create_directories(dir.Path("adir"));
        const std::string scene = dir.Write("scene.rib", "WorldBegin\nReadArchive \"missing.rib\"\nWorldEnd\n");
        diag::Report report;
        CHECK_FALSE(ReadRib(scene, &report));
        CHECK(Lines(report) == std::vector<std::string>{"scene.rib:2:13: error: archive 'missing.rib' not found "
                                                        "(searched " +
                                                        SceneDir(dir) + ")"});
        CHECK_FALSE(ParseRib("ReadArchive \"adir\"\n", dir.Path("scene.rib"), &report));
        CHECK_FALSE(ParseRib("ReadArchive 3\n", dir.Path("scene.rib"), &report));
        CHECK(test::LastMessage(report).find("'ReadArchive' expects an archive file name as its first argument") !=
              std::string::npos);
    }
    SECTION("cycles") {
        dir.Write("a.rib", "ReadArchive \"b.rib\"\n");
        dir.Write("b.rib", "\n ReadArchive \"a.rib\"\n");
        const std::string scene = dir.Write("scene.rib", "WorldBegin\nReadArchive \"a.rib\"\nWorldEnd\n");
        diag::Report report;
        CHECK_FALSE(ReadRib(scene, &report));
        REQUIRE(report.all().size() == 1);
        CHECK(Line(report.all()[0]) == "b.rib:2:14: error: 'ReadArchive' cycle: " + scene + " -> " + dir.Path("a.rib") +
                                           " -> " + dir.Path("b.rib") + " -> " + dir.Path("a.rib"));
        dir.Write("self.rib", "ReadArchive \"self.rib\"\n");
        CHECK_FALSE(ParseRib("ReadArchive \"self.rib\"\n", dir.Path("scene.rib"), &report));
        CHECK(test::LastMessage(report).find("self.rib:1:13: error: 'ReadArchive' cycle") != std::string::npos);
    }
}

TEST_CASE("Displacement shader messages inside an archive name the archive", "[renderer][rib]") {
    test::TempDir dir;
    dir.Write("part.rib", "\nDisplacement \"no_such_shader\"\n" + std::string(kSquare));
    const std::string scene = dir.Write("scene.rib", "WorldBegin\nReadArchive \"part.rib\"\nWorldEnd\n");
    diag::Report report;
    std::optional<SceneDesc> desc = ReadRib(scene, &report);
    REQUIRE(desc);
    REQUIRE(desc->primitives.size() == 1);
    CHECK(desc->primitives[0].attr().displacement->file == dir.Path("part.rib"));
    PreparedScene prepared;
    CHECK(Renderer(Options{.shaderPaths = {test::SourceDir() + "/shaders"}}).Prepare(*desc, &prepared, &report));
    REQUIRE(!report.all().empty());
    CHECK(Line(report.all().back()).rfind("part.rib:2:1: warning: shader 'no_such_shader' not found", 0) == 0);
    CHECK(report.all().back().where.text == "Displacement \"no_such_shader\"");
}

TEST_CASE("ObjectInstance places a retained object with the instance's transform", "[renderer][rib]") {
    // Object 1 (by number) is the square moved left; "pair" (by name) two squares, coloured inside.
    const std::string rib = std::string(kCamera) +
                            "ObjectBegin 1\n"
                            "  Translate -1 0 0\n" +
                            kSquare +
                            "ObjectEnd\n"
                            "WorldBegin\n"
                            "  ObjectBegin \"pair\"\n"
                            "    AttributeBegin\n      Color 1 0 0\n" +
                            kSquare + "    AttributeEnd\n    Translate 0 -2 0\n" + kSquare +
                            "  ObjectEnd\n"
                            "  Color 0 0 1\n"
                            "  ObjectInstance 1\n"
                            "  TransformBegin\n    Translate 1 1 0\n    ObjectInstance \"pair\"\n  TransformEnd\n"
                            "  ObjectInstance 1\n"  // the object's Translate did not leak out
                            "WorldEnd\n";
    diag::Report report;
    std::optional<SceneDesc> desc = ParseRib(rib, "t.rib", &report);
    INFO(report);
    REQUIRE(desc);
    CHECK(report.all().empty());
    REQUIRE(desc->primitives.size() == 4);
    CHECK(desc->primitives[0].base.patch().corners[0] == glm::dvec3(-1, 0, 0));
    CHECK(desc->primitives[0].color == glm::dvec3(0, 0, 1));  // the instance's colour
    CHECK(desc->primitives[1].base.patch().corners[0] == glm::dvec3(1, 1, 0));
    CHECK(desc->primitives[1].color == glm::dvec3(1, 0, 0));  // the object's own colour
    CHECK(desc->primitives[2].base.patch().corners[0] == glm::dvec3(1, -1, 0));
    CHECK(desc->primitives[2].color == glm::dvec3(0, 0, 1));
    CHECK(desc->primitives[3].base.patch().corners[0] == glm::dvec3(-1, 0, 0));
    CHECK(desc->primitives[1].attr().line == 17);  // where the object defines it
    CHECK(Coverage(Render(*desc)) ==
          "......##\n"
          "......##\n"
          "..##....\n"
          "..##....\n"
          "......##\n"
          "......##\n"
          "........\n"
          "........\n");
}

TEST_CASE("Inline archives (ArchiveBegin) are read where ReadArchive names them, before a file", "[renderer][rib]") {
    test::TempDir dir;
    dir.Write("square", std::string("Color 1 1 0\n") + kSquare);  // a file of the same name: not read
    // Defined before the world, inside an object and inside another archive (defined when read);
    // a conditional inside it is decided where it is read.
    const std::string scene =
        dir.Write("scene.rib", std::string(kCamera) +
                                   "ArchiveBegin \"square\" \"string note\" [\"x\"]\n"
                                   "  IfBegin \"defined(user:green)\"\n    Color 0 1 0\n  IfEnd\n" +
                                   kSquare +
                                   "ArchiveEnd\n"
                                   "ArchiveBegin \"outer\"\n"
                                   "  ArchiveBegin \"inner\"\n    Translate -2 -2 0\n"
                                   "  ArchiveEnd\n"
                                   "ArchiveEnd\n"
                                   "WorldBegin\n"
                                   "  ReadArchive \"square\"\n"
                                   "  Attribute \"user\" \"float green\" [1]\n"
                                   "  ReadArchive \"outer\"\n"
                                   "  ReadArchive \"inner\"\n"
                                   "  ReadArchive \"square\"\n"
                                   "WorldEnd\n");
    diag::Report report;
    std::optional<SceneDesc> desc = ReadRib(scene, &report);
    INFO(report);
    REQUIRE(desc);
    CHECK(report.all().empty());
    REQUIRE(desc->primitives.size() == 2);
    CHECK(desc->primitives[0].base.patch().corners[0] == glm::dvec3(0, 0, 0));
    CHECK(desc->primitives[0].color == glm::dvec3(1, 1, 1));
    CHECK(desc->primitives[1].base.patch().corners[0] == glm::dvec3(-2, -2, 0));
    CHECK(desc->primitives[1].color == glm::dvec3(0, 1, 0));
    CHECK(desc->primitives[1].attr().line == 13);  // where the archive says it
    CHECK(Coverage(Render(*desc)) ==
          "........\n"
          "........\n"
          "....##..\n"
          "....##..\n"
          "........\n"
          "........\n"
          "##......\n"
          "##......\n");
}

TEST_CASE("Inline archives give exact errors", "[renderer][rib]") {
    using Lines = std::vector<std::string>;
    CHECK(ErrorsOf("WorldBegin\nArchiveEnd\nWorldEnd\n") ==
          Lines{"t.rib:2:1: error: 'ArchiveEnd' without matching 'ArchiveBegin'"});
    CHECK(ErrorsOf("ArchiveBegin \"a\"\nWorldBegin\nWorldEnd\n") ==
          Lines{"t.rib:1:1: error: 'ArchiveBegin' has no matching 'ArchiveEnd'"});
    CHECK(ErrorsOf("ArchiveBegin\nArchiveEnd\n") ==
          Lines{"t.rib:1:1: error: 'ArchiveBegin' expects an archive name as its first argument"});
    // An error inside is reported where the archive says it.
    CHECK(ErrorsOf("ArchiveBegin \"a\"\nSphere 1 2\nArchiveEnd\nWorldBegin\nReadArchive \"a\"\nWorldEnd\n") ==
          Lines{"t.rib:2:1: error: 'Sphere' expects 4 numbers (radius zmin zmax thetamax), got 2"});
    CHECK(ErrorsOf("ArchiveBegin \"a\"\nReadArchive \"a\"\nArchiveEnd\nWorldBegin\nReadArchive \"a\"\nWorldEnd\n") ==
          Lines{"t.rib:2:13: error: inline archive 'a' reads itself (from line 5)"});
}

TEST_CASE("Retained objects give exact errors", "[renderer][rib]") {
    using Lines = std::vector<std::string>;
    CHECK(ErrorsOf("WorldBegin\nObjectInstance 3\nWorldEnd\n") ==
          Lines{"t.rib:2:16: error: no object '3' has been defined"});
    CHECK(ErrorsOf("WorldBegin\nObjectBegin 1\nSphere 1 -1 1 360\n") ==
          Lines{"t.rib:2:1: error: 'ObjectBegin' has no matching 'ObjectEnd'"});
    CHECK(ErrorsOf("WorldBegin\nObjectEnd\nWorldEnd\n") ==
          Lines{"t.rib:2:1: error: 'ObjectEnd' without matching 'ObjectBegin'"});
    CHECK(ErrorsOf("WorldBegin\nObjectBegin 1\nLightSource \"pointlight\" 1\nObjectEnd\nWorldEnd\n") ==
          Lines{"t.rib:3:1: error: 'LightSource' cannot be part of an object (started by 'ObjectBegin' on line 2)"});
    CHECK(ErrorsOf("WorldBegin\nObjectBegin 1\nAttributeBegin\nObjectEnd\nWorldEnd\n") ==
          Lines{"t.rib:4:1: error: 'ObjectEnd' inside an 'AttributeBegin' or 'TransformBegin' of the object"});
    CHECK(ErrorsOf("WorldBegin\nAttributeBegin\nObjectBegin 1\nAttributeEnd\nObjectEnd\nWorldEnd\n") ==
          Lines{"t.rib:4:1: error: 'AttributeEnd' inside an object closes a block opened outside it"});
    CHECK(ErrorsOf("WorldBegin\nObjectBegin\nObjectEnd\nWorldEnd\n") ==
          Lines{"t.rib:2:1: error: 'ObjectBegin' expects one object handle (a number or a string)"});
    CHECK(ErrorsOf("ObjectBegin 1\nObjectEnd\nObjectInstance 1\nWorldBegin\nWorldEnd\n") ==
          Lines{"t.rib:3:1: error: 'ObjectInstance' must come between 'WorldBegin' and 'WorldEnd'"});
    // An error in an object is reported where the object says it, with a note at the instance.
    CHECK(ErrorsOf("WorldBegin\nObjectBegin 1\nSphere 1 2\nObjectEnd\n\nObjectInstance 1\nWorldEnd\n") ==
          Lines{"t.rib:3:1: error: 'Sphere' expects 4 numbers (radius zmin zmax thetamax), got 2",
                "t.rib:6:1: note: in the instance of object '1' here"});
    // An object redefined to instance itself recurses no further than the limit.
    CHECK(ErrorsOf("WorldBegin\nObjectBegin 1\nObjectEnd\nObjectBegin 1\nObjectInstance 1\nObjectEnd\n"
                   "ObjectInstance 1\nWorldEnd\n")
              .front() ==
          "t.rib:5:1: error: objects instance each other more than 32 deep (an object that instances itself?)");
}

TEST_CASE("Procedural DelayedReadArchive reads its archive at once, in an attribute block of its own",
          "[renderer][rib]") {
    test::TempDir dir;
    // The archive changes the colour and the transform for what follows it inside the archive.
    dir.Write("parts/square.rib",
              std::string("Color 1 0 0\n") + kSquare + "Translate -2 -2 0\nColor 0 0 1\n" + kSquare);
    const std::string after = std::string("Color 0 1 0\n") +
                              "Procedural \"DelayedReadArchive\" [\"parts/square.rib\"] "
                              "[0 1 0 1 0 0]\n" +
                              kSquare;
    diag::Report report;
    std::optional<SceneDesc> desc =
        ParseRib(std::string(kCamera) + "WorldBegin\n" + after + "WorldEnd\n", dir.Path("scene.rib"), &report);
    INFO(report);
    REQUIRE(desc);
    CHECK(report.all().empty());
    REQUIRE(desc->primitives.size() == 3);
    CHECK(desc->primitives[0].color == glm::dvec3(1, 0, 0));
    CHECK(desc->primitives[1].color == glm::dvec3(0, 0, 1));
    CHECK(desc->primitives[1].base.patch().corners[0] == glm::dvec3(-2, -2, 0));
    // After it: the colour and transform of before it.
    CHECK(desc->primitives[2].color == glm::dvec3(0, 1, 0));
    CHECK(desc->primitives[2].base.patch().corners[0] == glm::dvec3(0, 0, 0));

    // Procedural2 "DelayedReadArchive2" names the file as a parameter; in an object definition
    // the archive's requests are part of the object, in their block.
    const std::string procedural2 =
        "Procedural2 \"DelayedReadArchive2\" \"SimpleBound\" \"string filename\" [\"parts/square.rib\"] "
        "\"float[6] bound\" [0 1 0 1 0 0]\n";
    desc = ParseRib(std::string(kCamera) + "WorldBegin\nObjectBegin 1\n" + procedural2 +
                        "ObjectEnd\nColor 0 1 0\nObjectInstance 1\nTranslate 1 0 0\nObjectInstance 1\n" + kSquare +
                        "WorldEnd\n",
                    dir.Path("scene.rib"), &report);
    INFO(report);
    REQUIRE(desc);
    REQUIRE(desc->primitives.size() == 5);
    CHECK(desc->primitives[2].color == glm::dvec3(1, 0, 0));
    CHECK(desc->primitives[2].base.patch().corners[0] == glm::dvec3(1, 0, 0));
    CHECK(desc->primitives[3].base.patch().corners[0] == glm::dvec3(-1, -2, 0));
    CHECK(desc->primitives[4].color == glm::dvec3(0, 1, 0));
    CHECK(desc->primitives[4].base.patch().corners[0] == glm::dvec3(1, 0, 0));
}

TEST_CASE("Procedurals that run programs are skipped, unknown ones and bad arguments refused", "[renderer][rib]") {
    test::TempDir dir;
    dir.Write("open.rib", std::string("AttributeBegin\n") + kSquare);
    auto error = [&](const std::string& request) {
        diag::Report report;
        CHECK_FALSE(ParseRib("WorldBegin\n" + request + "\nWorldEnd\n", dir.Path("scene.rib"), &report));
        REQUIRE(report.all().size() == 1);
        return Line(report.all()[0]);
    };
    // A program's geometry is skipped with a warning, as an unsupported primitive is.
    for (const char* kind : {"RunProgram", "DynamicLoad"}) {
        diag::Report report;
        const std::string request = "Procedural \"" + std::string(kind) + "\" [\"make\" \"\"] [-1 1 -1 1 -1 1]\n";
        const auto scene = ParseRib("WorldBegin\n" + request + kSquare + "WorldEnd\n", dir.Path("scene.rib"), &report);
        REQUIRE(scene);
        CHECK(scene->primitives.size() == 1);
        REQUIRE(report.all().size() == 1);
        CHECK(Line(report.all()[0]) == "scene.rib:2:12: warning: procedural '" + std::string(kind) +
                                           "' makes geometry by running a program, which affray does not do: skipped "
                                           "(write its output to a RIB file and read that with 'ReadArchive')");
    }
    CHECK(error("Procedural \"Sprinkle\" [\"a\"] [-1 1 -1 1 -1 1]") ==
          "scene.rib:2:12: error: unknown procedural 'Sprinkle' (affray reads \"DelayedReadArchive\")");
    CHECK(error("Procedural \"DelayedReadArchive\" [\"open.rib\"] [-1 1]") ==
          "scene.rib:2:33: error: 'Procedural \"DelayedReadArchive\"' expects [\"file\"] and a bound [xmin xmax ymin "
          "ymax zmin zmax]");
    CHECK(error("Procedural \"DelayedReadArchive\" [\"gone.rib\"] [-1 1 -1 1 -1 1]") ==
          "scene.rib:2:33: error: archive 'gone.rib' not found (searched " + SceneDir(dir) + ")");
    CHECK(error("Procedural2 \"DelayedReadArchive2\" \"SimpleBound\" \"float[6] bound\" [-1 1 -1 1 -1 1]") ==
          "scene.rib:2:1: error: 'Procedural2 \"DelayedReadArchive2\"' needs a \"string filename\" parameter");
    // The archive must close the blocks it opens.
    CHECK(error("Procedural \"DelayedReadArchive\" [\"open.rib\"] [-1 1 -1 1 -1 1]")
              .find("error: the archive read by 'Procedural' on line 2 leaves a block open") != std::string::npos);
}

TEST_CASE("A shader sees a ScopedCoordinateSystem over a CoordinateSystem of the same name", "[renderer][rib]") {
    test::TempDir dir;
    // Moves the square's points down 2 units where the x of P in the space named by `space` is
    // within (0.5, 1): a band of the square whose place tells the space apart.
    dir.Write("band.sl",
              "displacement band(string space = \"shader\") {\n"
              "  float x = xcomp(transform(space, P));\n"
              "  P += (x > 0.5 && x < 1 ? 1 : 0) * vector(0, -2, 0);\n"
              "}\n");
    const std::string square = "Displacement \"band\" \"string space\" \"paint\"\n" + std::string(kSquare);
    auto render = [&](const std::string& world) {
        diag::Report report;
        std::optional<SceneDesc> desc =
            ParseRib(std::string(kCamera) + "WorldBegin\n" + world + "WorldEnd\n", dir.Path("scene.rib"), &report);
        INFO(report);
        REQUIRE(desc);
        return Coverage(Render(*desc, dir.Path(".")));
    };
    // "paint" one unit left of world: x in paint = world x + 1, so the band is at world x in
    // [-0.5, 0], off the square; with paint at world, the band is the square's right half.
    const std::string left = "Translate -1 0 0\n";
    const std::string global =
        render("AttributeBegin\n" + left + "CoordinateSystem \"paint\"\nAttributeEnd\n" + square);
    const std::string scoped = render("CoordinateSystem \"paint\"\nAttributeBegin\n" + left +
                                      "ScopedCoordinateSystem \"paint\"\nIdentity\n" + square + "AttributeEnd\n");
    const std::string atWorld = render("CoordinateSystem \"paint\"\n" + square);
    CHECK(scoped == global);
    CHECK(scoped != atWorld);
    // After the block the scene's own "paint" is seen again.
    CHECK(render("CoordinateSystem \"paint\"\nAttributeBegin\n" + left +
                 "ScopedCoordinateSystem \"paint\"\nAttributeEnd\n" + square) == atWorld);
}

namespace {

// `text` gzip-compressed into file `path` (one gzip member per piece of `pieces`, as
// `gzip -c a b > c` writes them).
void WriteGzip(const std::string& path, const std::vector<std::string>& pieces) {
    std::string bytes;
    for (const std::string& piece : pieces) {
        z_stream z{};
        REQUIRE(deflateInit2(&z, 9, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) == Z_OK);
        std::string out(deflateBound(&z, piece.size()) + 64, '\0');
        z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(piece.data()));
        z.avail_in = static_cast<uInt>(piece.size());
        z.next_out = reinterpret_cast<Bytef*>(out.data());
        z.avail_out = static_cast<uInt>(out.size());
        REQUIRE(deflate(&z, Z_FINISH) == Z_STREAM_END);
        out.resize(z.total_out);
        deflateEnd(&z);
        bytes += out;
    }
    std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace

TEST_CASE("gzip-compressed scenes and archives read as their text, within rib-bytes", "[renderer][rib]") {
    test::TempDir dir;
    const std::string world = "WorldBegin\nReadArchive \"parts.rib.gz\"\nWorldEnd\n";
    WriteGzip(dir.Path("parts.rib.gz"),
              {std::string("Color 0 1 0\n") + kSquare, "Translate -2 -2 0\n" + std::string(kSquare)});
    dir.Write("plain.rib", std::string(kCamera) + "WorldBegin\nColor 0 1 0\n" + kSquare + "Translate -2 -2 0\n" +
                               kSquare + "WorldEnd\n");
    WriteGzip(dir.Path("scene.rib.gz"), {std::string(kCamera) + world});
    diag::Report report;
    std::optional<SceneDesc> plain = ReadRib(dir.Path("plain.rib"), &report);
    std::optional<SceneDesc> gz = ReadRib(dir.Path("scene.rib.gz"), &report);
    INFO(report);
    REQUIRE(plain);
    REQUIRE(gz);
    REQUIRE(gz->primitives.size() == 2);
    CHECK(gz->primitives[0].color == glm::dvec3(0, 1, 0));
    CHECK(gz->primitives[1].base.patch().corners[0] == glm::dvec3(-2, -2, 0));
    CHECK(Coverage(Render(*gz)) == Coverage(Render(*plain)));

    auto error = [&](const std::string& path) {
        diag::Report r;
        CHECK_FALSE(ReadRib(path, &r));
        REQUIRE(r.all().size() == 1);
        return Line(r.all()[0]);
    };
    // A stream cut short, or damaged.
    std::string bytes = test::ReadText(dir.Path("parts.rib.gz"));
    dir.Write("cut.rib.gz", bytes.substr(0, bytes.size() / 2));
    std::string damaged = bytes;
    damaged[12] = static_cast<char>(damaged[12] ^ 0x5a);
    damaged[13] = static_cast<char>(damaged[13] ^ 0xa5);
    dir.Write("damaged.rib.gz", damaged);
    CHECK(error(dir.Path("cut.rib.gz")) == "cut.rib.gz:0:0: error: cannot read file: the gzip stream is cut short");
    CHECK(error(dir.Path("damaged.rib.gz")).find("cut.rib.gz") == std::string::npos);
    CHECK(error(dir.Path("damaged.rib.gz")).find("error: cannot read file: the gzip stream is damaged (") !=
          std::string::npos);

    // rib-bytes: a plain file past it is refused before it is read; a compressed one as it
    // decompresses past it.
    const std::string big(5000, '#');
    dir.Write("big.rib", big + "\n");
    WriteGzip(dir.Path("big.rib.gz"), {big + "\n"});
    {
        test::ScopedLimit limit(diag::Limit::RibBytes, 4096);
        CHECK(error(dir.Path("big.rib")) ==
              "big.rib:0:0: error: cannot read file: it holds more than 4096 bytes (limit rib-bytes = 4096; raise it "
              "with --limit rib-bytes=N)");
        CHECK(error(dir.Path("big.rib.gz")) ==
              "big.rib.gz:0:0: error: cannot read file: decompressed, it holds more than 4096 bytes (limit rib-bytes = "
              "4096; raise it with --limit rib-bytes=N)");
        CHECK(ReadRib(dir.Path("scene.rib.gz"), &report));
    }
}
