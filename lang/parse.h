// lang/parse.h: the entry point from source text to syntax tree.
#pragma once

#include <optional>

#include "lang/ast.h"
#include "lang/diagnostics.h"
#include "lang/preprocess.h"

namespace affray::lang {

/// Lexes and parses `diags.file()`. Syntax errors go to `diags` (several per run where the parser
/// can recover); the returned unit holds what parsed, and is only meaningful if
/// !diags.hasErrors(). Never throws on bad input.
TranslationUnit Parse(Diagnostics& diags);

/// Preprocesses `diags.file()` (lang/preprocess.h), then lexes and parses the result. Errors of
/// both stages go to `diags`, at their line in the original file, the main one or an included one
/// (named by its path). If preprocessing fails, nothing is parsed
/// and the unit is empty. Never throws on bad input.
TranslationUnit PreprocessAndParse(Diagnostics& diags, const PreprocessOptions& options);

}  // namespace affray::lang
