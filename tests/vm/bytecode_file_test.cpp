// tests/vm/bytecode_file_test.cpp: the .afb format (vm/bytecode_file.*): round trips of every
// shader in shaders/, the exact error for each kind of bad file (wrong magic or version, every
// truncation, every single-byte flip, programs Verify rejects), a fuzz loop that must never crash
// (CI runs it under ASan and UBSan), and the atomic file writer.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "tests/test_util.h"
#include "tests/texture/texture_test_util.h"
#include "vm/bytecode_file.h"
#include "vm/verify.h"

using namespace affray;

namespace {

vm::BytecodeFile FileFor(const std::string& path) {
    compiler::CompileResult r = compiler::CompileFile(path);
    INFO(path << ":\n" << r.diagnostics);
    REQUIRE(r.ok());
    vm::BytecodeFile file;
    file.shaderName = r.shader->name;
    file.sourcePath = r.shader->sourcePath;
    file.sourceHash = vm::HashSource(r.shader->sourceText);
    file.bound = r.shader->genericBound;
    file.shade = r.shader->genericShade;
    return file;
}

const vm::BytecodeFile& Wave() {
    static const vm::BytecodeFile file = FileFor(test::SourceDir() + "/shaders/wave.sl");
    return file;
}
const std::string& WaveBytes() {
    static const std::string bytes = vm::SaveBytecode(Wave());
    return bytes;
}

uint64_t Bits(double x) { return std::bit_cast<uint64_t>(x); }

void RequireSameProgram(const vm::Program& a, const vm::Program& b) {
    CHECK(a.shaderName == b.shaderName);
    CHECK(a.sourcePath == b.sourcePath);
    CHECK(a.registerCount == b.registerCount);
    CHECK(a.globalRegisters == b.globalRegisters);
    REQUIRE(a.code.size() == b.code.size());
    for (size_t i = 0; i < a.code.size(); ++i) {
        INFO("instruction " << i);
        CHECK(a.code[i].op == b.code[i].op);
        CHECK(a.code[i].flags == b.code[i].flags);
        CHECK(a.code[i].a == b.code[i].a);
        CHECK(a.code[i].b == b.code[i].b);
        CHECK(a.code[i].c == b.code[i].c);
    }
    CHECK(a.lines == b.lines);
    REQUIRE(a.constants.size() == b.constants.size());
    for (size_t i = 0; i < a.constants.size(); ++i) CHECK(Bits(a.constants[i]) == Bits(b.constants[i]));
    REQUIRE(a.outputs.size() == b.outputs.size());
    for (size_t i = 0; i < a.outputs.size(); ++i) {
        CHECK(a.outputs[i].name == b.outputs[i].name);
        CHECK(a.outputs[i].size == b.outputs[i].size);
        CHECK(a.outputs[i].registers == b.outputs[i].registers);
    }
    REQUIRE(a.params.size() == b.params.size());
    for (size_t i = 0; i < a.params.size(); ++i) {
        const vm::ProgramParam &p = a.params[i], &q = b.params[i];
        CHECK(p.name == q.name);
        CHECK(p.type == q.type);
        CHECK(p.size == q.size);
        CHECK(p.firstRegister == q.firstRegister);
        REQUIRE(p.defaults.size() == q.defaults.size());
        for (size_t j = 0; j < p.defaults.size(); ++j) CHECK(Bits(p.defaults[j]) == Bits(q.defaults[j]));
    }
    REQUIRE(bool(a.textures) == bool(b.textures));
    if (!a.textures) return;
    REQUIRE(a.textures->size() == b.textures->size());
    for (size_t i = 0; i < a.textures->size(); ++i) {
        const vm::TextureSlot &x = (*a.textures)[i], &y = (*b.textures)[i];
        INFO("texture slot " << i);
        CHECK(x.path == y.path);
        CHECK(x.options.channel == y.options.channel);
        CHECK(x.options.swrap == y.options.swrap);
        CHECK(x.options.twrap == y.options.twrap);
        CHECK(x.options.filter == y.options.filter);
        CHECK(Bits(x.options.sblur) == Bits(y.options.sblur));
        CHECK(Bits(x.options.tblur) == Bits(y.options.tblur));
        CHECK(Bits(x.options.fill) == Bits(y.options.fill));
        CHECK(x.fillIfMissing == y.fillIfMissing);
        CHECK(x.dependsOn == y.dependsOn);
        CHECK(bool(x.map) == bool(y.map));
    }
}

/// The error LoadBytecode gives for `bytes`, or "<loaded>".
std::string LoadError(std::string_view bytes) {
    vm::BytecodeFile file;
    std::string error;
    return vm::LoadBytecode(bytes, &file, &error) ? "<loaded>" : error;
}

void PutU64(std::string* bytes, size_t offset, uint64_t x) {
    for (int i = 0; i < 8; ++i) (*bytes)[offset + i] = static_cast<char>(x >> (8 * i));
}

/// Rewrites the length, header check and checksum of `bytes` (magic and version left alone), so
/// that the parser itself is exercised on whatever the body holds.
void Reseal(std::string* bytes) {
    if (bytes->size() < 36) return;
    PutU64(bytes, 12, bytes->size());
    PutU64(bytes, 20, vm::HashSource(std::string_view(*bytes).substr(0, 20)));
    PutU64(bytes, bytes->size() - 8, vm::HashSource(std::string_view(*bytes).substr(0, bytes->size() - 8)));
}

/// `file` with one program edited, saved: the checksum is right, the program is not.
template <class Edit>
std::string SavedWith(bool bound, Edit edit) {
    vm::BytecodeFile file = Wave();
    edit(bound ? file.bound : file.shade);
    return vm::SaveBytecode(file);
}

}  // namespace

