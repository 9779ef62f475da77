// tests/renderer/facing_test.cpp: which side of a primitive the renderer shows (RI Spec 3.2 section
// 4.2, Orientation and Sides), through the RIB reader and the whole renderer, for every kind of
// primitive and every combination of its winding (or parameter direction), Orientation or
// ReverseOrientation, the handedness of the current coordinate system (a mirroring Scale before
// or after the orientation request; a mirroring camera), N given or not, displaced or not, and
// Sides 1 against Sides 2.
//
// The expected side is the spec's rule, simulated here (Handedness) independently of rib/: a
// primitive's normal is dPdu x dPdv (a polygon's, its winding's) in object space, carried to the
// world as a normal, and turned inside out where the current orientation differs from the
// handedness of the current coordinate system. With Sides 1 a surface shows only where that
// geometric normal faces the viewer, whatever the vertex normals N say, displaced or not.
//
// Each TEST_CASE renders the combinations of one family of primitives as a grid of small cells
// (one per combination and Sides) in one image, so that the file runs in a few seconds. To add a
// primitive, add a Shape to its family's list.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "compiler/compile.h"
#include "tests/renderer/render_coverage.h"
#include "vm/bytecode_file.h"

using namespace affray;

namespace {

/// The orientation request of a cell, if any.
enum class Orient { None, Outside, Inside, LeftHanded, RightHanded, Reverse };
constexpr Orient kOrients[] = {Orient::None,       Orient::Outside,     Orient::Inside,
                               Orient::LeftHanded, Orient::RightHanded, Orient::Reverse};

std::string RibOf(Orient o) {
    switch (o) {
        case Orient::None: return "";
        case Orient::Outside: return "Orientation \"outside\"";
        case Orient::Inside: return "Orientation \"inside\"";
        case Orient::LeftHanded: return "Orientation \"lh\"";
        case Orient::RightHanded: return "Orientation \"rh\"";
        case Orient::Reverse: return "ReverseOrientation";
    }
    return "";
}

/// Where a cell mirrors its coordinate system: across x before the orientation request (the
/// handedness that Orientation "lh" and "rh" compare with is then right), or across z, the view
/// axis, after it (it must flip the current orientation with the coordinate system, so that a
/// mirrored solid keeps its outside, and it turns the side of a flat surface the camera sees).
enum class Mirror { None, XBefore, ZAfter };
constexpr Mirror kMirrors[] = {Mirror::None, Mirror::XBefore, Mirror::ZAfter};

/// Vertex normals "N", where the primitive takes them: none, the unreversed primitive's normal
/// direction, or its opposite (the rule must ignore both).
enum class Normals { None, Along, Against };

/// The combinations of one primitive, N aside: reversed or not, orientation, mirror, displaced
/// or not.
constexpr int kPerShape = 2 * std::size(kOrients) * std::size(kMirrors) * 2;

/// RI 3.2 section 4.2 by the letter: the current orientation starts as the handedness of the
/// initial coordinate system (camera space, left-handed) and flips whenever the handedness of the
/// current coordinate system flips; Orientation and ReverseOrientation set it; a primitive is
/// turned inside out where the two differ.
struct Handedness {
    bool systemLeft = true, orientationLeft = true;

