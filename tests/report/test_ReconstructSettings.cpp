// The options reconstruct and batch share: one list, the same checks and
// names on the command line and in a manifest, and a record that names
// every one of them.
#include <gtest/gtest.h>

#include <stdexcept>

#include "report/ReconstructSettings.hpp"

using namespace dfrecon;
using namespace dfrecon;

TEST(ReconstructSettings, TheRecordNamesEveryOptionAsTheCommandLineDoes) {
    const nlohmann::ordered_json json = reconstructSettingsJson({});
    std::vector<std::string> keys;
    for (const auto& [key, value] : json.items()) keys.push_back(key);
    EXPECT_EQ(keys, reconstructSettingsNames());
    EXPECT_EQ(keys.front(), "pixel-mm");
}

TEST(ReconstructSettings, GivenOptionsOverrideTheBase) {
    ReconstructSettings base;
    base.options.cap = CapMode::Dome;
    base.ascii = true;
    const ReconstructSettings s = withGivenOptions(base, {{"interpolation", "smooth", ""},
                                                          {"cap-offset", "1.5", ""},
                                                          {"ascii", "false", ""},
                                                          {"allow-invalid", "yes", ""},
                                                          {"contour-error", "0.1", ""}});
    EXPECT_EQ(s.options.cap, CapMode::Dome);  // kept from the base
    EXPECT_EQ(s.options.interpolation, Interpolation::Smooth);
    EXPECT_EQ(s.options.capOffsetMm, 1.5);
    EXPECT_FALSE(s.ascii);
    EXPECT_TRUE(s.allowInvalid);
    EXPECT_EQ(s.options.contourErrorMm, 0.1);
    const nlohmann::ordered_json json = reconstructSettingsJson(s);
    EXPECT_EQ(json["cap"], "dome");
    EXPECT_EQ(json["cap-offset"], 1.5);
    EXPECT_TRUE(reconstructSettingsJson({})["cap-offset"].is_null());  // automatic
}

TEST(ReconstructSettings, BadValuesAreRefusedWithTheirPlace) {
    const struct {
        GivenOption option;
        std::string message;
    } cases[] = {
        {{"cap", "round", "here"}, "here: --cap: round not in"},
        {{"pixel-mm", "-1", "here"}, "must be at least 0, not -1"},
        {{"smooth-tolerance", "0", "here"}, "must be greater than 0, not 0"},
        {{"max-depth", "13", "here"}, "here: --max-depth"},
        {{"max-error", "nan", "here"}, "'nan' is not a number"},
        {{"colour", "red", "here"}, "here: unknown option 'colour'"},
        {{"help", "", "here"}, "unknown option 'help'"},
        {{"ascii", "perhaps", "here"}, "here: Could not convert: --ascii = perhaps"},
    };
    for (const auto& c : cases) {
        try {
            withGivenOptions({}, {c.option});
            ADD_FAILURE() << c.option.name << "=" << c.option.value << " was accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos)
                << c.option.name << ": " << e.what();
        }
    }
}
