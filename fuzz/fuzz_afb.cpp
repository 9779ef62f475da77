// fuzz/fuzz_afb.cpp: compiled bytecode (.afb bytes) -> loader and verifier -> if verified, each
// program run once, in a number type the input picks (every type in the replay program:
// fuzz_util.h), then the file loaded and specialised as `affray eval` loads it, and the
// specialised programs run too.
// The input's length and checksum fields are set to match its bytes first (fuzz_util.h), so that
// mutations reach the parser and the verifier; the raw bytes are loaded too, for the checks that
// come before the checksum. Programs are straight-line code (loops are unrolled by the compiler,
// and the verifier admits no jump), so a run takes at most as many steps as the program has words.
#include <string>

#include "compiler/compile.h"
#include "fuzz/fuzz_util.h"
#include "vm/bytecode_file.h"

using namespace affray;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view raw(reinterpret_cast<const char*>(data), size);
    std::string error;
    vm::LoadBytecode(raw, nullptr, &error);

    std::string bytes(raw);
    fuzz::FixAfbChecksums(&bytes);
    vm::BytecodeFile file;
    if (!vm::LoadBytecode(bytes, &file, &error)) return 0;
    const uint64_t pick = fuzz::PickOf(bytes);
    fuzz::RunNumberTypes(file.bound, pick);
    fuzz::RunNumberTypes(file.shade, pick + 1);

    // As `affray eval` and the renderer load it: outputs checked, programs specialised.
    const std::string path = fuzz::WriteTemp("input.afb", bytes);
    compiler::CompileResult result = compiler::LoadCompiledShader(path);
    if (!result.ok()) return 0;
    fuzz::RunNumberTypes(result.shader->bound, pick + 2);
    fuzz::RunNumberTypes(result.shader->shade, pick + 3);
    return 0;
}
