// compiler/regex_match.cpp: match()'s regular expression search (regex_match.h).
#include "compiler/regex_match.h"

#include <regex>

namespace affray::compiler {

std::optional<bool> RegexSearch(const std::string& pattern, const std::string& subject, std::string* error) {
    if (pattern.size() > kMaxMatchLength || subject.size() > kMaxMatchLength) {
        *error = "'match' takes strings of at most " + std::to_string(kMaxMatchLength) + " characters";
        return std::nullopt;
    }
    try {
        return std::regex_search(subject, std::regex(pattern, std::regex::extended));
    } catch (const std::regex_error&) {
        *error = "invalid regular expression '" + pattern + "'";
        return std::nullopt;
    }
}

}  // namespace affray::compiler