TEST_CASE("FNV-1a 64 of known strings", "[vm][bytecode]") {
    CHECK(vm::HashSource("") == 0xcbf29ce484222325ull);
    CHECK(vm::HashSource("a") == 0xaf63dc4c8601ec8cull);
    CHECK(vm::HashSource("foobar") == 0x85944171f73967e8ull);
}

TEST_CASE("every shader round-trips field for field and byte for byte", "[vm][bytecode]") {
    for (const std::string& path : test::AllShaders()) {
        INFO(path);
        const vm::BytecodeFile file = FileFor(path);
        REQUIRE_FALSE(file.bound.code.empty());
        const std::string bytes = vm::SaveBytecode(file);
        CHECK(vm::SaveBytecode(file) == bytes);

        vm::BytecodeFile loaded;
        std::string error;
        REQUIRE(vm::LoadBytecode(bytes, &loaded, &error));
        CHECK(error.empty());
        CHECK(loaded.shaderName == file.shaderName);
        CHECK(loaded.sourcePath == file.sourcePath);
        CHECK(loaded.sourceHash == file.sourceHash);
        RequireSameProgram(file.bound, loaded.bound);
        RequireSameProgram(file.shade, loaded.shade);
        CHECK(vm::SaveBytecode(loaded) == bytes);
    }
}

TEST_CASE("loaded programs compute what the compiled ones do", "[vm][bytecode]") {
    for (const std::string& path : test::AllShaders()) {
        INFO(path);
        const vm::BytecodeFile file = FileFor(path);
        vm::BytecodeFile loaded;
        REQUIRE(vm::LoadBytecode(vm::SaveBytecode(file), &loaded, nullptr));
        for (int i = 0; i <= 4; ++i) {
            for (int j = 0; j <= 4; ++j) {
                const double u = 0.25 * i, v = 0.25 * j;
                glm::dvec3 expected[3] = {test::PointOnSquare(file.bound, u, v), test::PointOnSquare(file.shade, u, v),
                                          test::PointOnSquare(file.shade, u, v, "N")};
                glm::dvec3 actual[3] = {test::PointOnSquare(loaded.bound, u, v),
                                        test::PointOnSquare(loaded.shade, u, v),
                                        test::PointOnSquare(loaded.shade, u, v, "N")};
                for (int k = 0; k < 3; ++k)
                    for (int c = 0; c < 3; ++c) CHECK(Bits(expected[k][c]) == Bits(actual[k][c]));
            }
        }
    }
}

