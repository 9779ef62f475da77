// fuzz/fuzz_util.cpp: see fuzz_util.h.
#include "fuzz/fuzz_util.h"

#include <stdlib.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "diag/limits.h"
#include "scene/geometry/surface.h"
#include "vm/bytecode_file.h"
#include "vm/interpreter.h"

namespace affray::fuzz {

namespace fs = std::filesystem;

namespace {

bool g_everyNumberType = false;

struct PrivateDir {
    std::string path;
    PrivateDir() {
        std::error_code ec;
        fs::path base = fs::temp_directory_path(ec);
        if (ec) base = "/tmp";
        std::string pattern = (base / "affray-fuzz-XXXXXX").string();
        if (!mkdtemp(pattern.data())) {
            std::perror("affray fuzz: cannot create a temporary directory");
            std::abort();
        }
        path = pattern;
    }
    ~PrivateDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

/// Two lights and an ambient colour, whatever a surface program asks.
struct FixedLights final : vm::LightQueries {
    double Trace(const double direction[3], int channel) override { return direction[channel] * 0.5; }
    double Light(int slot, int component, bool shadowed) override {
        if (slot == vm::kAmbientSlot) return component < 3 ? 0.0 : 0.1;
        const double L[2][3] = {{1, 2, 3}, {0, 0, -1}};
        if (component < 3) return slot < 2 ? L[slot][component] : 0.0;
        return shadowed ? 0.5 : 1.0;
    }
};

/// Runs `program` over a region of the unit square, to its first triple output; with `lights`
/// (a surface or light program, which runs on points only) at one point, its lights answered.
template <class N>
void RunAs(const vm::Program& program, vm::LightQueries* lights = nullptr) {
    vm::Interpreter<N> interp(program);
    interp.SetLights(lights);
    const double u1 = lights ? 0.25 : 0.5, v0 = lights ? 0.5 : 0.25;
    for (const vm::ProgramOutput& out : program.outputs) {
        if (out.size != 3) continue;
        renderer::EvaluateOnPatch(interp, renderer::BilinearPatch::UnitSquare(), 0.25, u1, v0, 0.5,
                                  glm::dvec3(0.0, 0.0, -5.0), out);
        return;
    }
}

void PutU64(std::string* bytes, size_t offset, uint64_t x) {
    for (int i = 0; i < 8; ++i) (*bytes)[offset + i] = static_cast<char>((x >> (8 * i)) & 0xff);
}

}  // namespace

const std::string& TempDir() {
    static PrivateDir dir;
    return dir.path;
}

std::string WriteTemp(const std::string& name, std::string_view bytes) {
    static int64_t writes = 0;
    const std::string path = TempDir() + "/" + name;
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    }
    // File times can be as coarse as the kernel's tick: step a time of our own instead.
    std::error_code ec;
    const auto base = fs::file_time_type::clock::now() - std::chrono::hours(24);
    fs::last_write_time(path, base + std::chrono::microseconds(++writes), ec);
    return path;
}

std::string SourceDir() { return AFFRAY_SOURCE_DIR; }

void FixAfbChecksums(std::string* bytes) {
    // The layout of vm/bytecode_file.h: length at 12, header check of bytes 0..19 at 20, and the
    // checksum of everything before it in the last 8 bytes.
    constexpr size_t kHeaderSize = 28, kChecksumSize = 8;
    if (bytes->size() < kHeaderSize + kChecksumSize) return;
    PutU64(bytes, 12, bytes->size());
    PutU64(bytes, 20, vm::HashSource(std::string_view(*bytes).substr(0, 20)));
    const size_t body = bytes->size() - kChecksumSize;
    PutU64(bytes, body, vm::HashSource(std::string_view(*bytes).substr(0, body)));
}

void SetSmallLimits() {
    diag::SetLimit(diag::Limit::ProgramOps, kFuzzProgramOps);
    diag::SetLimit(diag::Limit::LoopIterations, kFuzzLoopIterations);
}

void SetEveryNumberType(bool every) { g_everyNumberType = every; }

uint64_t PickOf(std::string_view bytes) {
    uint64_t h = 14695981039346656037ull;
    for (char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
    return h ^ (h >> 32);
}

void RunNumberTypes(const vm::Program& program, uint64_t pick) {
    for (int type = 0; type < kNumberTypes; ++type) {
        if (!g_everyNumberType && static_cast<uint64_t>(type) != pick % kNumberTypes) continue;
        switch (type) {
            case 0: RunAs<double>(program); break;
            case 1: RunAs<vm::Interval>(program); break;
            case 2: RunAs<vm::Affine>(program); break;
            case 3: RunAs<vm::ReducedAffine>(program); break;
            case 4: RunAs<vm::Dual<double>>(program); break;
            case 5: RunAs<vm::Dual<vm::Interval>>(program); break;
            case 6: RunAs<vm::Dual<vm::Affine>>(program); break;
            default: RunAs<vm::Dual<vm::ReducedAffine>>(program); break;
        }
    }
}

void RunSurface(const vm::Program& program, uint64_t pick) {
    FixedLights lights;
    if (g_everyNumberType || pick % 2 == 0) RunAs<double>(program, &lights);
    if (g_everyNumberType || pick % 2 == 1) RunAs<vm::Dual<double>>(program, &lights);
}

}  // namespace affray::fuzz
