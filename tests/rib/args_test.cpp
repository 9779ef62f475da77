// tests/rib/args_test.cpp: the argument checks every RIB request shares (rib/args.*), called
// directly on requests read from text: declarations ("[class] type[n]") parsed and refused with
// their reasons; the standard primitive variables' declarations; names split from their inline
// declarations; positional numbers bare, as one array or grouped, and each way of having too few
// or too many; a leading name string; token-value parameter lists with inline and Declare'd
// declarations, repeated names and every refusal; parameters of fixed counts; affine matrices.
// Each refusal is checked for its exact message and the line and column it points at. (What each
// request does with its arguments is tested through whole files in the other tests/rib/ files.)
#include <catch2/catch.hpp>

#include <string>

#include "rib/args.h"

using namespace affray;
using rib::RibDeclaration;

namespace {

/// The checks, made callable, and the message and place of the last refusal.
class Checks : public rib::RibArgChecks {
  public:
    using RibArgChecks::FormatNumber;
    using RibArgChecks::LeadingNumbers;
    using RibArgChecks::LeadingString;
    using RibArgChecks::Matrix;
    using RibArgChecks::NoArgs;
    using RibArgChecks::Numbers;
    using RibArgChecks::ParamList;
    using RibArgChecks::ParamNumbers;
    using RibArgChecks::ParamVector;

    void Declare(const std::string& name, const std::string& declaration) { m_declared[name] = declaration; }
    void UniformVaries(bool on) { m_uniformVaries = on; }
    /// "line:column: message" of the last refusal.
    std::string Error() const {
        return std::to_string(m_errorAt.line) + ":" + std::to_string(m_errorAt.column) + ": " + m_errorMessage;
    }
};

/// The one request of `text`, which must read.
rib::RibRequest Request(const std::string& text) {
    rib::RibRequestReader reader(text);
    rib::RibRequest r;
    std::string error;
    rib::RibPos at;
    REQUIRE(reader.Next(&r, &error, &at) == rib::RibRequestReader::Status::Ok);
    return r;
}

/// Why RibDeclaration::Parse refuses `text`, or "" if it takes it.
std::string DeclarationProblem(const std::string& text) {
    RibDeclaration d;
    std::string problem;
    return RibDeclaration::Parse(text, &d, &problem) ? "" : problem;
}

}  // namespace

TEST_CASE("rib args: declarations give their class, type, array size and component count", "[rib][args]") {
    struct Case {
        const char* text;
        const char* storage;
        const char* type;
        int arraySize, components;
        renderer::StorageClass storageClass;
        size_t uniformCount;
    };
    using renderer::StorageClass;
    const Case cases[] = {
        {"float", "", "float", 1, 1, StorageClass::Uniform, 1},
        {"uniform float", "uniform", "float", 1, 1, StorageClass::Uniform, 1},
        {"constant color", "constant", "color", 1, 3, StorageClass::Constant, 3},
        {"varying float[2]", "varying", "float", 2, 1, StorageClass::Varying, 2},
        {"  vertex   point ", "vertex", "point", 1, 3, StorageClass::Vertex, 3},
        {"facevarying normal", "facevarying", "normal", 1, 3, StorageClass::FaceVarying, 3},
        {"facevertex vector", "facevertex", "vector", 1, 3, StorageClass::FaceVarying, 3},
        {"vertex hpoint", "vertex", "hpoint", 1, 4, StorageClass::Vertex, 4},
        {"matrix [3]", "", "matrix", 3, 16, StorageClass::Uniform, 48},
        {"string[2]", "", "string", 2, 1, StorageClass::Uniform, 2},
        {"int", "", "int", 1, 1, StorageClass::Uniform, 1},
        {"integer", "", "integer", 1, 1, StorageClass::Uniform, 1},
        {"bool", "", "bool", 1, 1, StorageClass::Uniform, 1},
    };
    for (const Case& c : cases) {
        INFO(c.text);
        RibDeclaration d;
        std::string problem;
        REQUIRE(RibDeclaration::Parse(c.text, &d, &problem));
        CHECK(d.storage == c.storage);
        CHECK(d.type == c.type);
        CHECK(d.arraySize == c.arraySize);
        CHECK(d.components == c.components);
        CHECK(d.Storage() == c.storageClass);
        CHECK(d.UniformCount() == c.uniformCount);
    }
}

