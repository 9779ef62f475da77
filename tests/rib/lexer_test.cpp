// tests/rib/lexer_test.cpp: the RIB tokenizer (rib/lexer.cpp), its binary encoding (RI Spec 3.2,
// Appendix C.2): each encoding of numbers, strings, float arrays and defined requests and
// strings, written by a small encoder here, reads as the same scene as its ASCII text; mixed with
// ASCII; and every malformed encoding (a value cut short, a request or string never defined, a
// reserved byte) is an error at its place. (ASCII tokens and their errors are tested through
// whole requests in rib_test.cpp and the rib_lex_* golden cases.)
#include <catch2/catch.hpp>

#include <cstring>
#include <string>

#include "rib/lexer.h"
#include "rib/rib.h"
#include "tests/rib/rib_test_util.h"

using namespace affray;

namespace {

std::string Byte(unsigned b) { return std::string(1, static_cast<char>(b)); }

/// n bytes of v, big-endian.
std::string BigEndian(uint64_t v, int n) {
    std::string out;
    for (int i = n - 1; i >= 0; --i) out += Byte((v >> (8 * i)) & 0xff);
    return out;
}

std::string Float(float f) {
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    return Byte(0244) + BigEndian(bits, 4);
}

std::string Double(double d) {
    uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    return Byte(0245) + BigEndian(bits, 8);
}

/// A string: short (0220 + length) up to 15 bytes, else 0240 with a one-byte length.
std::string String(const std::string& s) {
    return s.size() < 16 ? Byte(0220 + unsigned(s.size())) + s : Byte(0240) + BigEndian(s.size(), 1) + s;
}

std::string FloatArray(std::initializer_list<float> values) {
    std::string out = Byte(0310) + BigEndian(values.size(), 1);
    for (float f : values) {
        uint32_t bits;
        std::memcpy(&bits, &f, sizeof bits);
        out += BigEndian(bits, 4);
    }
    return out;
}

std::string DefineRequest(unsigned code, const std::string& name) { return Byte(0314) + Byte(code) + String(name); }
std::string Request(unsigned code) { return Byte(0246) + Byte(code); }

/// The value of one binary number token, read as Translate's x.
double NumberOf(const std::string& encoded) {
    const renderer::SceneDesc s = test::ParseWorld("Translate " + encoded + " 0 0\nSphere 1 -1 1 360", nullptr);
    REQUIRE(s.primitives.size() == 1);
    return s.primitives[0].attr().objectToWorld[3][0];
}

}  // namespace

TEST_CASE("rib binary: every number encoding", "[rib][binary]") {
    // 0200 + 4d + w: w + 1 bytes, big-endian, d of them after the point; signed with an integer part.
    CHECK(NumberOf(Byte(0200) + Byte(0x05)) == 5);
    CHECK(NumberOf(Byte(0200) + Byte(0xfb)) == -5);
    CHECK(NumberOf(Byte(0201) + BigEndian(0x1234, 2)) == 0x1234);
    CHECK(NumberOf(Byte(0202) + BigEndian(0x010000, 3)) == 65536);
    CHECK(NumberOf(Byte(0203) + BigEndian(0xfffffffe, 4)) == -2);
    CHECK(NumberOf(Byte(0204) + Byte(0x80)) == 0.5);                // .B: unsigned
    CHECK(NumberOf(Byte(0205) + Byte(0xff) + Byte(0x80)) == -0.5);  // B.B: -1 + 0.5
    CHECK(NumberOf(Byte(0206) + BigEndian(0x0102, 2) + Byte(0x40)) == 258.25);
    CHECK(NumberOf(Byte(0211) + BigEndian(0xc000, 2)) == 0.75);      // .BB
    CHECK(NumberOf(Byte(0213) + BigEndian(0x00024000, 4)) == 2.25);  // BB.BB
    CHECK(NumberOf(Byte(0216) + BigEndian(0x400000, 3)) == 0.25);    // .BBB
    CHECK(NumberOf(Byte(0217) + BigEndian(0xfe800000, 4)) == -1.5);  // B.BBB
    CHECK(NumberOf(Float(-3.25f)) == -3.25);
    CHECK(NumberOf(Double(0.1)) == 0.1);
}

