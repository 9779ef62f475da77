// tests/rib/conditional_test.cpp: conditional RIB (rib/conditional.cpp): IfBegin, ElseIf, Else
// and IfEnd take the branch their expression of options and attributes selects, drop the others
// as they are read, and report a malformed expression or structure at its place.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "rib/rib.h"
#include "tests/rib/rib_test_util.h"

using namespace affray;
using namespace affray::test;

namespace {

// The colors of the primitives of the world `world`, after the header `header`, in order: each
// branch of a test makes a patch of its own color.
std::vector<double> Reds(const std::string& header, const std::string& world) {
    diag::Report report;
    std::optional<renderer::SceneDesc> scene = rib::ParseRib(header + InWorld(world), "t.rib", &report);
    INFO(report);
    REQUIRE(scene);
    CHECK(report.empty());
    std::vector<double> reds;
    for (const renderer::PrimitiveDesc& p : scene->primitives) reds.push_back(p.color.r);
    return reds;
}

// A patch of color (red, 0, 0).
std::string Patch(int red) {
    return "Color " + std::to_string(red) + " 0 0\nPatch \"bilinear\" \"P\" [0 0 0  1 0 0  0 1 0  1 1 0]\n";
}

// IfBegin "expression" with a patch of color 1 if it holds, else one of color 2.
std::string Choose(const std::string& expression) {
    return "IfBegin \"" + expression + "\"\n" + Patch(1) + "Else\n" + Patch(2) + "IfEnd\n";
}

}  // namespace

TEST_CASE("rib conditionals: the branch the options and attributes select is read", "[rib]") {
    const std::string header = "Option \"user\" \"string pass_class\" [\"Final\"] \"int frame\" [3]\n";
    // RenderMan for Maya's pass tests.
    CHECK(Reds(header, Choose("!defined(user:pass_class) || $user:pass_class == 'Final'")) == std::vector<double>{1});
    CHECK(Reds(header, Choose("$user:pass_class == 'Shadow'")) == std::vector<double>{2});
    CHECK(Reds(header, Choose("${user:pass_class} != \\\"Shadow\\\"")) == std::vector<double>{1});
    CHECK(Reds(header, Choose("defined(user:nothing)")) == std::vector<double>{2});
    // Arithmetic, comparisons, precedence, concat.
    CHECK(Reds(header, Choose("$user:frame * 2 - 1 == 5 && !($user:frame < 3)")) == std::vector<double>{1});
    CHECK(Reds(header, Choose("1 + 2 * 3 == 7 && 2 >= 2 && 1 <= 1 && 3 > 2 && -1 < 0")) == std::vector<double>{1});
    CHECK(Reds(header, Choose("concat('a', $user:frame, 'b') == 'a3b'")) == std::vector<double>{1});
    CHECK(Reds(header, Choose("0 || ''")) == std::vector<double>{2});
    CHECK(Reds(header, Choose("'x'")) == std::vector<double>{1});
    // An attribute of the name wins over the option, within its block.
    CHECK(Reds(header, "AttributeBegin\nAttribute \"user\" \"int frame\" [4]\n" + Choose("$user:frame == 4") +
                           "AttributeEnd\n" + Choose("$user:frame == 4")) == std::vector<double>{1, 2});

    // ElseIf: the first branch that holds; the others are not evaluated (they may test what is
    // not defined), and nested conditionals in a branch not taken are dropped whole.
    const std::string chain = "IfBegin \"$user:frame == 1\"\n" + Patch(1) + "ElseIf \"$user:frame == 3\"\n" + Patch(2) +
                              "ElseIf \"$user:undefined == 3\"\n" + Patch(3) + "Else\n" + Patch(4) + "IfEnd\n";
    CHECK(Reds(header, chain) == std::vector<double>{2});
    CHECK(Reds(header, "IfBegin \"0\"\nIfBegin \"$user:undefined\"\n" + Patch(1) + "Else\n" + Patch(2) +
                           "IfEnd\nElse\n" + Patch(3) + "IfEnd\n" + Patch(4)) == std::vector<double>{3, 4});
    CHECK(Reds(header, "IfBegin \"1\"\n" + Choose("0") + "IfEnd\n") == std::vector<double>{2});

    // A branch not taken drops what it holds before an object records it, and its blocks.
    CHECK(Reds(header, "ObjectBegin 1\nIfBegin \"0\"\nAttributeBegin\n" + Patch(1) + "Else\n" + Patch(2) +
                           "IfEnd\nObjectEnd\nObjectInstance 1\n") == std::vector<double>{2});
    // Options are a frame's: FrameEnd restores them.
    diag::Report report;
    std::optional<std::vector<renderer::SceneDesc>> frames = rib::ParseRibFrames(
        "FrameBegin 1\nOption \"user\" \"float shadow\" [1]\n" + InWorld(Choose("defined(user:shadow)")) +
            "FrameEnd\nFrameBegin 2\n" + InWorld(Choose("defined(user:shadow)")) + "FrameEnd\n",
        "t.rib", &report);
    REQUIRE(frames);
    REQUIRE(frames->size() == 2);
    CHECK((*frames)[0].primitives.at(0).color.r == 1);
    CHECK((*frames)[1].primitives.at(0).color.r == 2);
}

