// vm/bytecode_file.h: the compiled-bytecode file format (.afb) and its reader and writer.
// A file holds the two generic programs compiled from one shader source (bound: outputs P;
// shade: outputs P and N), field for field what vm::Program holds, so a loaded program is the
// compiled one. Rules for changing the format: bump kBytecodeVersion whenever the layout or the
// meaning of a field changes (opcode numbers included: see vm/opcodes.h), and never read a
// version other than the current one.
//
// Every integer is little-endian and written byte by byte (never a memcpy of a struct), so the
// bytes do not depend on the host. `str` is a u32 byte count followed by the bytes (no NUL);
// doubles are their IEEE-754 binary64 bit patterns as u64. FNV-1a 64 is HashSource().
//
//   offset  size  field
//   0       8     magic "AFRAYBC\0"
//   8       4     u32 format version (kBytecodeVersion = 6)
//   12      8     u64 file length L in bytes, this header and the final checksum included
//   20      8     u64 header check: FNV-1a 64 of bytes 0..19
//   28      ...   str shaderName, str sourcePath, u64 sourceHash (FNV-1a 64 of the source)
//   ...     ...   program section "bound", then program section "shade" (below)
//   L-8     8     u64 checksum: FNV-1a 64 of bytes 0..L-9
//
//   program section              (one vm::Program)
//     str  tag                   "bound" or "shade"
//     str  shaderName, str sourcePath
//     i32  registerCount
//     u32  global count (= kGlobalCount), then per global: u16 base register (0xffff: unread)
//     u32  constant count (<= kMaxConstants), then per constant: u64 binary64 bits
//     u32  instruction count, then per instruction: u8 op, u8 flags, u16 a, u16 b, u16 c
//     u32  line count (0 or the instruction count), then per instruction: i32 source line
//     u32  output count, then per output: str name, i32 size, u16 registers[3]
//     u32  param count, then per param: str name, str type, i32 size, u16 firstRegister,
//          u32 default count, then per default: u64 binary64 bits
//     u32  space count, then per space: str name (the coordinate spaces the shader names)
//     u32  texture slot count (<= 256), then per slot: str path, i32 channel, u8 swrap, u8 twrap,
//          u8 filter (texture::Wrap and texture::Filter numbers), u8 fill-if-missing (0 or 1),
//          u64 sblur, u64 tblur, u64 fill (binary64 bits), u32 count then str names of the
//          parameters the options depend on. The loader reads each map again.
//
// The header check and the length let a reader tell a truncated file ("truncated file") from a
// damaged one ("corrupt file (checksum mismatch)"); the checksum is tested before any field
// after the header is interpreted, and every program must then pass vm::Verify().
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "diag/diagnostic.h"
#include "vm/program.h"

namespace affray::vm {

/// The only format version this affray writes and reads.
// 2: control flow, noise, Ext words, flags; 3: tan (63); 4: texture slots, Texture2 and Texture8;
// 5: the globals time and dtime; 6: the globals Cs, Os and Ps, the Light opcode (66).
static constexpr uint32_t kBytecodeVersion = 6;

/// What an .afb file holds.
struct BytecodeFile {
    std::string shaderName;
    std::string sourcePath;   // as given to the compiler, for messages
    uint64_t sourceHash = 0;  // FNV-1a 64 of the source text (for caches)
    Program bound;
    Program shade;
};

/// Serialises to bytes (deterministic: the same input gives the same bytes). Any Program is
/// written as it is, valid or not; LoadBytecode() is where programs are verified.
std::string SaveBytecode(const BytecodeFile& file);

/// Parses bytes; on any problem returns false and sets *error (if non-null) to one sentence:
/// "not an affray bytecode file", "unsupported bytecode version 7 (this affray reads 1)",
/// "truncated file", "corrupt file (checksum mismatch)", "program 'bound': instruction 12:
/// register r40 out of range". Every loaded program passes vm::Verify() when this returns true.
/// Never crashes, hangs or allocates more than the input's size allows, whatever the bytes.
bool LoadBytecode(std::string_view bytes, BytecodeFile* out, std::string* error);

/// Writes atomically: a temporary file beside `path`, renamed over it; the temporary file is
/// removed on failure, so `path` is either the old file or the complete new one. A failure is
/// reported (if `report` is not null) as an error at `path`: "cannot write file: reason".
bool WriteBytecodeFile(const std::string& path, const BytecodeFile& file, diag::Report* report);
/// Reads and parses the whole file; a problem is reported as an error at `path` (if `report` is
/// not null), with LoadBytecode's sentence or "cannot open file: reason".
bool ReadBytecodeFile(const std::string& path, BytecodeFile* out, diag::Report* report);

/// FNV-1a 64-bit hash of text (Fowler, Noll and Vo; offset basis 14695981039346656037, prime
/// 1099511628211).
uint64_t HashSource(std::string_view text);

}  // namespace affray::vm
