// tests/compiler/regex_match_test.cpp: match()'s search (compiler/regex_match.*): a POSIX
// extended regular expression found anywhere in the subject (not anchored unless the pattern
// says so), an invalid pattern and a string past kMaxMatchLength refused with their sentences.
// The built-in in shaders, with its diagnostics' places, is tests/compiler/library_test.cpp's.
#include <catch2/catch.hpp>

#include <string>

#include "compiler/regex_match.h"

using affray::compiler::kMaxMatchLength;
using affray::compiler::RegexSearch;

TEST_CASE("regex match: a search anywhere in the subject, in POSIX extended syntax", "[compiler][match]") {
    std::string error;
    CHECK(RegexSearch("ood", "wood", &error) == true);
    CHECK(RegexSearch("^w", "wood", &error) == true);
    CHECK(RegexSearch("^o", "wood", &error) == false);
    CHECK(RegexSearch("d$", "wood", &error) == true);
    CHECK(RegexSearch("o{2}", "wood", &error) == true);
    CHECK(RegexSearch("o{3}", "wood", &error) == false);
    CHECK(RegexSearch("(ma|ro)ck", "rock", &error) == true);
    CHECK(RegexSearch("[0-9]+\\.tx", "bump12.tx", &error) == true);
    CHECK(RegexSearch("[0-9]+\\.tx", "bump.tx", &error) == false);
    CHECK(RegexSearch("", "", &error) == true);
    CHECK(RegexSearch("a", "", &error) == false);
    CHECK(RegexSearch("Wood", "wood", &error) == false);  // case matters
    CHECK(error.empty());
}

TEST_CASE("regex match: an invalid pattern or an overlong string is an error, not an answer", "[compiler][match]") {
    std::string error;
    CHECK_FALSE(RegexSearch("(", "x", &error).has_value());
    CHECK(error == "invalid regular expression '('");
    CHECK_FALSE(RegexSearch("a{2,1}", "x", &error).has_value());
    CHECK(error == "invalid regular expression 'a{2,1}'");
    const std::string longest(kMaxMatchLength, 'a'), tooLong(kMaxMatchLength + 1, 'a');
    error.clear();
    CHECK(RegexSearch("a$", longest, &error) == true);
    CHECK(RegexSearch(longest, longest, &error) == true);
    CHECK(error.empty());
    const std::string said = "'match' takes strings of at most " + std::to_string(kMaxMatchLength) + " characters";
    CHECK_FALSE(RegexSearch("a", tooLong, &error).has_value());
    CHECK(error == said);
    error.clear();
    CHECK_FALSE(RegexSearch(tooLong, "a", &error).has_value());
    CHECK(error == said);
}