TEST_CASE("rib conditionals: malformed expressions and structure are errors at their place", "[rib]") {
    const std::string header = "Option \"user\" \"string pass\" [\"a\"] \"float[2] range\" [0 1]\n";
    auto error = [&](const std::string& world) { return FirstError(header + InWorld(world)); };
    auto expression = [&](const std::string& text) { return error("IfBegin \"" + text + "\"\nIfEnd\n"); };
    const std::string at = "t.rib:3: error: 'IfBegin' expression \"";
    CHECK(expression("$user:nothing == 1") ==
          at + "$user:nothing == 1\": no option or attribute 'user:nothing' is defined (test it with "
               "defined(user:nothing))");
    CHECK(expression("$user:range == 1") == at + "$user:range == 1\": 'user:range' holds 2 values, not one");
    CHECK(expression("$user:pass == 1") == at + "$user:pass == 1\": '==' compares a number with a string");
    CHECK(expression("$user:pass =~ 'a.*'") == at + "$user:pass =~ 'a.*'\": the pattern match '=~' is not supported");
    CHECK(expression("(1 == 1") == at + "(1 == 1\": '(' has no matching ')'");
    CHECK(expression("1 ==") == at + "1 ==\": the expression ends too soon");
    CHECK(expression("1 1") == at + "1 1\": unexpected '1'");
    CHECK(expression("'a") == at + "'a\": unterminated string");
    CHECK(expression("pass == 'a'") == at + "pass == 'a'\": unknown word 'pass' (a variable is written $pass)");
    CHECK(expression("'a' + 'b'") == at + "'a' + 'b'\": '+' needs numbers (concat() joins strings)");
    CHECK(expression("defined($user:pass)") == at + "defined($user:pass)\": defined needs a name in parentheses");
    CHECK(expression("${user:pass") == at + "${user:pass\": '${' has no matching '}'");
    const std::string deep = std::string(100000, '(') + "1";
    CHECK(expression(deep) == at + deep + "\": the expression nests more than 200 deep");
    CHECK(expression(std::string(100000, '!') + "1").find("nests more than 200 deep") != std::string::npos);

    CHECK(error("IfBegin\nIfEnd\n") == "t.rib:3: error: 'IfBegin' expects one string (an expression)");
    CHECK(error("IfBegin \"1\"\nElseIf [\"1\"]\nIfEnd\n") ==
          "t.rib:4: error: 'ElseIf' expects one string (an expression)");
    CHECK(error("IfEnd\n") == "t.rib:3: error: 'IfEnd' without matching 'IfBegin'");
    CHECK(error("Else\n") == "t.rib:3: error: 'Else' without matching 'IfBegin'");
    CHECK(error("IfBegin \"1\"\nElse\nElseIf \"1\"\nIfEnd\n") ==
          "t.rib:5: error: 'ElseIf' after the 'Else' of the 'IfBegin' on line 3");
    CHECK(error("IfBegin \"1\"\nElse\nElse\nIfEnd\n") ==
          "t.rib:5: error: 'Else' after the 'Else' of the 'IfBegin' on line 3");
    CHECK(error("IfBegin \"1\"\nElse 1\nIfEnd\n") == "t.rib:4: error: 'Else' takes no arguments, found number 1");
    CHECK(FirstError("IfBegin \"1\"\nWorldBegin\nWorldEnd\n") == "t.rib:1: error: 'IfBegin' has no matching 'IfEnd'");
}
