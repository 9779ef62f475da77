// tests/diag/diagnostic_test.cpp: the one diagnostic format (diag/diagnostic.h): the message line,
// the source line and its caret (under tabs, escaped bytes and UTF-8), notes, one line per message
// whatever the message holds, repeats kept once, and the error limit.
#include <catch2/catch.hpp>

#include "diag/diagnostic.h"

using namespace affray::diag;

TEST_CASE("diag: a diagnostic prints as file:line:col, the source line and a caret, then its notes", "[diag]") {
    Diagnostic d{Severity::Error, {"a.sl", 3, 7, "  P += foo;"}, "unknown variable 'foo'", {}};
    d.notes.push_back({Severity::Note, {"a.sl", 1, 1, "displacement t() {"}, "in shader 't'", {}});
    CHECK(Format(d) ==
          "a.sl:3:7: error: unknown variable 'foo'\n"
          "      P += foo;\n"
          "          ^\n"
          "a.sl:1:1: note: in shader 't'\n"
          "    displacement t() {\n"
          "    ^\n");
    // No column: the source line without a caret; no line: the file alone; no file: the program.
    CHECK(Format({Severity::Warning, {"s.rib", 4, 0, "Foo"}, "w", {}}) == "s.rib:4: warning: w\n    Foo\n");
    CHECK(Format({Severity::Error, {"out.exr"}, "cannot write file: x", {}}) ==
          "out.exr: error: cannot write file: x\n");
    CHECK(Format({Severity::Error, {}, "bad option", {}}) == "affray: error: bad option\n");
}

TEST_CASE("diag: every message prints on one line and the caret stays under its column", "[diag]") {
    // Line breaks and control characters in a message or a file name are escaped.
    CHECK(Format({Severity::Error, {"x\ny.rib", 1, 2, {}}, "mode 'a\nb\r\x01'", {}}) ==
          "x\\ny.rib:1:2: error: mode 'a\\nb\\r\\x01'\n");
    // Tabs stay tabs under tabs; an escaped byte widens the caret's way by its width; a UTF-8
    // character (two bytes here) takes one column.
    CHECK(Format({Severity::Error, {"t.sl", 1, 3, "\t\tx"}, "m", {}}) == "t.sl:1:3: error: m\n    \t\tx\n    \t\t^\n");
    CHECK(Format({Severity::Error, {"t.sl", 1, 2, "\x01x"}, "m", {}}) == "t.sl:1:2: error: m\n    \\x01x\n        ^\n");
    CHECK(Format({Severity::Error, {"t.sl", 1, 4, "\xc3\xa9tx"}, "m", {}}) ==
          "t.sl:1:4: error: m\n    \xc3\xa9tx\n      ^\n");
    // A stray byte that is not UTF-8 is escaped; a valid sequence is kept.
    CHECK(OneLine("a\xff"
                  "b\xe2\x82\xac") == "a\\xffb\xe2\x82\xac");
    CHECK(OneLine("\xc0\xaf") == "\\xc0\\xaf");  // overlong
}

TEST_CASE("diag: a report keeps repeats once, attaches notes, and stops storing past the limit", "[diag]") {
    Report r;
    r.warning({"a.sl", 2, 3, {}}, "unused variable 'x'");
    r.error({"a.sl", 5, 1, {}}, "bad");
    r.note({"a.sl", 1, 1, {}}, "declared here");
    r.error({"a.sl", 5, 1, {}}, "bad");  // an unrolled loop's repeat
    r.note({"a.sl", 1, 1, {}}, "declared here");
    CHECK(r.errorCount() == 1);
    REQUIRE(r.all().size() == 2);
    CHECK(r.all()[1].notes.size() == 1);
    CHECK(r.format() ==
          "a.sl:2:3: warning: unused variable 'x'\na.sl:5:1: error: bad\na.sl:1:1: note: declared here\n");

    Report many;
    for (int i = 1; i <= Report::kMaxErrors + 5; ++i) many.error({"m.sl", i, 1, {}}, "e");
    CHECK(many.errorCount() == Report::kMaxErrors + 5);
    CHECK(many.all().size() == static_cast<size_t>(Report::kMaxErrors));
    const std::string text = many.format();
    CHECK(text.substr(text.rfind("m.sl: error")) == "m.sl: error: too many errors (55), stopping after 50\n");

    // Adding one report to another keeps its count, its notes and its limit.
    Report all;
    all.add(r);
    all.add(many);
    CHECK(all.errorCount() == 1 + Report::kMaxErrors + 5);
    CHECK(all.all()[1].notes.size() == 1);
}