    void Mirrored() {
        systemLeft = !systemLeft;
        orientationLeft = !orientationLeft;
    }
    void Apply(Orient o) {
        switch (o) {
            case Orient::None: break;
            case Orient::Outside: orientationLeft = systemLeft; break;
            case Orient::Inside: orientationLeft = !systemLeft; break;
            case Orient::LeftHanded: orientationLeft = true; break;
            case Orient::RightHanded: orientationLeft = false; break;
            case Orient::Reverse: orientationLeft = !orientationLeft; break;
        }
    }
    bool InsideOutP() const { return systemLeft != orientationLeft; }
};

/// One primitive of a family, centred on its object space's origin within a radius of 1.5 (the
/// camera looks along +z). Unreversed, its normal faces the camera (-z) if it is open, or points
/// out if it is closed. Closed means that every camera ray that meets it enters it (a solid, or a
/// tube seen across its axis): with Sides 1 it shows what Sides 2 shows where its normal points
/// out, and its far inside where the normal points in.
struct Shape {
    const char* name;
    bool closed;
    bool takesNormals;  // "N" is a factor (polygons; bilinear patches, which RI lets have N)
    /// The RIB of the primitive, reversed (the other winding or parameter direction) or not.
    std::function<std::string(bool reversed, Normals normals)> rib;
};

/// One combination of the factors, Sides aside.
struct Combination {
    const Shape* shape;
    bool reversed;
    Orient orient;
    Mirror mirror;
    Normals normals;
    bool displaced;
};

std::string NameOf(const Combination& c, bool cameraMirrored) {
    std::string name = std::string(c.shape->name) + (c.reversed ? ", reversed" : ", not reversed");
    name += c.orient == Orient::None ? ", no orientation request" : ", " + RibOf(c.orient);
    if (c.mirror == Mirror::XBefore) name += ", Scale -1 1 1 before it";
    if (c.mirror == Mirror::ZAfter) name += ", Scale 1 1 -1 after it";
    if (cameraMirrored) name += ", camera mirrored (Scale -1 1 1)";
    if (c.shape->takesNormals)
        name += c.normals == Normals::None ? ", no N" : (c.normals == Normals::Along ? ", N along" : ", N against");
    if (c.displaced) name += ", displaced";
    return name;
}

// The grid: cells of 6 x 6 pixels of 0.625 (world units), so that every cell's centre and every
// pixel's centre are exact; a primitive within a radius of 1.5 leaves a margin of 0.375.
constexpr int kCellPixels = 6;
constexpr double kPixel = 0.625, kCellSize = kCellPixels * kPixel;
constexpr int kColumns = 24;
// The pixel whose centre is (0.3125, -0.3125) from its cell's centre (with the camera mirrored,
// the pixel seeing the same point): a point of every primitive off its seams.
constexpr int kCentre = kCellPixels / 2;
// A displacement along N, smooth and gentle (its slope keeps every facing as it was), which
// vanishes where s or t is 0 or 1: the faces of a polygon cube, each lifted along its own normal,
// stay joined at their edges. Given as bytecode: Renderer::Prepare compiles a source shader once per
// object space, which is once per cell here (milliseconds each), and only loads bytecode.
const char* const kBumpShader =
    "displacement bump(float Km = 0.1) {\n"
    "  P += Km * sin(3.14159265 * s) * sin(3.14159265 * t) * normalize(N);\n"
    "}\n";
// Hits are certified to 0.1 pixel (0.0625 in the world), five times finer than the default, so
// that silhouettes are sharp and the depths of one surface in two cells agree within kSameDepth;
// a far inside is farther than kFarther.
constexpr double kTolerance = 0.1, kSameDepth = 0.15, kFarther = 0.3;
// Pixels of a cell that may differ between Sides 1 and Sides 2 where they should not: one whose
// centre lies within the tolerance of a silhouette (the same primitive, translated, may be hit or
// missed there). None does in these cells today.
constexpr int kSilhouettePixels = 1;

/// Renders `rib` as test::RenderRib does (one sample at each pixel's centre, shaders from `dir`),
/// certifying hits to kTolerance pixels.
image::ImageBuffer Render(const test::TempDir& dir, const std::string& rib) {
    return test::RenderRib(dir, rib, nullptr, kTolerance);
}

/// The rendered grid.
class Grid {
  public:
    Grid(image::ImageBuffer image, bool mirrored) : m_image(std::move(image)), m_mirrored(mirrored) {}
    /// Pixel (x, y) of `cell` (x to the world's +x, y down), mirrored back if the camera is.
    size_t Index(int cell, int x, int y) const {
        const int column = cell % kColumns, row = cell / kColumns;
        const int px =
            m_mirrored ? (kColumns - 1 - column) * kCellPixels + (kCellPixels - 1 - x) : column * kCellPixels + x;
        return size_t(row * kCellPixels + y) * size_t(m_image.width) + size_t(px);
    }
    bool CoveredP(int cell, int x, int y) const { return m_image.rgba[4 * Index(cell, x, y) + 3] > 0.5f; }
    double Depth(int cell, int x, int y) const { return test::DepthOf(m_image)[Index(cell, x, y)]; }
    /// The depths of two cells side by side, pixel by pixel ("-" where nothing shows), for messages.
    std::string Text(int a, int b) const {
        std::string text = "depths (Sides 2 | Sides 1):\n";
        for (int y = 0; y < kCellPixels; ++y) {
            for (int cell : {a, b}) {
                for (int x = 0; x < kCellPixels; ++x) {
                    char value[16];
                    std::snprintf(value, sizeof value, " %5.2f", Depth(cell, x, y));
                    text += CoveredP(cell, x, y) ? value : "     -";
                }
                text += cell == a ? "  |" : "\n";
            }
        }
        return text;
    }

