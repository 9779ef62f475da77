// lang/parse.h: the entry point from source text to syntax tree.
#pragma once

#include <optional>

#include "lang/ast.h"
#include "lang/diagnostics.h"

namespace affray::lang {

/// Lexes and parses `diags.file()`. Syntax errors go to `diags` (several per run where the parser
/// can recover); the returned unit holds what parsed, and is only meaningful if
/// !diags.hasErrors(). Never throws on bad input.
TranslationUnit Parse(Diagnostics& diags);

}  // namespace affray::lang
