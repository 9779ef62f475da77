// tests/renderer/render_test.cpp: scene preparation and the tile loop (renderer/render.*) on tiny
// scenes whose answers are known by hand: clipping planes, one-sided surfaces, the shader search
// path, named coordinate systems, clipping planes and format seen by shaders, quadrics in the BVH,
// and AOVs.
#include "renderer/renderer.h"

#include <catch2/catch.hpp>

#include <sstream>

#include "renderer/film.h"
#include "rib/rib.h"
#include "tests/test_random.h"
#include "tests/test_util.h"

using namespace affray;
using namespace affray::renderer;
using affray::rib::ParseRib;

namespace {

/// Parses `rib` (the scene's path is `dir`/scene.rib, for the search path), prepares and renders
/// it with one box-filtered sample per pixel; returns the image.
/// With `split`, the BVH is built that way (Options::bvhSplit).
image::ImageBuffer Render(const test::TempDir& dir, const std::string& rib, PreparedScene* keep = nullptr,
                          Bvh::Split split = Bvh::Split::kSah) {
    affray::diag::Report error;
    std::optional<SceneDesc> desc = ParseRib(rib, dir.Path("scene.rib"), &error);
    INFO(error);
    REQUIRE(desc);
    desc->camera.xsamples = desc->camera.ysamples = 1;
    desc->camera.filter = FilterDesc{FilterDesc::Kind::Box, 1, 1};
    PreparedScene prepared;
    const bool prepared_ok = Renderer(Options{.shaderPaths = {test::SourceDir() + "/shaders"}, .bvhSplit = split})
                                 .Prepare(*desc, &prepared, &error);
    INFO(error);
    REQUIRE(prepared_ok);
    Options options;
    options.threads = 2;
    image::ImageBuffer image;
    RenderStats stats;
    Renderer(options).Render(prepared, &image, &stats);
    if (keep) *keep = std::move(prepared);
    return image;
}

float Alpha(const image::ImageBuffer& image, int x, int y) { return image.rgba[(size_t(y) * image.width + x) * 4 + 3]; }

const std::vector<float>& Channel(const image::ImageBuffer& image, const std::string& name) {
    for (const auto& [n, values] : image.extraChannels)
        if (n == name) return values;
    FAIL("no channel " << name);
    static std::vector<float> none;
    return none;
}

// An orthographic camera looking down -z at the unit square around the origin (camera z into the
// scene): world (x, y, z) is seen at depth 5 - z.
const char* const kCamera = R"(Format 8 8 1
Projection "orthographic"
ScreenWindow -1 1 -1 1
Display "t.exr" "file" "rgba,Z,N,P,st,cost"
Scale 1 1 -1
Translate 0 0 -5
)";

int Covered(const image::ImageBuffer& image) {
    int n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) n += Alpha(image, x, y) == 1.0f;
    return n;
}

}  // namespace

TEST_CASE("render: clipping planes cut camera rays by camera depth", "[renderer][render]") {
    test::TempDir dir;
    const std::string world = "WorldBegin\nSphere 0.9 -0.9 0.9 360\nWorldEnd\n";
    // The sphere spans depths 4.1 to 5.9: a near plane past its back, or a far plane before its
    // front, leaves nothing; a near plane through its middle shows the back half's inside.
    CHECK(Covered(Render(dir, std::string(kCamera) + world)) > 30);
    CHECK(Covered(Render(dir, std::string(kCamera) + "Clipping 6 100\n" + world)) == 0);
    CHECK(Covered(Render(dir, std::string(kCamera) + "Clipping 0.1 4\n" + world)) == 0);
    const image::ImageBuffer cut = Render(dir, std::string(kCamera) + "Clipping 5 100\n" + world);
    REQUIRE(Covered(cut) > 30);
    const std::vector<float>& z = Channel(cut, "Z");
    for (float depth : z)
        if (depth < 1e29f) CHECK(depth >= 5.0f);
}

TEST_CASE("render: a one-sided surface seen from behind is invisible", "[renderer][render]") {
    test::TempDir dir;
    // The patch's dPdu x dPdv points to +z, towards the camera: seen from the front. Reversed, the
    // camera sees its back: with Sides 1 it vanishes, and the sphere behind it shows through.
    const std::string patch = "Patch \"bilinear\" \"P\" [-1 -1 1  1 -1 1  -1 1 1  1 1 1]\n";
    const std::string sphere = "Sphere 0.5 -0.5 0.5 360\n";
    auto render = [&](const std::string& attributes) {
        return Render(dir,
                      std::string(kCamera) + "WorldBegin\n" + attributes + patch + "Sides 2\n" + sphere + "WorldEnd\n");
    };
    const image::ImageBuffer front = render("Sides 1\n"), back = render("Sides 1\nReverseOrientation\n"),
                             twoSided = render("ReverseOrientation\n");
    CHECK(Covered(front) == 64);
    CHECK(Covered(twoSided) == 64);
    const int sphereOnly = Covered(back);
    CHECK(sphereOnly > 4);
    CHECK(sphereOnly < 40);
    // Where the sphere shows through, its depth (at most 4.5 + 0.5) is behind the patch (4).
    const std::vector<float>& z = Channel(back, "Z");
    for (float depth : z)
        if (depth < 1e29f) CHECK(depth > 4.4f);
}

