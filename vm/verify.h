// vm/verify.h: checks a program once, before it runs, so the interpreter's loop can trust it.
#pragma once

#include <string>

#include "vm/program.h"

namespace affray::vm {

/// Returns true if `program` is well-formed: every opcode known, every register and constant in
/// range, every register read after it is written (globals count as written at the start),
/// every output and global register in range, and the line table as long as the code. Otherwise
/// returns false with the first problem in *error ("instruction 12: register r40 out of range").
/// Never crashes on garbage. Light instructions (vm/lights.h) are allowed only with `lights`: in
/// a surface shader's program, which runs on points alone, never on a bound type.
bool Verify(const Program& program, std::string* error, bool lights = false);

}  // namespace affray::vm