  private:
    image::ImageBuffer m_image;
    bool m_mirrored;
};

/// Renders every combination of `shapes` twice (Sides 2, then Sides 1, in adjacent cells), and
/// checks each against the rule. Returns the number of combinations checked.
int CheckFacing(const std::vector<Shape>& shapes, bool cameraMirrored) {
    std::vector<Combination> combinations;
    for (const Shape& shape : shapes)
        for (bool reversed : {false, true})
            for (Orient orient : kOrients)
                for (Mirror mirror : kMirrors)
                    for (Normals normals : {Normals::None, Normals::Along, Normals::Against}) {
                        if (!shape.takesNormals && normals != Normals::None) continue;
                        for (bool displaced : {false, true})
                            combinations.push_back({&shape, reversed, orient, mirror, normals, displaced});
                    }
    test::TempDir dir;
    const compiler::CompileResult bump = compiler::CompileSource("bump.sl", kBumpShader);
    REQUIRE(bump.ok());
    affray::diag::Report error;
    REQUIRE(vm::WriteBytecodeFile(
        dir.Path("bump.afb"), {"bump", "bump.sl", 0, bump.shader->genericBound, bump.shader->genericShade}, &error));

    // The camera at z = -5 looking along +z: world space is left-handed, as camera space is,
    // unless the camera transform mirrors it.
    const int cells = 2 * static_cast<int>(combinations.size());
    const int width = kColumns * kCellPixels, height = (cells + kColumns - 1) / kColumns * kCellPixels;
    const double halfWidth = 0.5 * kPixel * width, halfHeight = 0.5 * kPixel * height;
    std::ostringstream rib;
    rib << "Format " << width << ' ' << height << " 1\nProjection \"orthographic\"\n"
        << "ScreenWindow " << -halfWidth << ' ' << halfWidth << ' ' << -halfHeight << ' ' << halfHeight << '\n'
        << "Display \"facing.exr\" \"file\" \"rgba,Z\"\n"
        << (cameraMirrored ? "Scale -1 1 1\n" : "") << "Translate 0 0 5\nWorldBegin\n";
    for (int cell = 0; cell < cells; ++cell) {
        const Combination& c = combinations[size_t(cell / 2)];
        rib << "AttributeBegin\nTranslate " << -halfWidth + (cell % kColumns + 0.5) * kCellSize << ' '
            << halfHeight - (cell / kColumns + 0.5) * kCellSize << " 0\n"
            << (c.mirror == Mirror::XBefore ? "Scale -1 1 1\n" : "") << RibOf(c.orient) << '\n'
            << (c.mirror == Mirror::ZAfter ? "Scale 1 1 -1\n" : "") << (cell % 2 ? "Sides 1\n" : "Sides 2\n")
            << (c.displaced ? "Displacement \"bump\"\n" : "") << c.shape->rib(c.reversed, c.normals)
            << "AttributeEnd\n";
    }
    rib << "WorldEnd\n";
    const Grid grid(Render(dir, rib.str()), cameraMirrored);

    for (size_t i = 0; i < combinations.size(); ++i) {
        const Combination& c = combinations[i];
        const int two = 2 * static_cast<int>(i), one = two + 1;
        INFO(NameOf(c, cameraMirrored));
        INFO(grid.Text(two, one));
        if (!grid.CoveredP(two, kCentre, kCentre)) {
            FAIL_CHECK("with Sides 2 the primitive does not show at the cell's centre");
            continue;
        }
        Handedness h;
        if (cameraMirrored) h.Mirrored();
        if (c.mirror == Mirror::XBefore) h.Mirrored();
        h.Apply(c.orient);
        if (c.mirror == Mirror::ZAfter) h.Mirrored();
        // The normal is the unreversed primitive's unless it is reversed or turned inside out
        // (not both); carried to the world as a normal, it is turned only by a mirror across z.
        const bool kept = c.reversed == h.InsideOutP();
        const bool facing = kept != (c.mirror == Mirror::ZAfter);
        if (c.shape->closed ? kept : facing) {
            INFO("expected: Sides 1 shows what Sides 2 shows");
            int differ = 0;
            for (int y = 0; y < kCellPixels; ++y)
                for (int x = 0; x < kCellPixels; ++x) {
                    const bool covered = grid.CoveredP(two, x, y);
                    differ += covered != grid.CoveredP(one, x, y) ||
                              (covered && std::fabs(grid.Depth(one, x, y) - grid.Depth(two, x, y)) > kSameDepth);
                }
            CHECK(grid.CoveredP(one, kCentre, kCentre));
            CHECK(differ <= kSilhouettePixels);
        } else if (c.shape->closed) {
            INFO("expected: Sides 1 shows the far inside, behind the near side Sides 2 shows");
            CHECK(grid.CoveredP(one, kCentre, kCentre));
            CHECK(grid.Depth(one, kCentre, kCentre) > grid.Depth(two, kCentre, kCentre) + kFarther);
        } else {
            INFO("expected: Sides 1 shows nothing");
            int covered = 0;
            for (int y = 0; y < kCellPixels; ++y)
                for (int x = 0; x < kCellPixels; ++x) covered += grid.CoveredP(one, x, y);
            CHECK(covered == 0);
        }
    }
    return static_cast<int>(combinations.size());
}

/// The numbers, each followed by a space, with enough digits.
std::string Numbers(std::initializer_list<double> numbers) {
    std::ostringstream out;
    out.precision(17);
    for (double x : numbers) out << x << ' ';
    return out.str();
}
std::string Point(const glm::dvec3& p) { return Numbers({p.x, p.y, p.z}); }

/// The nu x nv control points (u fastest) of a sheet over [-1.2, 1.2]^2 at heights z(x, y), u
/// along +y and v along +x (dPdu x dPdv towards -z, the camera), or reversed: u along +x, v +y.
std::string Sheet(int nu, int nv, bool reversed, double (*z)(double, double)) {
    std::string out;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const double a = -1.2 + 2.4 * i / (nu - 1), b = -1.2 + 2.4 * j / (nv - 1);
            const double x = reversed ? a : b, y = reversed ? b : a;
            out += Point({x, y, z(x, y)});
        }
    return out;
}