TEST_CASE("render: shaders are found on the scene's search path and see its coordinate systems", "[renderer][render]") {
    test::TempDir dir;
    // The shader lifts P by the height of "lift" space's origin above world's: 0.5. It lives in a
    // directory only the scene's search path names.
    dir.Write("mine/lifted.sl",
              "displacement lifted() { P += vector(0, 0, zcomp(transform(\"lift\", \"world\", point(0, 0, 0)))); }");
    const std::string world =
        "WorldBegin\nTransformBegin\nTranslate 0 0 0.5\nCoordinateSystem \"lift\"\n"
        "TransformEnd\nDisplacement \"lifted\"\n"
        "Patch \"bilinear\" \"P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\nWorldEnd\n";
    const image::ImageBuffer image =
        Render(dir, std::string(kCamera) + "Option \"searchpath\" \"shader\" [\"mine:&\"]\n" + world);
    REQUIRE(Covered(image) == 64);
    for (float depth : Channel(image, "Z")) CHECK(depth == Approx(4.5).margin(0.02));
    // Without the search path the shader is not found: a warning naming the directories searched,
    // and the patch renders undisplaced (as prman renders it).
    affray::diag::Report error;
    std::optional<SceneDesc> desc = ParseRib(std::string(kCamera) + world, dir.Path("scene.rib"), &error);
    REQUIRE(desc);
    PreparedScene prepared;
    CHECK(Renderer(Options{.shaderPaths = {test::SourceDir() + "/shaders"}}).Prepare(*desc, &prepared, &error));
    CHECK(error.format().find("warning: shader 'lifted' not found") != std::string::npos);
    CHECK_FALSE(error.hasErrors());
    REQUIRE(prepared.primitives.size() == 1);
    CHECK_FALSE(prepared.primitives[0].shader());
}

TEST_CASE("render: shaders see the scene's clipping planes and format through depth() and option()",
          "[renderer][render]") {
    test::TempDir dir;
    // The patch is at camera depth 5; with Clipping 1 9 its depth() is 0.5, and Format 8 8 1
    // makes the factor 1: lifted by 0.5 towards the camera.
    dir.Write("mine/deep.sl",
              "displacement deep() { float f[3]; float k = option(\"Format\", f);\n"
              "  P += vector(0, 0, depth(P) * k * f[0] / 8); }");
    const std::string world =
        "Clipping 1 9\nOption \"searchpath\" \"shader\" [\"mine:&\"]\nWorldBegin\nDisplacement \"deep\"\n"
        "Patch \"bilinear\" \"P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\nWorldEnd\n";
    const image::ImageBuffer image = Render(dir, std::string(kCamera) + world);
    REQUIRE(Covered(image) == 64);
    for (float depth : Channel(image, "Z")) CHECK(depth == Approx(4.5).margin(0.02));
}

TEST_CASE("render: quadrics and patches share the BVH, and AOVs describe the nearest hit", "[renderer][render]") {
    test::TempDir dir;
    // A unit sphere in front of a far patch. Near the image centre the sphere is hit near its
    // north pole (v = 1), which faces the camera: P on the unit sphere, N = P, depth 5 - P.z.
    PreparedScene prepared;
    const image::ImageBuffer image = Render(dir,
                                            std::string(kCamera) +
                                                "WorldBegin\nSphere 1 -1 1 360\n"
                                                "Patch \"bilinear\" \"P\" [-1 -1 -2  1 -1 -2  -1 1 -2  1 1 -2]\n"
                                                "WorldEnd\n",
                                            &prepared);
    CHECK(prepared.bvh->nodeCount() == 1);  // one leaf holds both
    CHECK(Covered(image) == 64);
    const size_t centre = 4 * 8 + 4;  // pixel (4, 4), whose sample is jittered in [0, 0.25]^2
    const glm::dvec3 P(Channel(image, "P.X")[centre], Channel(image, "P.Y")[centre], Channel(image, "P.Z")[centre]);
    const glm::dvec3 N(Channel(image, "N.X")[centre], Channel(image, "N.Y")[centre], Channel(image, "N.Z")[centre]);
    CHECK(glm::length(P) == Approx(1).margin(0.01));
    CHECK(glm::length(N - P) < 0.02);
    CHECK(P.x >= -0.01);
    CHECK(P.x <= 0.26);
    CHECK(Channel(image, "Z")[centre] == Approx(5 - P.z).margin(0.01));
    CHECK(Channel(image, "st.t")[centre] > 0.9f);
    CHECK(Channel(image, "cost")[centre] > 0);
    // The corner pixel (0, 0) misses the sphere and sees the patch at depth 7.
    CHECK(Channel(image, "Z")[0] == Approx(7).margin(1e-6));
    CHECK(Channel(image, "N.Z")[0] == Approx(1).margin(1e-9));
}

