// tests/tools/ctest_names_test.cpp: every test case name survives CTest registration.
// catch_discover_tests (tests/CMakeLists.txt) passes the names through a CMake list, where ';'
// splits a name in two and '[' or ']' groups list elements: such a name silently registers as
// other, empty tests (this once hid 121 of 262 test cases from CTest). A leading '-' reads as a
// command-line option.
#include <catch2/catch.hpp>

#include <string>

TEST_CASE("test names are safe for CTest registration", "[tools][ctest]") {
    const Catch::IConfigPtr config = Catch::getCurrentContext().getConfig();  // set while tests run
    REQUIRE(config);
    const std::vector<Catch::TestCase>& all = Catch::getAllTestCasesSorted(*config);
    CHECK(all.size() > 100);
    for (const Catch::TestCase& t : all) {
        INFO(t.name);
        CHECK(t.name.find_first_of(";[]\\") == std::string::npos);
        CHECK(!t.name.empty());
        CHECK(t.name[0] != '-');
    }
}
