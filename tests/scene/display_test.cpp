// tests/scene/display_test.cpp: Display modes (scene/display.*): each group of the grammar and the
// AOV it asks for, groups combined, spaces around them, prman's names for colour and opacity; an
// unknown or empty group refused with the sentence naming it, the channels left as they were; and
// the single-group check the RIB reader uses.
#include <catch2/catch.hpp>

#include <string>

#include "scene/display.h"

using namespace affray::renderer;

TEST_CASE("Display modes select the AOV channels", "[scene][display]") {
    auto parse = [](const std::string& mode) {
        DisplayChannels ch;
        std::string error;
        INFO("mode " << mode);
        REQUIRE(ParseDisplayMode(mode, &ch, &error));
        return ch;
    };
    CHECK(parse("rgba") == DisplayChannels{});
    CHECK(parse("rgb") == DisplayChannels{});
    CHECK(parse("rgbz").z);
    CHECK(parse("rgbaz") == DisplayChannels{true, false, false, false, false, false});
    CHECK(parse("r,g,b,a") == DisplayChannels{});
    CHECK(parse("z").z);
    CHECK(parse("rgba,Z") == parse("rgbaz"));
    CHECK(parse("rgba,N,P,st,cost,err") == DisplayChannels{false, true, true, true, true, true});
    CHECK(parse(" rgb , N ") == DisplayChannels{false, true, false, false, false, false});
    // prman's output variables for colour and opacity, as its exporters name the primary display.
    CHECK(parse("Ci") == DisplayChannels{});
    CHECK(parse("Ci,a") == DisplayChannels{});
    CHECK(parse("Ci,Oi,N") == DisplayChannels{false, true, false, false, false, false});

    auto fails = [](const std::string& mode, const std::string& mention) {
        DisplayChannels ch{true, true, true, true, true, true};
        std::string error;
        INFO("mode '" << mode << "'");
        REQUIRE_FALSE(ParseDisplayMode(mode, &ch, &error));
        INFO("error: " << error);
        CHECK(error.find(mention) != std::string::npos);
        CHECK(ch == DisplayChannels{true, true, true, true, true, true});  // untouched on error
    };
    fails("rgba,foo", "'foo'");
    fails("RGBA", "'RGBA'");
    fails("rgba,n", "'n'");
    fails("rgba,,Z", "empty channel group");
    fails("", "empty channel group");
    fails("rgba,", "empty channel group");
}

TEST_CASE("display: the refusal's sentence, and single groups as the RIB reader checks them", "[scene][display]") {
    DisplayChannels ch;
    std::string error;
    REQUIRE_FALSE(ParseDisplayMode("rgba, foo ", &ch, &error));
    CHECK(error ==
          "unknown channel group 'foo' in display mode 'rgba, foo ' (expected comma-separated rgb, rgba, rgbz, "
          "rgbaz, r, g, b, a, z, Ci, Oi, Z, N, P, st, cost, err)");
    CHECK_FALSE(ParseDisplayMode("N,", &ch, nullptr));  // no place for the sentence
    CHECK(ch == DisplayChannels{});

    for (const char* group :
         {"rgb", "rgba", "rgbz", "rgbaz", "r", "g", "b", "a", "z", "Ci", "Oi", "Z", "N", "P", "st", "cost", "err"})
        CHECK(DisplayGroupP(group));
    for (const char* group : {"", " N", "N ", "n", "rgba,N", "Cs", "ST"}) {
        INFO("group '" << group << "'");
        CHECK_FALSE(DisplayGroupP(group));
    }
}
