// compiler/regex_match.h: RSL's match(pattern, subject), a POSIX extended regular expression
// searched for in the subject, worked out when the shader is compiled (both are constants).
// Kept apart from the lowering because std::regex is the only user of <regex> (see
// compiler/CMakeLists.txt for the one warning this file is built without).
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace affray::compiler {

/// The longest pattern or subject match() takes: libstdc++'s regex recurses per character, so a
/// long string could exhaust the stack instead of giving an error.
inline constexpr size_t kMaxMatchLength = 1000;

/// Whether `pattern` matches part of `subject`; nullopt, with *error saying why, for a pattern
/// that is not a valid regular expression or a string longer than kMaxMatchLength.
std::optional<bool> RegexSearch(const std::string& pattern, const std::string& subject, std::string* error);

}  // namespace affray::compiler
