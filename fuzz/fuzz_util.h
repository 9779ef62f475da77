// fuzz/fuzz_util.h: what the fuzz targets share: a private temporary directory, files written
// into it, the source tree's directories, and the entry point every target defines.
// Rules: a helper here must be deterministic for a given input (libFuzzer replays inputs) and
// must leave nothing behind outside the temporary directory, which is removed at exit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "vm/program.h"

/// libFuzzer's entry point: one input, run to completion; returns 0.
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace affray::fuzz {

/// A directory private to this process (created on first use, removed at exit).
const std::string& TempDir();

/// Writes `bytes` to TempDir()/name and returns the path. Each write gives the file a new
/// modification time, so caches keyed by path and time (texture::Open) read it again.
std::string WriteTemp(const std::string& name, std::string_view bytes);

/// The source tree (shaders/, tests/...), as configured.
std::string SourceDir();

/// Sets the length, header check and checksum fields of .afb bytes to match the bytes, so that
/// mutations reach the loader's parser and the verifier instead of stopping at the checksum.
/// Leaves bytes too short to hold a header as they are.
void FixAfbChecksums(std::string* bytes);

/// The compiler's limits in the fuzz targets that compile shaders: program-ops 20,000 (default
/// 250,000) and loop-iterations 256 (default 10,000). A shader that grows past them is refused
/// with the limit's error, as one past the defaults is, long before its lowering takes seconds
/// under the sanitizers (fuzz/README.md).
inline constexpr int64_t kFuzzProgramOps = 20'000;
inline constexpr int64_t kFuzzLoopIterations = 256;
void SetSmallLimits();

/// The number of number types of the VM: double, Interval, Affine, ReducedAffine and their Duals.
inline constexpr int kNumberTypes = 8;

/// Whether RunNumberTypes runs a program in every number type (the replay program sets it, so
/// that CTest checks every seed and regression in all of them) or in the one an input picks
/// (the default, under libFuzzer: eight times fewer runs of the VM an input).
void SetEveryNumberType(bool every);

/// A hash of the input's bytes (FNV-1a), for picking: any change of the input may pick another.
uint64_t PickOf(std::string_view bytes);

/// Runs `program` once over a small region of the unit square, for its first output of three
/// values: in every number type when SetEveryNumberType(true), else in number type
/// `pick % kNumberTypes` alone. `program` must have passed vm::Verify().
void RunNumberTypes(const vm::Program& program, uint64_t pick);
/// Runs a surface program (one that asks for lights: Light instructions) on a patch point, in
/// the point types it may run in (double, and Dual<double>), its lights answered by a fixed set
/// of two.
void RunSurface(const vm::Program& program, uint64_t pick);

}  // namespace affray::fuzz
