// tests/lang/source_test.cpp: source files in memory (lang/source.*): lines counted and returned
// without their line ends ("\n" or "\r\n"), a last line with or without its newline, an empty
// file, lines out of range; and loading from disk, with the reason a file cannot be read.
#include <catch2/catch.hpp>

#include <string>

#include "lang/source.h"
#include "tests/test_util.h"

using affray::lang::SourceFile;

TEST_CASE("source: lines are found without their line ends", "[lang][source]") {
    const SourceFile f("a.sl", "first\r\n\n  third\nlast");
    CHECK(f.path() == "a.sl");
    CHECK(f.lineCount() == 4);
    CHECK(f.lineText(1) == "first");
    CHECK(f.lineText(2) == "");
    CHECK(f.lineText(3) == "  third");
    CHECK(f.lineText(4) == "last");
    CHECK(f.lineText(0) == "");
    CHECK(f.lineText(5) == "");
    CHECK(f.lineText(-1) == "");
    // A final newline ends the last line; it starts none.
    CHECK(SourceFile("b.sl", "one\ntwo\n").lineCount() == 2);
    CHECK(SourceFile("b.sl", "one\ntwo\n").lineText(2) == "two");
    CHECK(SourceFile("b.sl", "one\n\n").lineCount() == 2);
    // An empty file has one empty line, so a place at 1:1 can always be shown.
    const SourceFile empty("c.sl", "");
    CHECK(empty.lineCount() == 1);
    CHECK(empty.lineText(1) == "");
    // A lone carriage return is part of the line; only the one before '\n' or the end is dropped.
    CHECK(SourceFile("d.sl", "a\rb\r").lineText(1) == "a\rb");
}

TEST_CASE("source: files are loaded from disk, or the reason they cannot be", "[lang][source]") {
    affray::test::TempDir dir;
    const std::string path = dir.Write("s.sl", "displacement d() {\n}\n");
    SourceFile f("unchanged", "x");
    std::string error;
    REQUIRE(SourceFile::Load(path, &f, &error));
    CHECK(f.path() == path);
    CHECK(f.text() == "displacement d() {\n}\n");
    CHECK(f.lineText(2) == "}");
    SourceFile kept("kept", "y");
    CHECK_FALSE(SourceFile::Load(dir.Path("missing.sl"), &kept, &error));
    CHECK(error.find("No such file or directory") != std::string::npos);
    CHECK(kept.path() == "kept");
    CHECK(kept.text() == "y");
    CHECK_FALSE(SourceFile::Load(dir.Path("missing.sl"), &kept, nullptr));  // no place for the reason
}