TEST_CASE("rib binary: a binary scene reads as its ASCII text", "[rib][binary]") {
    const std::string ascii =
        "Surface \"matte\" \"Kd\" [0.75]\n"
        "Translate 1 2 3\n"
        "Sphere 1.5 -1 1 360\n"
        "Polygon \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]\n"
        "AttributeBegin ReverseOrientation\nColor [0.25 0.5 1]\nDisk 0 2 180\nAttributeEnd\n";
    // The same requests: names defined once and then named by code, a string token defined and
    // interpolated, numbers in several encodings, float arrays; ASCII and binary mixed.
    const std::string binary =
        DefineRequest(1, "Surface") + DefineRequest(2, "Sphere") + Byte(0315) + Byte(7) + String("Kd") + Request(1) +
        String("matte") + Byte(0317) + Byte(7) + FloatArray({0.75f}) + "\n" +  //
        "Translate " + Byte(0200) + Byte(1) + Float(2) + Double(3) + "\n" +    //
        Request(2) + Byte(0205) + Byte(1) + Byte(0x80) + Byte(0200) + Byte(0xff) + "1 " + Double(360) + "\n" +
        "Polygon " + String("P") + FloatArray({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}) + "\n" +
        // A name of more than 15 bytes: the long string form (0240, a one-byte length).
        DefineRequest(3, "AttributeBegin") + Request(3) + DefineRequest(5, "ReverseOrientation") + Request(5) +
        "\nColor" + FloatArray({0.25f, 0.5f, 1}) + "\n" + Byte(0314) + Byte(4) + "\"Disk\"" + Request(4) +
        FloatArray({0, 2, 180}) + "\nAttributeEnd\n";
    diag::Report report;
    const renderer::SceneDesc a = test::ParseWorld(ascii), b = test::ParseWorld(binary, &report);
    CHECK(report.all().empty());
    REQUIRE(b.primitives.size() == 3);
    CHECK(renderer::ToString(a) == renderer::ToString(b));
    INFO(renderer::ToString(a) << "\n---\n" << renderer::ToString(b));
}

TEST_CASE("rib binary: malformed encodings are errors at their place", "[rib][binary]") {
    const auto error = [](const std::string& body) { return test::WorldError(body); };
    // (A value cut short at the end of the file: nothing may follow it.)
    const auto cut = [](const std::string& body) { return test::FirstError("WorldBegin\n" + body); };
    CHECK(cut("Translate 1 2 " + Byte(0203) + Byte(0)) ==
          "t.rib:2: error: binary RIB ends inside the value that starts here");
    CHECK(cut("Translate 1 2 " + Byte(0244) + Byte(0x3f)) ==
          "t.rib:2: error: binary RIB ends inside the value that starts here");
    CHECK(cut("Polygon \"P\" " + Byte(0310) + Byte(12) + BigEndian(0, 4)) ==
          "t.rib:2: error: binary RIB ends inside the value that starts here");
    CHECK(cut("Surface " + Byte(0240) + Byte(40) + "matte") ==
          "t.rib:2: error: binary RIB ends inside the value that starts here");
    CHECK(error(Request(9) + "1 -1 1 360") == "t.rib:2: error: binary RIB request code 9 was never defined");
    CHECK(error("Surface " + Byte(0320) + BigEndian(300, 2)) ==
          "t.rib:2: error: binary RIB string token 300 was never defined");
    CHECK(error("Sphere 1 -1 1 " + Byte(0247)) == "t.rib:2: error: unexpected byte 0xa7 (reserved in binary RIB)");
    CHECK(error("Sphere 1 -1 1 " + Byte(0377)) == "t.rib:2: error: unexpected byte 0xff (reserved in binary RIB)");
    CHECK(error("Sphere 1 -1 1 " + Byte(0210) + Byte(1)) == "t.rib:2: error: invalid binary RIB number code byte 0x88");
    CHECK(error("Sphere 1 -1 1 " + Float(std::numeric_limits<float>::quiet_NaN())) ==
          "t.rib:2: error: invalid binary RIB number: NaN and infinity are not allowed");
    CHECK(error("Sphere " + FloatArray({1, -1, std::numeric_limits<float>::infinity(), 360})) ==
          "t.rib:2: error: invalid number in a binary RIB array: NaN and infinity are not allowed");
    CHECK(error(DefineRequest(1, "3D") + Request(1)) ==
          "t.rib:2: error: binary RIB defines request code 1 as \"3D\", which is no request name");
    // A byte inside a binary value is never read as ASCII: a newline or '#' there is data.
    CHECK(NumberOf(Byte(0200) + Byte('\n')) == 10);
    CHECK(NumberOf(Byte(0200) + Byte('#')) == '#');
}

TEST_CASE("rib ascii numbers: correctly rounded, underflow to zero, overflow an error", "[rib][lexer]") {
    using rib::RibLexer;
    using rib::RibToken;
    auto number = [](const std::string& text) {
        RibLexer lexer(text);
        const RibToken t = lexer.Next();
        REQUIRE(t.kind == RibToken::Kind::Number);
        return t.number;
    };
    // Correctly rounded to the nearest double (a parse through long double may round twice).
    CHECK(number("0.1") == 0.1);
    CHECK(number("+2.5e3") == 2500.0);
    CHECK(number("-7") == -7.0);
    CHECK(number("1.7976931348623157e308") == 1.7976931348623157e308);
    CHECK(number("9007199254740993") == 9007199254740992.0);  // 2^53 + 1: ties to even
    CHECK(number("2.2250738585072011e-308") == 2.2250738585072011e-308);
    // Below double's range: zero (or a subnormal), as RenderMan renderers read it.
    CHECK(number("1e-400") == 0.0);
    CHECK(number("4e-320") == 4e-320);
    for (const char* bad : {"1e400", "-2e308"}) {
        RibLexer lexer(bad);
        const RibToken t = lexer.Next();
        CHECK(t.kind == RibToken::Kind::Error);
        CHECK(t.text.find("out of range") != std::string::npos);
    }
}