TEST_CASE("render: a crater field on a displaced sphere is bounded and renders", "[renderer][render]") {
    test::TempDir dir;
    // shaders/craters.sl: smoothstep edges from cellnoise that may coincide, in a min over 27
    // cells. At frequency 12 every cell of the renderer's 8 x 8 check grid spans several lattice
    // cells, where the smoothstep divides by a range containing 0: before issue 12 the sphere was
    // refused ("cannot be bounded over any part of the patch"). Craters only push inwards, by at
    // most Km: every hit lies between radius 1 - Km and 1.
    const double km = 0.08;
    PreparedScene prepared;
    const image::ImageBuffer image =
        Render(dir,
               std::string(kCamera) + "WorldBegin\nDisplacement \"craters\" \"Km\" [" + std::to_string(km) +
                   "] \"frequency\" [12]\nSphere 1 -1 1 360\nWorldEnd\n",
               &prepared);
    // The disc of radius 1 - Km is covered whatever the craters; the corners are empty.
    CHECK(Covered(image) >= 32);
    CHECK(Alpha(image, 0, 0) == 0.0f);
    for (int y = 2; y <= 5; ++y)
        for (int x = 2; x <= 5; ++x) {
            const size_t i = size_t(y) * 8 + x;
            INFO("pixel " << x << ", " << y);
            REQUIRE(Alpha(image, x, y) == 1.0f);
            const glm::dvec3 P(Channel(image, "P.X")[i], Channel(image, "P.Y")[i], Channel(image, "P.Z")[i]);
            CHECK(glm::length(P) >= 1 - km - 1e-3);
            CHECK(glm::length(P) <= 1 + 1e-3);
            CHECK(P.z > 0);  // the near hemisphere, seen from +z
        }
}

namespace {

// A perspective view of a displaced twisted sheet, 48 x 36, for comparing base surfaces.
const char* const kSheetCamera = R"(Format 48 36 1
Projection "perspective" "fov" [40]
Display "t.exr" "file" "rgba,st,P,err"
Translate 0 0 3.1
Rotate -130 1 0 0
WorldBegin
LightSource "distantlight" 1 "intensity" [1.1] "from" [-3 1.5 1.1] "to" [0 0 0]
Displacement "wave" "Km" [0.08] "frequency" [5] "decay" [2]
)";

/// A twisted bilinear sheet at (u, v), as text "x y z".
std::string SheetPoint(double u, double v) {
    const glm::dvec3 c[4] = {{-1, -1, 0}, {1, -1, 0.3}, {-1.1, 1, -0.2}, {0.9, 1.2, 0.4}};
    const glm::dvec3 p = c[0] * (1 - u) * (1 - v) + c[1] * u * (1 - v) + c[2] * (1 - u) * v + c[3] * u * v;
    std::ostringstream out;
    out.precision(17);
    out << p.x << ' ' << p.y << ' ' << p.z << ' ';
    return out.str();
}

/// The sheet's points at u = i / (nu - 1), v = j / (nv - 1), u fastest, as a RIB array.
std::string SheetPoints(int nu, int nv) {
    std::string text = "\"P\" [";
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) text += SheetPoint(double(i) / (nu - 1), double(j) / (nv - 1));
    return text + "]\n";
}

/// How two renders of one surface differ: pixels hit by one only, pixels hit by both whose points
/// lie farther apart than the two hits' certified errors allow, and pixels whose RGBA or st
/// differ by more than 0.01.
struct ImageDifference {
    int coverage = 0, beyondError = 0, differing = 0;
};