TEST_CASE("rib args: a declaration without a type, with words after it, or a bad array size is refused",
          "[rib][args]") {
    CHECK(DeclarationProblem("") == "declaration \"\" has no type");
    CHECK(DeclarationProblem("uniform") == "declaration \"uniform\" has no type");
    CHECK(DeclarationProblem("float Km") == "declaration \"float Km\" has words after its type");
    CHECK(DeclarationProblem("uniform float [2] x") == "declaration \"uniform float [2] x\" has words after its type");
    for (const char* bad : {"float[0]", "float[-1]", "float[]", "float[2", "float[x]", "float[2]]", "float[65537]"})
        CHECK(DeclarationProblem(bad) ==
              std::string("declaration \"") + bad + "\" needs a positive array size, as \"float[2]\"");
    CHECK(DeclarationProblem("float[65536]") == "");
    CHECK(DeclarationProblem("varying quaternion") ==
          "declaration \"varying quaternion\" has an unknown type 'quaternion' (expected float, integer, string, "
          "color, point, vector, normal, hpoint or matrix)");
    CHECK(DeclarationProblem("Float") != "");  // names are case-sensitive
    // A refused declaration leaves the output as it was.
    RibDeclaration d;
    d.type = "kept";
    std::string problem;
    CHECK_FALSE(RibDeclaration::Parse("float extra", &d, &problem));
    CHECK(d.type == "kept");
}

TEST_CASE("rib args: the standard primitive variables' declarations", "[rib][args]") {
    CHECK(rib::StandardDeclaration("P") == "vertex point");
    CHECK(rib::StandardDeclaration("Pw") == "vertex hpoint");
    CHECK(rib::StandardDeclaration("N") == "varying normal");
    CHECK(rib::StandardDeclaration("Np") == "uniform normal");
    CHECK(rib::StandardDeclaration("st") == "varying float[2]");
    CHECK(rib::StandardDeclaration("s") == "varying float");
    CHECK(rib::StandardDeclaration("t") == "varying float");
    CHECK(rib::StandardDeclaration("Cs") == "varying color");
    CHECK(rib::StandardDeclaration("Os") == "varying color");
    CHECK(rib::StandardDeclaration("Km") == "");
    CHECK(rib::StandardDeclaration("p") == "");
    // Each parses.
    for (const char* name : {"P", "Pw", "N", "Np", "st", "s", "t", "Cs", "Os"})
        CHECK(DeclarationProblem(rib::StandardDeclaration(name)) == "");
}

TEST_CASE("rib args: a name splits from the declaration before it", "[rib][args]") {
    auto split = [](const std::string& text, const char* blanks = " \t\n\r") {
        const rib::DeclaredName d = rib::SplitDeclaredName(text, blanks);
        return d.declaration + "|" + d.name;
    };
    CHECK(split("Km") == "|Km");
    CHECK(split("uniform float Km") == "uniform float|Km");
    CHECK(split("  color   Ci  ") == "color|Ci");
    CHECK(split("varying\tfloat[2]\nst\r") == "varying\tfloat[2]|st");
    CHECK(split("") == "|");
    CHECK(split(" \t\n") == "|");
    CHECK(split("float:x", ":") == "float|x");
    CHECK(split("float x", ":") == "|float x");  // a space is no blank here
}

TEST_CASE("rib args: no arguments", "[rib][args]") {
    Checks c;
    CHECK(c.NoArgs(Request("WorldBegin")));
    CHECK_FALSE(c.NoArgs(Request("WorldBegin\n  \"x\" 1")));
    CHECK(c.Error() == "2:3: 'WorldBegin' takes no arguments, found string \"x\"");
}

