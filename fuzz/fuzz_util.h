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

/// Runs `program` once in every number type of the VM (double, Interval, Affine, ReducedAffine
/// and their Duals) over a small region of the unit square, for its first output of three values.
/// `program` must have passed vm::Verify().
void RunEveryNumberType(const vm::Program& program);

}  // namespace affray::fuzz