ImageDifference Compare(const image::ImageBuffer& a, const image::ImageBuffer& b) {
    REQUIRE(a.rgba.size() == b.rgba.size());
    ImageDifference out;
    auto P = [](const image::ImageBuffer& im, size_t i) {
        return glm::dvec3(Channel(im, "P.X")[i], Channel(im, "P.Y")[i], Channel(im, "P.Z")[i]);
    };
    for (size_t i = 0; i < a.rgba.size() / 4; ++i) {
        double d = 0;
        for (int c = 0; c < 4; ++c) d = std::max(d, double(std::fabs(a.rgba[4 * i + c] - b.rgba[4 * i + c])));
        for (const char* channel : {"st.s", "st.t"})
            d = std::max(d, double(std::fabs(Channel(a, channel)[i] - Channel(b, channel)[i])));
        out.differing += d > 0.01;
        const bool hitA = a.rgba[4 * i + 3] == 1, hitB = b.rgba[4 * i + 3] == 1;
        out.coverage += hitA != hitB;
        // float AOVs: a little slack for their rounding.
        if (hitA && hitB)
            out.beyondError += glm::length(P(a, i) - P(b, i)) > Channel(a, "err")[i] + Channel(b, "err")[i] + 1e-5;
    }
    return out;
}

}  // namespace

TEST_CASE("render: bezier patches and patch meshes on a bilinear sheet render as the bilinear patch",
          "[renderer][render][bicubic]") {
    test::TempDir dir;
    const std::string camera = kSheetCamera;
    const image::ImageBuffer reference = Render(dir, camera + "Patch \"bilinear\" " + SheetPoints(2, 2) + "WorldEnd\n");
    CHECK(Covered(reference) > 48 * 36 / 3);
    // P = c00 + c10 u + c01 v + c11 u v in the power basis, whose "points" are the coefficients of
    // [u^3 u^2 u 1] x [v^3 v^2 v 1]: u^a v^b at index 4 (3 - b) + (3 - a).
    const glm::dvec3 c[4] = {{-1, -1, 0}, {1, -1, 0.3}, {-1.1, 1, -0.2}, {0.9, 1.2, 0.4}};
    glm::dvec3 coeff[16] = {};
    coeff[15] = c[0], coeff[14] = c[1] - c[0], coeff[11] = c[2] - c[0], coeff[10] = c[0] - c[1] - c[2] + c[3];
    std::ostringstream power;
    power.precision(17);
    for (const glm::dvec3& x : coeff) power << x.x << ' ' << x.y << ' ' << x.z << ' ';
    const std::pair<const char*, std::string> variants[] = {
        {"a bezier patch", "Patch \"bicubic\" " + SheetPoints(4, 4)},
        // 2 x 1 patches: the shader sees the mesh's (u,v), so the ripples match across the seam.
        {"a bezier patch mesh", "PatchMesh \"bicubic\" 7 \"nonperiodic\" 4 \"nonperiodic\" " + SheetPoints(7, 4)},
        {"a bilinear patch mesh", "PatchMesh \"bilinear\" 3 \"nonperiodic\" 4 \"nonperiodic\" " + SheetPoints(3, 4)},
        {"a power-basis patch", "Basis \"power\" 4 \"power\" 4\nPatch \"bicubic\" \"P\" [" + power.str() + "]\n"},
    };
    for (const auto& [name, geometry] : variants) {
        INFO(name);
        const image::ImageBuffer image = Render(dir, camera + geometry + "WorldEnd\n");
        const ImageDifference diff = Compare(reference, image);
        INFO(diff.coverage << " pixels hit by one render only, " << diff.beyondError
                           << " hit farther apart than their certified errors, " << diff.differing
                           << " differ by more than 0.01");
        if (std::string(name).find("mesh") == std::string::npos) {
            // One patch over the same (u,v): the same regions, the same hits, up to rounding.
            CHECK(diff.differing <= 2);
            CHECK(diff.coverage == 0);
        } else {
            // A mesh's patches are subdivided on their own, so the final regions and the hits in
            // them differ, within the hits' certified errors; a ray that grazes a crest or an edge
            // within its tolerance may count as a hit in one render only.
            CHECK(diff.coverage <= 48 * 36 / 100);
            CHECK(diff.beyondError <= 2);
            CHECK(diff.differing <= 48 * 36 / 20);
        }
    }
}