TEST_CASE("rib args: positional numbers bare, as one array or grouped, exactly as many as asked", "[rib][args]") {
    Checks c;
    for (const char* text : {"Translate 1 2 3", "Translate [1 2 3]", "Translate [1 2] 3", "Translate 1 [2] [3]"}) {
        INFO(text);
        double v[3] = {0, 0, 0};
        CHECK(c.Numbers(Request(text), 3, "dx dy dz", v));
        CHECK((v[0] == 1 && v[1] == 2 && v[2] == 3));
    }
    double v[3];
    CHECK_FALSE(c.Numbers(Request("Translate 1 2"), 3, "dx dy dz", v));
    CHECK(c.Error() == "1:1: 'Translate' expects 3 numbers (dx dy dz), got 2");
    CHECK_FALSE(c.Numbers(Request("  Translate 1 2 3 4"), 3, "dx dy dz", v));
    CHECK(c.Error() == "1:3: 'Translate' expects 3 numbers (dx dy dz), got number 4");
    CHECK_FALSE(c.Numbers(Request("Translate [1 2 3 4]"), 3, "dx dy dz", v));
    CHECK(c.Error() == "1:1: 'Translate' expects 3 numbers (dx dy dz), got array of 4 numbers");
    CHECK_FALSE(c.Numbers(Request("Translate 1 [2 3 4]"), 3, "dx dy dz", v));
    CHECK(c.Error() == "1:1: 'Translate' expects 3 numbers (dx dy dz), got array of 3 numbers");
    CHECK_FALSE(c.Numbers(Request("Translate 1 2 \"x\""), 3, "dx dy dz", v));
    CHECK(c.Error() == "1:1: 'Translate' expects 3 numbers (dx dy dz), got string \"x\"");
    CHECK_FALSE(c.Numbers(Request("Translate 1 2 3 \"x\" 1"), 3, "dx dy dz", v));
    CHECK(c.Error() == "1:1: 'Translate' expects 3 numbers (dx dy dz), got string \"x\"");
}

TEST_CASE("rib args: leading numbers may be followed by a parameter list", "[rib][args]") {
    Checks c;
    double v[4] = {0, 0, 0, 0};
    size_t next = 99;
    CHECK(c.LeadingNumbers(Request("Sphere 1 -1 1 360 \"Km\" 2"), 4, "radius zmin zmax thetamax", v, &next));
    CHECK(next == 4);
    CHECK((v[0] == 1 && v[1] == -1 && v[2] == 1 && v[3] == 360));
    CHECK(c.LeadingNumbers(Request("Sphere [1 -1 1 360]"), 4, "radius zmin zmax thetamax", v, &next));
    CHECK(next == 1);
    CHECK_FALSE(c.LeadingNumbers(Request("Sphere 1 -1 1 \"Km\" 2"), 4, "radius zmin zmax thetamax", v, &next));
    CHECK(c.Error() == "1:1: 'Sphere' expects 4 numbers (radius zmin zmax thetamax), got 3");
    CHECK_FALSE(c.LeadingNumbers(Request("Sphere 1 -1 [1 360 5]"), 4, "radius zmin zmax thetamax", v, &next));
    CHECK(c.Error() == "1:1: 'Sphere' expects 4 numbers (radius zmin zmax thetamax), got array of 3 numbers");
}

TEST_CASE("rib args: a leading name string", "[rib][args]") {
    Checks c;
    std::string name;
    CHECK(c.LeadingString(Request("Surface \"plastic\" \"Ks\" 1"), "a shader name", &name));
    CHECK(name == "plastic");
    CHECK_FALSE(c.LeadingString(Request("Surface 1"), "a shader name", &name));
    CHECK(c.Error() == "1:9: 'Surface' expects a shader name as its first argument, found number 1");
    CHECK_FALSE(c.LeadingString(Request("Surface [\"plastic\"]"), "a shader name", &name));
    CHECK(c.Error() == "1:9: 'Surface' expects a shader name as its first argument, found array of 1 string");
    CHECK_FALSE(c.LeadingString(Request("\n Surface"), "a shader name", &name));
    CHECK(c.Error() == "2:2: 'Surface' expects a shader name as its first argument");
    CHECK(name == "plastic");
}