/// A bulge towards the camera, 0 on the sheet's border.
double Bulge(double x, double y) { return -0.3 * (1 - x * x / 1.44) * (1 - y * y / 1.44); }
/// A plane, as z = 0: a flat bilinear patch has one normal, folded into its programs.
double Flat(double, double) { return 0; }
/// A saddle: a bilinear patch's twist.
double Twist(double x, double y) { return 0.1 * x * y; }

/// `count` copies of the normal `along`, or its opposite, as "N"; nothing for Normals::None.
std::string NormalsRib(Normals normals, int count, const glm::dvec3& along) {
    if (normals == Normals::None) return "";
    std::string out = " \"N\" [";
    for (int i = 0; i < count; ++i) out += Point(normals == Normals::Along ? along : -along);
    return out + "]";
}

/// Polygon loops, each reversed if `reversed`, as the RIB's vertex counts and vertices arrays.
std::string Loops(std::vector<std::vector<int>> loops, bool reversed) {
    std::string sizes = "[", vertices = "[";
    for (std::vector<int>& loop : loops) {
        if (reversed) std::reverse(loop.begin(), loop.end());
        sizes += std::to_string(loop.size()) + ' ';
        for (int v : loop) vertices += std::to_string(v) + ' ';
    }
    return sizes + "] " + vertices + "] ";
}

// A cube's faces, wound so that their normals point out, over its corners (x, y, z from the bits
// of the index), turned so that three faces show, the cells' centre pixel on the nearest.
const std::vector<std::vector<int>> kCubeLoops = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
const char* const kCubeTurn = "Rotate 25 1 0 0\nRotate 30 0 1 0\n";
glm::dvec3 CubeCorner(int i) { return glm::dvec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1); }
std::string CubePoints(double half) {
    std::string out = "\"P\" [";
    for (int i = 0; i < 8; ++i) out += Point(half * CubeCorner(i));
    return out + "]";
}
// Seen across its axis: z turned to the world's -y.
const char* const kAcross = "Rotate 90 1 0 0\n";