TEST_CASE("render: scenes/wavy_sheet.rib, a displaced bicubic patch mesh, renders", "[renderer][render][bicubic]") {
    std::ifstream file(test::SourceDir() + "/scenes/wavy_sheet.rib");
    std::stringstream text;
    text << file.rdbuf();
    affray::diag::Report error;
    std::optional<SceneDesc> desc = ParseRib(text.str(), test::SourceDir() + "/scenes/wavy_sheet.rib", &error);
    INFO(error);
    REQUIRE(desc);
    REQUIRE(desc->primitives.size() == 12);  // 4 x 3 b-spline patches
    desc->camera.xres = 48, desc->camera.yres = 36;
    desc->camera.xsamples = desc->camera.ysamples = 1;
    PreparedScene prepared;
    REQUIRE(Renderer(Options{.shaderPaths = {test::SourceDir() + "/shaders"}}).Prepare(*desc, &prepared, &error));
    // Each patch's BVH box holds its displaced points (the patches' corners included).
    test::Rng rng(5);
    const glm::dvec3 eye = Camera(prepared.desc.camera).Position();
    for (const Primitive& prim : prepared.primitives) {
        CHECK(prim.base().kind() == BaseSurface::Kind::BicubicPatch);
        const Box box = DisplacedBox(prim, eye, 8);  // as Renderer::Prepare makes it for 12 patches
        for (int k = 0; k < 40; ++k) {
            const double u = k < 4 ? (k & 1) : rng.uniform(0, 1), v = k < 4 ? (k >> 1) : rng.uniform(0, 1);
            const glm::dvec3 p = test::PointOnSurface(prim.bound(), prim.base(), u, v);
            INFO("patch line " << prim.line() << " at (" << u << ", " << v << ")");
            CHECK(glm::all(glm::lessThanEqual(box.lo, p)));
            CHECK(glm::all(glm::lessThanEqual(p, box.hi)));
        }
    }
    Options options;
    options.threads = 2;
    image::ImageBuffer image;
    RenderStats stats;
    Renderer(options).Render(prepared, &image, &stats);
    CHECK(Covered(image) > 48 * 36 / 4);
    for (float x : image.rgba) CHECK(std::isfinite(x));
    CHECK(stats.camera.depthLimitHits == 0);
}

TEST_CASE("render: Sides 1 culls by the geometric normal, whatever N says", "[renderer][render]") {
    // A closed cube seen from outside: with Sides 1 it must show exactly what Sides 2 shows (its
    // front faces), with or without outward vertex normals N (corner-averaged, so near the edges
    // N turns away from the viewer while the face itself faces it: 188 of its pixels differed
    // when N decided), displaced or not, and with either orientation when the winding follows it;
    // so must the same cube made of bilinear, bicubic and NuPatch faces, mirrored or not, and curved
    // closed surfaces of the other kinds. RenderMan culls by Ng (RI 3.2, 4.2).
    test::TempDir dir;
    const char* const camera = R"(Format 48 48 1
Projection "orthographic"
ScreenWindow -1.6 1.6 -1.6 1.6
Display "t.exr" "file" "rgba,Z"
Option "searchpath" "shader" ["mine:&"]
Translate 0 0 5
Rotate 35 1 0 0
Rotate 40 0 1 0
)";
    // Faces wound so that, in RenderMan's default left-handed orientation, Ng points out.
    const std::string faces = "[4 4 4 4 4 4] [0 2 3 1  4 5 7 6  0 1 5 4  2 6 7 3  0 4 6 2  1 3 7 5] ";
    const std::string points = "\"P\" [-1 -1 -1  1 -1 -1  -1 1 -1  1 1 -1  -1 -1 1  1 -1 1  -1 1 1  1 1 1] ";
    const std::string normals = "\"N\" [-1 -1 -1  1 -1 -1  -1 1 -1  1 1 -1  -1 -1 1  1 -1 1  -1 1 1  1 1 1]";
    dir.Write("mine/swell.sl", "displacement swell() { P += 0.05 * normalize(N); }");
    const auto depth = [&](const std::string& sides, const std::string& body) {
        const image::ImageBuffer image =
            Render(dir, std::string(camera) + "WorldBegin\n" + sides + "\n" + body + "\nWorldEnd\n");
        return Channel(image, "Z");
    };
    // The same cube as six patches of each kind: face loop (a, b, c, d) is the patch (a, b, d, c),
    // whose dPdu x dPdv points where the loop's winding normal does.
    const int loops[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    const auto corner = [](int i) { return glm::dvec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1); };
    const auto text = [](const glm::dvec3& p) {
        std::ostringstream out;
        out << p.x << " " << p.y << " " << p.z << " ";
        return out.str();
    };
    std::string bilinear, bicubic, nurbs;
    for (const auto& loop : loops) {
        const glm::dvec3 a = corner(loop[0]), b = corner(loop[1]), c = corner(loop[3]), d = corner(loop[2]);
        bilinear += "Patch \"bilinear\" \"P\" [" + text(a) + text(b) + text(c) + text(d) + "]\n";
        nurbs += "NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"P\" [" + text(a) + text(b) + text(c) + text(d) + "]\n";
        bicubic += "Patch \"bicubic\" \"P\" [";
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                const double u = i / 3.0, v = j / 3.0;
                bicubic += text((1 - v) * ((1 - u) * a + u * b) + v * ((1 - u) * c + u * d));
            }
        bicubic += "]\n";
    }
    struct Case {
        const char* name;
        std::string body;
        bool flat;  // flat faces: no pixel may differ
    };
    const Case cases[] = {
        {"winding only", "PointsPolygons " + faces + points, true},
        {"with N", "PointsPolygons " + faces + points + normals, true},
        // Lifted along N, whose N stays the interpolated one (no calculatenormal): still Ng decides.
        {"with N, displaced", "Displacement \"swell\"\nPointsPolygons " + faces + points + normals, false},
        {"with N, other orientation and winding",
         "Orientation \"rh\"\nPointsPolygons [4 4 4 4 4 4] [0 1 3 2  4 6 7 5  0 4 5 1  2 3 7 6  0 2 6 4  1 5 7 3] " +
             points + normals,
         true},
        // Curved surfaces of every other kind, whose Ng is dPdu x dPdv or their frame's normal
        // direction, flipped by the orientation.
        {"sphere", "Sphere 1.3 -1.3 1.3 360", false},
        {"sphere, mirrored (its normals stay out)", "Scale -1 1 1\nSphere 1.3 -1.3 1.3 360", false},
        {"torus", "Rotate 60 1 0 0\nTorus 1 0.4 0 360 360", false},
        {"subdivision cube", "SubdivisionMesh \"catmull-clark\" " + faces + points, false},
        {"bilinear patches", bilinear, true},
        {"bicubic patches", "Basis \"bezier\" 3 \"bezier\" 3\n" + bicubic, true},
        {"NuPatches", nurbs, true},
        {"bilinear patches, mirrored", "Scale 1 -1 1\n" + bilinear, true},
    };
    for (const auto& [name, body, flat] : cases) {
        INFO(name);
        const std::vector<float> one = depth("Sides 1", body), two = depth("Sides 2", body);
        REQUIRE(one.size() == two.size());
        int covered = 0, differ = 0;
        for (size_t i = 0; i < one.size(); ++i) {
            covered += two[i] < 1e29f;
            differ += one[i] != two[i];
        }
        CHECK(covered > 400);
        if (flat) {
            CHECK(differ == 0);
        } else {
            // Curved: at a grazing silhouette pixel the leaf's point may lie just past the
            // silhouette, where Ng turns away (4 pixels on the displaced cube; N deciding hid 194).
            CHECK(differ <= covered / 100);
        }
    }
    // Turned inside out, the same patches show the insides of the far faces wherever the cube is.
    for (const std::string& body : {"ReverseOrientation\n" + bilinear, "ReverseOrientation\n" + nurbs}) {
        const std::vector<float> one = depth("Sides 1", body), two = depth("Sides 2", body);
        int covered = 0, behind = 0;
        for (size_t i = 0; i < one.size(); ++i) {
            covered += two[i] < 1e29f;
            behind += two[i] < 1e29f && one[i] > two[i] && one[i] < 1e29f;
        }
        CHECK(behind > covered * 9 / 10);
    }
}