TEST_CASE("layout: little-endian fields at documented offsets, exact doubles", "[vm][bytecode]") {
    vm::BytecodeFile file;
    file.shaderName = "s";
    file.sourceHash = 0x0102030405060708ull;
    file.bound.registerCount = 1;
    file.bound.constants = {-0.0, std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::denorm_min()};
    file.bound.code = {vm::Instr{vm::Op::LoadK, 0, 0, 3, 0}};
    const std::string bytes = vm::SaveBytecode(file);
    CHECK(bytes.substr(0, 12) == std::string("AFRAYBC\0\6\0\0\0", 12));  // magic, version 6
    uint64_t length = 0;
    for (int i = 7; i >= 0; --i) length = (length << 8) | static_cast<uint8_t>(bytes[12 + i]);
    CHECK(length == bytes.size());
    CHECK(bytes.substr(28, 9) == std::string("\1\0\0\0s\0\0\0\0", 9));                 // shaderName, sourcePath
    CHECK(bytes.substr(37, 8) == std::string("\x08\x07\x06\x05\x04\x03\x02\x01", 8));  // sourceHash
    vm::BytecodeFile loaded;
    std::string error;
    REQUIRE(vm::LoadBytecode(bytes, &loaded, &error));
    RequireSameProgram(file.bound, loaded.bound);
    RequireSameProgram(file.shade, loaded.shade);
}

TEST_CASE("wrong magic, wrong version and trailing bytes", "[vm][bytecode]") {
    const std::string& bytes = WaveBytes();
    CHECK(LoadError(bytes) == "<loaded>");
    CHECK(LoadError("hello") == "not an affray bytecode file");
    CHECK(LoadError("#version 1\nsurface x() {}") == "not an affray bytecode file");
    std::string wrongMagic = bytes;
    wrongMagic[0] = 'X';
    CHECK(LoadError(wrongMagic) == "not an affray bytecode file");
    std::string version7 = bytes;
    version7[8] = 7;
    CHECK(LoadError(version7) ==
          "unsupported bytecode version 7 (this affray reads " + std::to_string(vm::kBytecodeVersion) + ")");
    CHECK(LoadError(bytes + "x") == "trailing bytes after the end of the file (1 extra)");
}

TEST_CASE("every truncation of a valid file is reported as one", "[vm][bytecode]") {
    const std::string& bytes = WaveBytes();
    int wrong = 0;
    for (size_t n = 0; n < bytes.size(); ++n) {
        std::string error = LoadError(std::string_view(bytes).substr(0, n));
        if (error != "truncated file" && wrong++ < 5) FAIL_CHECK("prefix of " << n << " bytes: " << error);
    }
    CHECK(wrong == 0);
}

TEST_CASE("every single-byte flip is detected", "[vm][bytecode]") {
    const std::string& bytes = WaveBytes();
    int wrong = 0;
    for (size_t i = 0; i < bytes.size(); ++i) {
        for (int mask : {0x01, 0x80, 0xff}) {
            std::string flipped = bytes;
            flipped[i] = static_cast<char>(flipped[i] ^ mask);
            std::string expected = "corrupt file (checksum mismatch)";
            if (i < 8) expected = "not an affray bytecode file";
            if (i >= 8 && i < 12)
                expected = "unsupported bytecode version " +
                           std::to_string(vm::kBytecodeVersion ^ (uint32_t(mask) << (8 * (i - 8)))) +
                           " (this affray reads " + std::to_string(vm::kBytecodeVersion) + ")";
            std::string error = LoadError(flipped);
            if (error != expected && wrong++ < 5) FAIL_CHECK("byte " << i << " ^ " << mask << ": " << error);
        }
    }
    CHECK(wrong == 0);
}