std::vector<Shape> PolygonShapes() {
    return {
        {"PointsPolygons quad", false, true,
         [](bool reversed, Normals normals) {
             // Clockwise seen from the camera (-z): Newell's normal, the winding's, is -z.
             return "PointsPolygons " + Loops({{0, 1, 2, 3}}, reversed) + "\"P\" [" + Point({-1.2, -1.2, 0}) +
                    Point({-1.2, 1.2, 0}) + Point({1.2, 1.2, 0}) + Point({1.2, -1.2, 0}) + "]" +
                    NormalsRib(normals, 4, {0, 0, -1}) + "\n";
         }},
        {"concave Polygon", false, true,
         [](bool reversed, Normals normals) {
             // A notched pentagon, which the mesh splits into triangles.
             std::vector<glm::dvec3> p = {{-1.2, -1.2, 0}, {-1.2, 1.2, 0}, {0, 0.6, 0}, {1.2, 1.2, 0}, {1.2, -1.2, 0}};
             if (reversed) std::reverse(p.begin(), p.end());
             std::string rib = "Polygon \"P\" [";
             for (const glm::dvec3& q : p) rib += Point(q);
             return rib + "]" + NormalsRib(normals, 5, {0, 0, -1}) + "\n";
         }},
        {"PointsGeneralPolygons with a hole", false, true,
         [](bool reversed, Normals normals) {
             // The quad with a square hole in a corner, away from the cell's centre.
             std::string rib = "PointsGeneralPolygons [2] " + Loops({{0, 1, 2, 3}, {4, 5, 6, 7}}, reversed) + "\"P\" [";
             for (const glm::dvec3& p : {glm::dvec3(-1.2, -1.2, 0), glm::dvec3(-1.2, 1.2, 0), glm::dvec3(1.2, 1.2, 0),
                                         glm::dvec3(1.2, -1.2, 0), glm::dvec3(-0.9, 0.5, 0), glm::dvec3(-0.9, 0.9, 0),
                                         glm::dvec3(-0.5, 0.9, 0), glm::dvec3(-0.5, 0.5, 0)})
                 rib += Point(p);
             return rib + "]" + NormalsRib(normals, 8, {0, 0, -1}) + "\n";
         }},
        {"PointsPolygons cube", true, true,
         [](bool reversed, Normals normals) {
             std::string rib =
                 std::string(kCubeTurn) + "PointsPolygons " + Loops(kCubeLoops, reversed) + CubePoints(0.9);
             if (normals != Normals::None) {
                 // Corner normals, out (along) or in.
                 rib += " \"N\" [";
                 for (int i = 0; i < 8; ++i) rib += Point(CubeCorner(i) * (normals == Normals::Along ? 1.0 : -1.0));
                 rib += "]";
             }
             return rib + "\n";
         }},
    };
}

std::vector<Shape> QuadricShapes() {
    // Reversed (RI 3.2 section 5.4: "the sense of a quadric can be reversed by giving negative
    // parameters"): a negative thetamax, which reverses dPdu (the disk's normal points to +z when
    // thetamax is positive), or v run the other way, which reverses dPdv. Each is seen across its
    // axis, unless said otherwise.
    auto quadric = [](const char* name, bool closed, const std::string& request, const std::string& reversed) {
        return Shape{name, closed, false, [=](bool r, Normals) { return (r ? reversed : request) + "\n"; }};
    };
    auto swept = [&](const char* name, bool closed, const std::string& request) {
        return quadric(name, closed, request + " 360", request + " -360");
    };
    const std::string across = kAcross;
    return {
        swept("Sphere", true, across + "Sphere 1.3 -1.3 1.3"),
        quadric("Cylinder", true, across + "Cylinder 1.1 -1.2 1.2 360", across + "Cylinder 1.1 1.2 -1.2 360"),
        // The apex at the top: the cell's centre pixel sees the wide part.
        swept("Cone", true, "Rotate -90 1 0 0\nTranslate 0 0 -1.2\nCone 2.4 1.2"),
        swept("Disk, face on", false, "Rotate 180 0 1 0\nDisk 0 1.3"),
        quadric("Torus", true, across + "Torus 0.85 0.45 0 360 360", across + "Torus 0.85 0.45 360 0 360"),
        quadric("Hyperboloid", true, across + "Hyperboloid 1 -0.6 -1.2  1 0.6 1.2 360",
                across + "Hyperboloid 1 0.6 1.2  1 -0.6 -1.2 360"),
        swept("Paraboloid", true, across + "Translate 0 0 -0.8\nParaboloid 1.2 0.2 1.4"),
        // Near a pole, where dPdu vanishes.
        swept("Sphere, pole on", true, "Sphere 1.3 -1.3 1.3"),
        // Open at its base: from the apex side, the camera sees its outside.
        swept("Cone, apex on", false, "Rotate 180 0 1 0\nTranslate 0 0 -0.6\nCone 1.2 1.3"),
    };
}

}  // namespace