TEST_CASE("render: Imager \"background\" composites its colour under every pixel, before the exposure",
          "[renderer][render]") {
    // RI 3.2's standard imager: colour += (1 - alpha) * background, alpha = 1; Exposure after it.
    test::TempDir dir;
    const std::string scene = std::string(kCamera) +
                              "Imager \"background\" \"background\" [0.1 0.2 0.3]\nExposure 2 1\nWorldBegin\n"
                              "Patch \"bilinear\" \"P\" [-1 -1 1  0 -1 1  -1 1 1  0 1 1]\nWorldEnd\n";
    const image::ImageBuffer image = Render(dir, scene);
    int background = 0, covered = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            CHECK(Alpha(image, x, y) == 1.0f);
            const float* rgba = &image.rgba[(size_t(y) * image.width + x) * 4];
            if (Channel(image, "Z")[size_t(y) * image.width + x] < 1e29f) {
                ++covered;
                continue;
            }
            ++background;
            CHECK(rgba[0] == Approx(0.2).epsilon(1e-3));
            CHECK(rgba[1] == Approx(0.4).epsilon(1e-3));
            CHECK(rgba[2] == Approx(0.6).epsilon(1e-3));
        }
    CHECK(background == 32);
    CHECK(covered == 32);
}

TEST_CASE("render: Atmosphere \"fog\" and \"depthcue\" mix what camera rays see towards their background",
          "[renderer][render]") {
    // RI 3.2's standard volume shaders on a constant red surface (Ci = Oi Cs): fog d = 1 -
    // exp(-length(I) / distance), depth cue d = (depth(P) - mindistance) / (maxdistance -
    // mindistance) clamped, depth(P) from the near (0) to the far (1) clipping plane; Ci = mix(Ci,
    // background, d), Oi = mix(Oi, 1, d). The left half at camera depth 4, the right at 6; the
    // atmosphere is an attribute, so the last row's patch, declared after "null", has none.
    test::TempDir dir;
    const auto scene = [](const std::string& atmosphere) {
        return std::string(kCamera) +
               "Clipping 1 9\nWorldBegin\nSurface \"constant\"\nColor [1 0 0]\nOpacity [0.5 0.5 0.5]\n" + atmosphere +
               "\nPatch \"bilinear\" \"P\" [-1 -0.75 1  0 -0.75 1  -1 1 1  0 1 1]\n"
               "Patch \"bilinear\" \"P\" [0 -0.75 -1  1 -0.75 -1  0 1 -1  1 1 -1]\n"
               "Atmosphere \"null\"\nPatch \"bilinear\" \"P\" [-1 -1 1  1 -1 1  -1 -0.75 1  1 -0.75 1]\nWorldEnd\n";
    };
    const glm::dvec3 red(1, 0, 0), blue(0, 0, 1);
    struct Case {
        std::string atmosphere;
        double nearD, farD;  // d at depth 4 and 6
    };
    const Case cases[] = {
        {"Atmosphere \"fog\" \"distance\" [2] \"background\" [0 0 1]", 1 - std::exp(-2.0), 1 - std::exp(-3.0)},
        {"Atmosphere \"depthcue\" \"mindistance\" [0.125] \"maxdistance\" [0.625] \"background\" [0 0 1]", 0.5, 1.0},
    };
    for (const Case& c : cases) {
        INFO(c.atmosphere);
        const image::ImageBuffer image = Render(dir, scene(c.atmosphere));
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                const float* rgba = &image.rgba[(size_t(y) * image.width + x) * 4];
                // Row 7 (y up: the bottom) is the patch without atmosphere.
                const double d = y == 7 ? 0.0 : x < 4 ? c.nearD : c.farD;
                const glm::dvec3 ci = glm::mix(0.5 * red, blue, d);
                const double oi = 0.5 + 0.5 * d;
                INFO("pixel " << x << " " << y);
                CHECK(rgba[0] == Approx(ci.x).margin(1e-6));
                CHECK(rgba[1] == Approx(ci.y).margin(1e-6));
                CHECK(rgba[2] == Approx(ci.z).margin(1e-6));
                CHECK(rgba[3] == Approx(oi).margin(1e-6));
            }
    }
}