TEST_CASE("rib args: parameter lists, with inline and Declare'd declarations", "[rib][args]") {
    Checks c;
    c.Declare("Kd", "uniform float");
    std::vector<rib::RibParam> params;
    const rib::RibRequest r = Request(
        "Surface \"s\" \"Km\" 1 \"uniform color tint\" [1 0.5 0] \"Kd\" [0.25]\n"
        "  \"string map\" \"a.tx\" \"Km\" [2] \"varying float h\" [1 2 3]");
    REQUIRE(c.ParamList(r, 1, &params));
    REQUIRE(params.size() == 5);
    CHECK(params[0].value.name == "Km");  // repeated: the later value, in the first one's place
    CHECK(params[0].value.declaration == "");
    CHECK(params[0].value.numbers == std::vector<double>{2});
    CHECK(params[0].at.line == 2);
    CHECK(params[0].at.column == 28);
    CHECK(params[1].value.name == "tint");
    CHECK(params[1].value.declaration == "uniform color");
    CHECK(params[1].value.numbers == std::vector<double>{1, 0.5, 0});
    CHECK(params[2].value.name == "Kd");
    CHECK(params[2].value.declaration == "uniform float");  // from Declare
    CHECK(params[3].value.name == "map");
    CHECK(params[3].value.strings == std::vector<std::string>{"a.tx"});
    CHECK(params[4].value.name == "h");  // varying: any whole number of values
    CHECK(params[4].value.numbers == std::vector<double>{1, 2, 3});
    // A list read into one that holds parameters replaces theirs by name and appends the others.
    std::vector<rib::RibParam> more = params;
    REQUIRE(c.ParamList(Request("Surface \"Kd\" 3 \"Ks\" 0.5"), 0, &more));
    REQUIRE(more.size() == 6);
    CHECK(more[2].value.numbers == std::vector<double>{3});
    CHECK(more[5].value.name == "Ks");
}

TEST_CASE("rib args: each way a parameter list is refused", "[rib][args]") {
    Checks c;
    c.Declare("Kd", "uniform float");
    auto refusal = [&](const std::string& text, bool checkDeclared = true) {
        std::vector<rib::RibParam> params;
        CHECK_FALSE(c.ParamList(Request(text), 0, &params, checkDeclared));
        return c.Error();
    };
    CHECK(refusal("Surface 1 2") == "1:9: 'Surface' expects a parameter name string, found number 1");
    CHECK(refusal("Surface [\"a\"] 2") == "1:9: 'Surface' expects a parameter name string, found array of 1 string");
    CHECK(refusal("Surface \" \" 2") == "1:9: 'Surface' has an empty parameter name");
    CHECK(refusal("Surface \"Km\" 1 \"Ks\"") == "1:16: 'Surface' parameter 'Ks' has no value");
    CHECK(refusal("Surface \"uniform float Km\" [1 2]") ==
          "1:28: 'Surface' parameter 'Km' is declared \"uniform float\" and expects 1 number, got 2");
    CHECK(refusal("Surface \"Kd\" [1 2]") ==
          "1:14: 'Surface' parameter 'Kd' is declared \"uniform float\" and expects 1 number, got 2");
    CHECK(refusal("Surface \"color c\" [1 2 3 4]") ==
          "1:19: 'Surface' parameter 'c' is declared \"color\" and expects 3 numbers, got 4");
    CHECK(refusal("Surface \"varying color c\" [1 2 3 4]") ==
          "1:27: 'Surface' parameter 'c' is declared \"varying color\" and expects a multiple of 3 numbers, got 4");
    CHECK(refusal("Surface \"string s\" 1") ==
          "1:20: 'Surface' parameter 's' is declared \"string\" and expects strings, got numbers");
    CHECK(refusal("Surface \"float f\" \"x\"") ==
          "1:19: 'Surface' parameter 'f' is declared \"float\" and expects numbers, got strings");
    CHECK(refusal("Surface \"string[2] s\" \"x\"") ==
          "1:23: 'Surface' parameter 's' is declared \"string[2]\" and expects 2 strings, got 1");
    CHECK(refusal("Surface \"quux Km\" 1") ==
          "1:9: 'Surface' parameter 'Km': declaration \"quux\" has an unknown type 'quux' (expected float, integer, "
          "string, color, point, vector, normal, hpoint or matrix)");
    // The declarations' checks can be left out (a shader affray does not have), not the shape's.
    std::vector<rib::RibParam> params;
    CHECK(c.ParamList(Request("Surface \"uniform point p\" 1 \"quux q\" 1"), 0, &params, false));
    CHECK(params.size() == 2);
    CHECK(refusal("Surface \"p\"", false) == "1:9: 'Surface' parameter 'p' has no value");
    // An empty value is neither strings nor numbers, and a varying class takes zero values.
    CHECK(c.ParamList(Request("Surface \"varying float h\" []"), 0, &params));
    // While a mesh reads its list, uniform values are one per face: any whole number.
    c.UniformVaries(true);
    CHECK(c.ParamList(Request("PointsPolygons \"uniform color c\" [1 2 3 4 5 6]"), 0, &params));
    CHECK(refusal("PointsPolygons \"uniform color c\" [1 2 3 4]") ==
          "1:34: 'PointsPolygons' parameter 'c' is declared \"uniform color\" and expects a multiple of 3 numbers, "
          "got 4");
    CHECK(refusal("PointsPolygons \"constant color c\" [1 2 3 4 5 6]") ==
          "1:35: 'PointsPolygons' parameter 'c' is declared \"constant color\" and expects 3 numbers, got 6");
}