TEST_CASE("programs that pass the checksum but not the verifier", "[vm][bytecode]") {
    const int nRegs = Wave().bound.registerCount;
    CHECK(LoadError(SavedWith(true, [](vm::Program& p) { p.code[0].a = static_cast<uint16_t>(p.registerCount); })) ==
          "program 'bound': instruction 0: register r" + std::to_string(nRegs) + " out of range");
    CHECK(LoadError(SavedWith(false, [](vm::Program& p) { p.code[1].op = static_cast<vm::Op>(200); })) ==
          "program 'shade': instruction 1: unknown opcode 200");
    CHECK(LoadError(SavedWith(true, [](vm::Program& p) { p.outputs[0].registers[0] = vm::kNoRegister; })) ==
          "program 'bound': output P register out of range or never written");
    CHECK(LoadError(SavedWith(true, [](vm::Program& p) { p.registerCount = -1; })) ==
          "program 'bound': register count -1 out of range");
    CHECK(LoadError(SavedWith(false, [](vm::Program& p) { p.constants.resize(vm::kMaxConstants + 1); })) ==
          "program 'shade': too many constants (65537)");
    const size_t nCode = Wave().bound.code.size();
    CHECK(LoadError(SavedWith(true, [](vm::Program& p) { p.lines.resize(p.code.size() + 1); })) ==
          "program 'bound': line table has " + std::to_string(nCode + 1) + " entries for " + std::to_string(nCode) +
              " instructions");
    if (!Wave().bound.params.empty())
        CHECK(LoadError(SavedWith(true, [](vm::Program& p) { p.params[0].defaults.push_back(1.0); })) ==
              "program 'bound': parameter " + Wave().bound.params[0].name + " has the wrong number of defaults");

    // Structure the writer never produces, sealed so that only the parser can object.
    std::string bytes = WaveBytes();
    const size_t tag = bytes.find(std::string("\5\0\0\0bound", 9));
    REQUIRE(tag != std::string::npos);
    bytes[tag + 8] = 'x';
    Reseal(&bytes);
    CHECK(LoadError(bytes) == "expected program section 'bound'");
    bytes = WaveBytes();
    bytes.insert(bytes.size() - 8, "abcd");
    Reseal(&bytes);
    CHECK(LoadError(bytes) == "corrupt file (4 unused bytes after the programs)");
    bytes = WaveBytes();
    bytes.erase(bytes.size() - 12, 4);
    Reseal(&bytes);
    CHECK(LoadError(bytes) == "corrupt file (a field runs past the end of the data)");
}

TEST_CASE("random and mutated files never crash the loader", "[vm][bytecode]") {
    const std::string& valid = WaveBytes();
    std::mt19937_64 rng(20240601);
    auto below = [&](size_t n) { return static_cast<size_t>(rng() % n); };
    int loaded = 0, problems = 0;
    for (int iter = 0; iter < 20000; ++iter) {
        std::string bytes;
        switch (iter % 4) {
            case 0:  // noise
                bytes.resize(below(300));
                for (char& c : bytes) c = static_cast<char>(rng());
                break;
            case 1:  // a sealed header over noise
                bytes = valid.substr(0, 28);
                bytes.resize(28 + below(400));
                for (size_t i = 28; i < bytes.size(); ++i) bytes[i] = static_cast<char>(rng());
                Reseal(&bytes);
                break;
            case 2:  // a few bytes of the body overwritten, mostly with small values, resealed
                bytes = valid;
                for (size_t k = 1 + below(4); k > 0; --k)
                    bytes[28 + below(bytes.size() - 36)] = static_cast<char>(below(2) ? below(4) : rng());
                Reseal(&bytes);
                break;
            default: {  // a range of the body deleted or duplicated, resealed
                bytes = valid;
                const size_t at = 28 + below(bytes.size() - 36), n = 1 + below(16);
                if (below(2))
                    bytes.erase(at, std::min(n, bytes.size() - 8 - at));
                else
                    bytes.insert(at, bytes.substr(at, n));
                Reseal(&bytes);
                break;
            }
        }
        vm::BytecodeFile file;
        std::string error;
        if (vm::LoadBytecode(bytes, &file, &error)) {
            // Whatever loads is verified, and the encoding has no slack: it saves to the same bytes.
            ++loaded;
            problems +=
                !vm::Verify(file.bound, nullptr) || !vm::Verify(file.shade, nullptr) || vm::SaveBytecode(file) != bytes;
        } else {
            problems += error.empty();
        }
    }
    CHECK(problems == 0);
    CHECK(loaded > 0);  // some mutations (a line number, a constant) give valid programs
}