TEST_CASE("render: Points render as the spheres they stand for", "[renderer][render]") {
    // Two points, one coloured, against the same spheres written as Sphere requests: the same image.
    test::TempDir dir;
    const std::string world = std::string(kCamera) + "WorldBegin\nLightSource \"distantlight\" 1\n";
    const image::ImageBuffer points = Render(
        dir, world + "Points \"P\" [-0.5 0 0  0.5 0.25 0] \"width\" [0.8 0.5] \"Cs\" [1 1 1  1 0 0]\nWorldEnd\n");
    const image::ImageBuffer spheres =
        Render(dir, world +
                        "TransformBegin\nTranslate -0.5 0 0\nSphere 0.4 -0.4 0.4 360\nTransformEnd\n"
                        "Translate 0.5 0.25 0\nColor [1 0 0]\nSphere 0.25 -0.25 0.25 360\nWorldEnd\n");
    CHECK(Covered(points) > 10);
    CHECK(points.rgba == spheres.rgba);
}

TEST_CASE("render: a mesh is one description whose faces share its arrays and programs, at about 200 bytes each",
          "[renderer][render][mesh]") {
    // A 40 x 40 grid of quads with vertex normals, displaced: 1,600 primitives.
    const int n = 40;
    std::ostringstream rib;
    rib << kCamera << "WorldBegin\nDisplacement \"dented\" \"Km\" [0.02]\nPointsPolygons [";
    for (int i = 0; i < n * n; ++i) rib << " 4";
    rib << "] [";
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int v = j * (n + 1) + i;
            rib << ' ' << v << ' ' << v + 1 << ' ' << v + n + 2 << ' ' << v + n + 1;
        }
    rib << "] \"P\" [";
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) rib << ' ' << -1 + 2.0 * i / n << ' ' << -1 + 2.0 * j / n << " 0";
    rib << "] \"N\" [";
    for (int k = 0; k < (n + 1) * (n + 1); ++k) rib << " 0 0.3 1";
    rib << "]\nWorldEnd\n";
    test::TempDir dir;
    PreparedScene prepared;
    const image::ImageBuffer image = Render(dir, rib.str(), &prepared);
    REQUIRE(prepared.primitives.size() == size_t(n * n));
    const Primitive& first = prepared.primitives[0];
    REQUIRE(first.base().kind() == BaseSurface::Kind::MeshPiece);
    // One description for the whole mesh, its faces its elements.
    REQUIRE(prepared.desc.primitives.size() == 1);
    CHECK(prepared.desc.primitives[0].elements == uint32_t(n * n));
    for (const Primitive& prim : prepared.primitives) {
        CHECK(prim.desc == first.desc);
        CHECK(prim.base().pieceRef().mesh == first.base().pieceRef().mesh);
        CHECK(prim.programs == first.programs);
    }
    CHECK(prepared.programs.size() == 1);
    // A piece gathered from the shared arrays is the piece the mesh's split makes.
    const MeshPiece piece = prepared.primitives[n + 1].base().piece();
    CHECK(piece.face == n + 1);
    CHECK(!piece.triangle);
    CHECK(piece.hasNormals);
    test::RequireVec(piece.P[0], {-1 + 2.0 / n, -1 + 2.0 / n, 0});
    test::RequireVec(piece.P[3], {-1 + 4.0 / n, -1 + 4.0 / n, 0});
    test::RequireVec(piece.N[2], {0, 0.3, 1});
    // By structure, with two threads' slots: the primitive (24) and its slots (16), its piece
    // of the mesh's arrays (P and N 24 each, a little more here with (n+1)^2 points; the face
    // corners' indices 16; the piece 24), its share of the BVH (28 in a leaf, 32 per node, about
    // 1.3 nodes per face at this size, 1.05 at a million). Measured 200.1 (a million: 190).
    const double perFace = double(SceneBytes(prepared, 2)) / double(n * n);
    INFO(perFace << " bytes per face");
    CHECK(perFace > 150);  // counts what is there: the arrays and the primitive alone are 136
    CHECK(perFace < 205);
    CHECK(Covered(image) == 64);
}