TEST_CASE("facing: polygon meshes show the side their winding and orientation face, whatever N says",
          "[renderer][facing]") {
    CHECK(CheckFacing(PolygonShapes(), false) == 4 * 3 * kPerShape);
}

TEST_CASE("facing: bilinear and bicubic patches and patch meshes show the side dPdu x dPdv and the orientation face",
          "[renderer][facing]") {
    const std::vector<Shape> shapes = {
        {"bilinear Patch", false, true,
         [](bool reversed, Normals normals) {
             // RI lets a bilinear patch have N (affray ignores it, with a warning).
             return "Patch \"bilinear\" \"P\" [" + Sheet(2, 2, reversed, Twist) + "]" +
                    NormalsRib(normals, 4, {0, 0, -1}) + "\n";
         }},
        {"flat bilinear Patch", false, false,
         [](bool reversed, Normals) { return "Patch \"bilinear\" \"P\" [" + Sheet(2, 2, reversed, Flat) + "]\n"; }},
        {"bicubic Patch", false, false,
         [](bool reversed, Normals) {
             return "Basis \"bezier\" 3 \"bezier\" 3\nPatch \"bicubic\" \"P\" [" + Sheet(4, 4, reversed, Bulge) + "]\n";
         }},
        {"bilinear PatchMesh", false, false,
         [](bool reversed, Normals) {
             return "PatchMesh \"bilinear\" 3 \"nonperiodic\" 3 \"nonperiodic\" \"P\" [" +
                    Sheet(3, 3, reversed, Twist) + "]\n";
         }},
        {"bicubic b-spline PatchMesh", false, false,
         [](bool reversed, Normals) {
             return "Basis \"b-spline\" 1 \"b-spline\" 1\n"
                    "PatchMesh \"bicubic\" 5 \"nonperiodic\" 5 \"nonperiodic\" \"P\" [" +
                    Sheet(5, 5, reversed, Bulge) + "]\n";
         }},
        {"periodic bicubic PatchMesh tube", true, false,
         [](bool reversed, Normals) {
             // Around z (u, counter-clockwise) and along it (v, from -1 to 1): dPdu x dPdv points
             // out.
             std::string points;
             for (int j = 0; j < 5; ++j)
                 for (int i = 0; i < 8; ++i) {
                     const double theta = 2 * M_PI * i / 8, z = reversed ? 2 - j : j - 2;
                     points += Point({1.3 * std::cos(theta), 1.3 * std::sin(theta), z});
                 }
             return std::string(kAcross) +
                    "Basis \"b-spline\" 1 \"b-spline\" 1\n"
                    "PatchMesh \"bicubic\" 8 \"periodic\" 5 \"nonperiodic\" \"P\" [" +
                    points + "]\n";
         }},
    };
    CHECK(CheckFacing(shapes, false) == (3 + 5) * kPerShape);
}

TEST_CASE("facing: NuPatches show the side dPdu x dPdv and the orientation face", "[renderer][facing]") {
    const std::vector<Shape> shapes = {
        {"cubic NuPatch", false, false,
         [](bool reversed, Normals) {
             return "NuPatch 5 4 [0 0 0 0 0.5 1 1 1 1] 0 1 4 4 [0 0 0 0 1 1 1 1] 0 1 \"P\" [" +
                    Sheet(5, 4, reversed, Bulge) + "]\n";
         }},
        {"rational NuPatch cylinder", true, false,
         [](bool reversed, Normals) {
             // The rational quadratic circle around z (u), along z (v): dPdu x dPdv points out.
             const double corner = std::sqrt(0.5);
             const double circle[9][3] = {{1, 0, 1},       {1, 1, corner},  {0, 1, 1},
                                          {-1, 1, corner}, {-1, 0, 1},      {-1, -1, corner},
                                          {0, -1, 1},      {1, -1, corner}, {1, 0, 1}};
             std::string points;
             for (int j = 0; j < 2; ++j)
                 for (const auto& c : circle) {
                     const double w = c[2], z = (j == 0) != reversed ? -1.2 : 1.2;
                     points += Numbers({1.2 * c[0] * w, 1.2 * c[1] * w, z * w, w});
                 }
             return std::string(kAcross) + "NuPatch 9 3 [0 0 0 1 1 2 2 3 3 4 4 4] 0 4 2 2 [0 0 1 1] 0 1 \"Pw\" [" +
                    points + "]\n";
         }},
    };
    CHECK(CheckFacing(shapes, false) == 2 * kPerShape);
}