TEST_CASE("files are written atomically and read back", "[vm][bytecode]") {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("affray_bytecode_test_" + std::to_string(std::random_device()()));
    fs::create_directories(dir);
    const std::string path = (dir / "wave.afb").string();
    affray::diag::Report error;

    REQUIRE(vm::WriteBytecodeFile(path, Wave(), &error));
    REQUIRE(vm::WriteBytecodeFile(path, Wave(), &error));  // over an existing file
    vm::BytecodeFile loaded;
    REQUIRE(vm::ReadBytecodeFile(path, &loaded, &error));
    RequireSameProgram(Wave().bound, loaded.bound);
    RequireSameProgram(Wave().shade, loaded.shade);
    auto entries = [&] {
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    };
    CHECK(entries() == std::vector<std::string>{"wave.afb"});

    SECTION("a missing directory fails and leaves nothing") {
        const std::string missing = (dir / "missing" / "x.afb").string();
        CHECK_FALSE(vm::WriteBytecodeFile(missing, Wave(), &error));
        CHECK(test::LastMessage(error) == missing + ": error: cannot write file: No such file or directory");
        CHECK_FALSE(fs::exists(dir / "missing"));
        CHECK(entries() == std::vector<std::string>{"wave.afb"});
    }
    SECTION("a failed rename removes the temporary file") {
        fs::create_directory(dir / "taken");
        fs::create_directory(dir / "taken" / "child");  // rename() cannot replace a non-empty directory
        CHECK_FALSE(vm::WriteBytecodeFile((dir / "taken").string(), Wave(), &error));
        CHECK(entries() == std::vector<std::string>{"taken", "wave.afb"});
    }
    SECTION("read errors name the file") {
        CHECK_FALSE(vm::ReadBytecodeFile((dir / "none.afb").string(), &loaded, &error));
        CHECK(test::LastMessage(error) ==
              (dir / "none.afb").string() + ": error: cannot open file: No such file or directory");
        const std::string& bytes = WaveBytes();
        std::ofstream((dir / "short.afb").string(), std::ios::binary).write(bytes.data(), 100);
        CHECK_FALSE(vm::ReadBytecodeFile((dir / "short.afb").string(), &loaded, &error));
        CHECK(test::LastMessage(error) == (dir / "short.afb").string() + ": error: truncated file");
    }
    fs::remove_all(dir);
}

TEST_CASE("texture slots: kept field for field, maps read again, bad slots refused", "[vm][bytecode][texture]") {
    test::TempDir dir;
    const std::string map = dir.Path("map.exr");
    {
        // A 2x2 map beside the shader, and a lookup of a missing map with a fill.
        const std::string shader = dir.Write("t.sl",
                                             "displacement t(float b = 0.5) {\n"
                                             "  P += texture(\"map.exr\"[0], s, t, \"blur\", b) * N;\n"
                                             "  P += texture(\"gone.exr\", s, t, \"fill\", 2) * N;\n}\n");
        test::tex::WriteImage(map, 2, 2, 1, {0, 1, 2, 3});
        compiler::CompileResult r = compiler::CompileFile(shader);
        INFO(r.diagnostics.format());
        REQUIRE(r.ok());
        vm::BytecodeFile file;
        file.bound = r.shader->genericBound;
        file.shade = r.shader->genericShade;
        const std::string bytes = vm::SaveBytecode(file);
        vm::BytecodeFile loaded;
        std::string error;
        REQUIRE(vm::LoadBytecode(bytes, &loaded, &error));
        RequireSameProgram(file.bound, loaded.bound);
        REQUIRE(loaded.bound.textures->size() == 2);
        CHECK((*loaded.bound.textures)[0].map);
        CHECK((*loaded.bound.textures)[0].dependsOn == std::vector<std::string>{"b"});
        CHECK_FALSE((*loaded.bound.textures)[1].map);  // its fill stands in
        CHECK(vm::SaveBytecode(loaded) == bytes);

        // The map gone: an error naming it (the other slot has a fill, so it loads without).
        std::filesystem::remove(map);
        CHECK(LoadError(bytes).find("program 'bound': cannot") == 0);
        CHECK(LoadError(bytes).find("map.exr") != std::string::npos);
        test::tex::WriteImage(map, 2, 2, 1, {0, 1, 2, 3});

        // A slot the code names that the table lacks, and options out of range.
        auto edited = [&](auto edit) {
            vm::BytecodeFile f = file;
            auto slots = std::make_shared<vm::TextureSlots>(*f.bound.textures);
            edit(*slots, f.bound);
            f.bound.textures = slots;
            return vm::SaveBytecode(f);
        };
        CHECK(LoadError(edited([](vm::TextureSlots& s, vm::Program&) {
                  s.pop_back();
              })).find("texture slot 1 out of range") != std::string::npos);
        CHECK(LoadError(edited([](vm::TextureSlots& s, vm::Program&) { s[0].options.sblur = -1; })) ==
              "program 'bound': texture slot of '" + (*file.bound.textures)[0].path + "' has bad options");
        CHECK(LoadError(edited([](vm::TextureSlots& s, vm::Program&) {
                  s[0].options.filter = static_cast<texture::Filter>(9);
              })).find("has bad options") != std::string::npos);
    }
}