TEST_CASE("render: the hit kept depends on neither the BVH's shape nor the primitives' order",
          "[renderer][render][bvh]") {
    // Issue 32: two rippled grids of 6 x 6 faces, red and blue, the blue 0.004 above the red:
    // their hits lie well within the tolerance of each other (some 0.02 here), on faces that the
    // BVH offers in an order its shape decides (before, the one met second was kept where its
    // range reached the first's hit). The same image, to the bit, from a SAH and a median BVH,
    // and with the grids given in the other order (other primitive indices, another tree): where
    // a red and a blue region have the same range along the ray (bounded by the x and y sides of
    // their bounds, which are the same), the tie is broken by the hits, not by the indices.
    test::TempDir dir;
    const int n = 6;
    auto grid = [&](const char* color, double z) {
        std::ostringstream out;
        out.precision(17);
        out << "AttributeBegin\nColor [" << color << "]\nSurface \"matte\"\n"
            << "Displacement \"wave\" \"Km\" [0.05] \"frequency\" [3]\nTranslate 0 0 " << z << "\nPointsPolygons [";
        for (int f = 0; f < n * n; ++f) out << " 4";
        out << "] [";
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const int a = y * (n + 1) + x;
                out << ' ' << a << ' ' << a + 1 << ' ' << a + n + 2 << ' ' << a + n + 1;
            }
        out << "]\n \"P\" [";
        for (int y = 0; y <= n; ++y)
            for (int x = 0; x <= n; ++x) out << ' ' << -1 + 2.0 * x / n << ' ' << -1 + 2.0 * y / n << " 0";
        out << "]\nAttributeEnd\n";
        return out.str();
    };
    const std::string head = R"(Format 40 32 1
Projection "perspective" "fov" [40]
Display "t.exr" "file" "rgba,Z"
Translate 0 0 3.2
Rotate -130 1 0 0
WorldBegin
LightSource "ambientlight" 1 "intensity" [0.2]
LightSource "distantlight" 2 "from" [1 1 3] "to" [0 0 0]
)";
    const std::string red = grid("0.9 0.1 0.1", 0), blue = grid("0.1 0.1 0.9", 0.004);
    PreparedScene sah, median, swapped;
    const image::ImageBuffer a = Render(dir, head + red + blue + "WorldEnd\n", &sah);
    const image::ImageBuffer b = Render(dir, head + red + blue + "WorldEnd\n", &median, Bvh::Split::kMedian);
    const image::ImageBuffer c = Render(dir, head + blue + red + "WorldEnd\n", &swapped);
    // The trees differ, and both grids are seen (the nearer, blue, mostly).
    REQUIRE(sah.primitives.size() == size_t(2 * n * n));
    CHECK_FALSE(*sah.bvh == *median.bvh);
    int reds = 0, blues = 0;
    for (size_t p = 0; p < a.rgba.size(); p += 4) {
        reds += a.rgba[p] > 2 * a.rgba[p + 2];
        blues += a.rgba[p + 2] > 2 * a.rgba[p];
    }
    CHECK(reds > 10);
    CHECK(blues > 300);
    CHECK(a.rgba == b.rgba);
    CHECK(a.rgba == c.rgba);
    CHECK(Channel(a, "Z") == Channel(b, "Z"));
    CHECK(Channel(a, "Z") == Channel(c, "Z"));
}