TEST_CASE("facing: subdivision meshes show the side their winding and orientation face", "[renderer][facing]") {
    const std::vector<Shape> shapes = {
        {"open SubdivisionMesh", false, false,
         [](bool reversed, Normals) {
             // 3 x 3 faces over 4 x 4 points, wound clockwise seen from the camera, the boundary
             // interpolated.
             std::vector<std::vector<int>> loops;
             for (int j = 0; j < 3; ++j)
                 for (int i = 0; i < 3; ++i)
                     loops.push_back({4 * j + i, 4 * (j + 1) + i, 4 * (j + 1) + i + 1, 4 * j + i + 1});
             std::string points;
             for (int j = 0; j < 4; ++j)
                 for (int i = 0; i < 4; ++i) {
                     const double x = -1.2 + 0.8 * i, y = -1.2 + 0.8 * j;
                     points += Point({x, y, Bulge(x, y)});
                 }
             return "SubdivisionMesh \"catmull-clark\" " + Loops(loops, reversed) +
                    "[\"interpolateboundary\"] [0 0] [] [] \"P\" [" + points + "]\n";
         }},
        {"SubdivisionMesh cube", true, false,
         [](bool reversed, Normals) {
             return std::string(kCubeTurn) + "SubdivisionMesh \"catmull-clark\" " + Loops(kCubeLoops, reversed) +
                    CubePoints(1.4) + "\n";
         }},
    };
    CHECK(CheckFacing(shapes, false) == 2 * kPerShape);
}

TEST_CASE("facing: quadrics show their outside, or their inside with a negative sweep or turned inside out",
          "[renderer][facing]") {
    CHECK(CheckFacing(QuadricShapes(), false) == 9 * kPerShape);
}

TEST_CASE("facing: under a mirroring camera, world space is right-handed: Orientation \"lh\" turns what it shows",
          "[renderer][facing]") {
    const std::vector<Shape> polygons = PolygonShapes(), quadrics = QuadricShapes();
    const std::vector<Shape> shapes = {polygons[0], polygons[3], quadrics[0], quadrics[3]};
    CHECK(CheckFacing(shapes, true) == (3 + 3 + 1 + 1) * kPerShape);
}

TEST_CASE("facing: a surface seen from behind hides nothing behind it, however close", "[renderer][facing]") {
    // Two one-sided squares facing opposite ways, 0.02 apart along the view (a tenth of the
    // tolerance, about a pixel here): the one nearer the camera seen from behind, the farther one
    // from the front. The search goes on past the first only: the second shows, in every pixel.
    // (It used to go on past the first's certified error for every primitive, and saw neither.)
    test::TempDir dir;
    const std::string camera =
        "Format 16 12 1\nProjection \"perspective\" \"fov\" [40]\nWorldBegin\n"
        "Sides 1\nSurface \"constant\"\n";
    auto square = [](double z, bool reversed) {
        std::ostringstream out;
        out << "AttributeBegin\n"
            << (reversed ? "ReverseOrientation\n" : "") << "Patch \"bilinear\" \"P\" [-9 -9 " << z << "  9 -9 " << z
            << "  -9 9 " << z << "  9 9 " << z << "]\nAttributeEnd\n";
        return out.str();
    };
    auto covered = [](const image::ImageBuffer& image) {
        int n = 0;
        for (size_t p = 0; p * 4 < image.rgba.size(); ++p) n += image.rgba[4 * p + 3] > 0.5f;
        return n;
    };
    // Which of the two orientations the camera sees from the front.
    const bool frontReversed = covered(test::RenderRib(dir, camera + square(5, true) + "WorldEnd\n")) > 0;
    REQUIRE(covered(test::RenderRib(dir, camera + square(5, !frontReversed) + "WorldEnd\n")) == 0);
    const image::ImageBuffer both =
        test::RenderRib(dir, camera + square(5, !frontReversed) + square(5.02, frontReversed) + "WorldEnd\n");
    CHECK(covered(both) == 16 * 12);
}