TEST_CASE("rib args: parameters of a fixed number of values", "[rib][args]") {
    Checks c;
    std::vector<rib::RibParam> params;
    REQUIRE(c.ParamList(Request("LightSource \"x\" \"from\" [1 2 3] \"intensity\" 2 \"name\" \"n\""), 1, &params));
    REQUIRE(params.size() == 3);
    glm::dvec3 from;
    CHECK(c.ParamVector(params[0], "'LightSource \"x\"'", &from));
    CHECK(from == glm::dvec3(1, 2, 3));
    double intensity = 0;
    CHECK(c.ParamNumbers(params[1], "'LightSource \"x\"'", 1, &intensity));
    CHECK(intensity == 2);
    CHECK_FALSE(c.ParamVector(params[1], "'LightSource \"x\"'", &from));
    CHECK(c.Error() == "1:44: 'LightSource \"x\"' parameter 'intensity' expects 3 numbers, got 1");
    CHECK_FALSE(c.ParamNumbers(params[0], "'LightSource \"x\"'", 1, &intensity));
    CHECK(c.Error() == "1:24: 'LightSource \"x\"' parameter 'from' expects 1 number, got 3");
    CHECK_FALSE(c.ParamNumbers(params[2], "'LightSource \"x\"'", 1, &intensity));
    CHECK(c.Error() == "1:53: 'LightSource \"x\"' parameter 'name' expects 1 number, got a string");
    CHECK(intensity == 2);
}

TEST_CASE("rib args: matrices are affine, read for row vectors, divided by their w", "[rib][args]") {
    Checks c;
    glm::dmat4 m;
    REQUIRE(c.Matrix(Request("ConcatTransform [1 0 0 0  0 2 0 0  0 0 3 0  5 6 7 1]"), &m));
    // For column vectors: p' = M p, the translation in the last column.
    CHECK(m * glm::dvec4(1, 1, 1, 1) == glm::dvec4(6, 8, 10, 1));
    CHECK(m[3] == glm::dvec4(5, 6, 7, 1));
    REQUIRE(c.Matrix(Request("Transform 2 0 0 0  0 2 0 0  0 0 2 0  2 4 6 2"), &m));
    CHECK(m ==
          glm::dmat4(glm::dvec4(1, 0, 0, 0), glm::dvec4(0, 1, 0, 0), glm::dvec4(0, 0, 1, 0), glm::dvec4(1, 2, 3, 1)));
    const std::string projective =
        "1:1: 'Transform' matrix must be affine (last column 0 0 0 1); projective transforms are not supported yet";
    CHECK_FALSE(c.Matrix(Request("Transform [1 0 0 1  0 1 0 0  0 0 1 0  0 0 0 1]"), &m));
    CHECK(c.Error() == projective);
    CHECK_FALSE(c.Matrix(Request("Transform [1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 0]"), &m));
    CHECK(c.Error() == projective);
    CHECK_FALSE(c.Matrix(Request("Transform [1 0 0 0  0 1 0 0  0 0 1 0  0 0 0]"), &m));
    CHECK(c.Error() == "1:1: 'Transform' expects 16 numbers (a 4x4 matrix), got 15");
}

TEST_CASE("rib args: numbers in messages are the shortest %g", "[rib][args]") {
    CHECK(Checks::FormatNumber(3) == "3");
    CHECK(Checks::FormatNumber(0.5) == "0.5");
    CHECK(Checks::FormatNumber(-1.25e-7) == "-1.25e-07");
    CHECK(Checks::FormatNumber(1e21) == "1e+21");
    CHECK(Checks::FormatNumber(1.0 / 3) == "0.333333");
}
