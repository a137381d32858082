// The plugin's messages (LodRule, LodSettings, StreamEvent, ResidencyReport): defaults, JSON round
// trips, and bad input rejected with the kind and key named.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "message_test_helpers.h"
#include "plugin_msgs/plugin_msgs.h"
#include "splat_lod/msgs/lod_settings.h"
#include "splat_lod/msgs/splat_statistics.h"
#include "splat_lod/msgs/stream_events.h"

using nlohmann::json;
using namespace plugin_msgs;

using engine::test::expect_rejected;
using engine::test::expect_round_trip;
using engine::test::parse_error;

// The plugin's messages travel on the engine's bus beside the engine's own: every kind is distinct.
TEST(SplatLodMsgs, KindsAreDistinctFromEachOtherAndTheEngines) {
    const std::vector<std::string_view> kinds{CameraState::kind, FrameStatistics::kind, BackgroundWork::kind,
                                              LodSettings::kind, StreamEvent::kind,     ResidencyReport::kind};
    for (std::size_t i = 0; i < kinds.size(); ++i)
        for (std::size_t j = i + 1; j < kinds.size(); ++j) EXPECT_NE(kinds[i], kinds[j]);
    EXPECT_EQ(LodSettings::kind, "lod_settings");
    EXPECT_EQ(StreamEvent::kind, "stream_event");
    EXPECT_EQ(ResidencyReport::kind, "residency");
}

TEST(SplatLodMsgs, LodSettingsDefaultsFollowTheDesign) {
    const LodSettings settings;
    EXPECT_EQ(settings.rule.mode, LodMode::full);
    EXPECT_EQ(settings.rule.size_threshold_px, 2.0f);
    EXPECT_EQ(settings.rule.rel_min, 0.5f);
    EXPECT_EQ(settings.rule.rel_max, 1.5f);
    EXPECT_EQ(settings.render_scale, 1.0f);
    EXPECT_EQ(settings.upscaler, Upscaler::spline);
    EXPECT_FALSE(settings.mip_filter);
    EXPECT_FALSE(settings.level_colouring);
    EXPECT_EQ(settings.splat_budget, 0u);  // no budget unless asked for
    EXPECT_EQ(settings.validate(), "");
    EXPECT_EQ(json::parse("{}").get<LodSettings>(), settings);  // missing keys keep defaults
}

TEST(SplatLodMsgs, LodSettingsRoundTripEveryModeAndUpscaler) {
    for (std::size_t m = 0; m < plugin_msgs::kLodModeNames.size(); ++m) {
        const auto mode = static_cast<LodMode>(m);
        for (const auto upscaler : {Upscaler::spline, Upscaler::bicubic, Upscaler::bilinear, Upscaler::lanczos3}) {
            LodSettings settings;
            settings.rule.mode = mode;
            settings.upscaler = upscaler;
            settings.rule.size_threshold_px = 3.7f;
            settings.rule.rel_min = 0.25f;
            settings.rule.rel_max = 2.0f;
            settings.render_scale = 1.0f / 3.0f;
            settings.mip_filter = true;
            settings.level_colouring = true;
            settings.splat_budget = 200000;
            settings.rule.transition_band = 0.75f;
            expect_round_trip(settings);
        }
    }
}

// The rule's modes differ only by their traits: the four of the multi-scale method's ablation, each
// a different row, and the JSON keys of a rule sit flat in the object that carries it.
TEST(SplatLodMsgs, LodRuleModesAreTheirTraits) {
    using plugin_msgs::traits;
    EXPECT_FALSE(traits(LodMode::baseline).all_levels);
    EXPECT_FALSE(traits(LodMode::baseline).coverage_rule);
    EXPECT_TRUE(traits(LodMode::filter_small).coverage_rule);
    EXPECT_FALSE(traits(LodMode::filter_small).all_levels);
    EXPECT_TRUE(traits(LodMode::insert_large).all_levels);
    EXPECT_FALSE(traits(LodMode::insert_large).coverage_rule);
    EXPECT_TRUE(traits(LodMode::full).all_levels && traits(LodMode::full).coverage_rule &&
                traits(LodMode::full).transitions);
    for (std::size_t a = 0; a < plugin_msgs::kLodModeNames.size(); ++a)
        for (std::size_t b = a + 1; b < plugin_msgs::kLodModeNames.size(); ++b) {
            const auto ta = traits(static_cast<LodMode>(a)), tb = traits(static_cast<LodMode>(b));
            EXPECT_FALSE(ta.all_levels == tb.all_levels && ta.coverage_rule == tb.coverage_rule &&
                         ta.transitions == tb.transitions)
                << plugin_msgs::kLodModeNames[a] << " and " << plugin_msgs::kLodModeNames[b] << " do the same";
        }
    plugin_msgs::LodRule rule;
    rule.rel_min = 0.75f;
    rule.transition_placement = plugin_msgs::TransitionPlacement::centred;
    rule.overlap_transition_band = 0.75f;
    json object = json::object();
    plugin_msgs::write_rule(object, rule);
    EXPECT_EQ(object.at("rel_min").get<float>(), 0.75f);
    plugin_msgs::LodRule read;
    plugin_msgs::read_rule(object, "test", read);
    EXPECT_EQ(read, rule);
    EXPECT_EQ(rule.validate(), "");
    rule.rel_min = 2.0f;
    EXPECT_EQ(rule.validate("streamer.rule").rfind("streamer.rule.rel_min: ", 0), 0u) << rule.validate();
}

TEST(SplatLodMsgs, AutoPlacementIsResolvedPerAsset) {
    plugin_msgs::LodRule rule;
    rule.transition_band = 0.125f;
    rule.overlap_transition_band = 0.75f;
    ASSERT_EQ(rule.transition_placement, plugin_msgs::TransitionPlacement::automatic);
    // Levels that overlap at their switches: inside, with the overlap band; levels that abut: centred,
    // with the band; not known: before, with the band.
    using plugin_msgs::LevelHandover;
    const plugin_msgs::LodRule overlap = rule.for_asset(LevelHandover::overlapping);
    const plugin_msgs::LodRule abutting = rule.for_asset(LevelHandover::abutting);
    const plugin_msgs::LodRule unknown = rule.for_asset(LevelHandover::unknown);
    EXPECT_EQ(overlap.transition_placement, plugin_msgs::TransitionPlacement::inside);
    EXPECT_EQ(overlap.transition_band, 0.75f);
    EXPECT_EQ(abutting.transition_placement, plugin_msgs::TransitionPlacement::centred);
    EXPECT_EQ(abutting.transition_band, 0.125f);
    EXPECT_EQ(unknown.transition_placement, plugin_msgs::TransitionPlacement::before);
    EXPECT_EQ(unknown.transition_band, 0.125f);
    plugin_msgs::LodRule expected = rule;
    expected.transition_placement = plugin_msgs::TransitionPlacement::inside;
    expected.transition_band = 0.75f;
    EXPECT_EQ(overlap, expected) << "nothing else changes";
    // Any other placement is the rule itself, whatever the asset.
    for (const auto placement :
         {plugin_msgs::TransitionPlacement::inside, plugin_msgs::TransitionPlacement::before,
          plugin_msgs::TransitionPlacement::centred, plugin_msgs::TransitionPlacement::staggered}) {
        rule.transition_placement = placement;
        for (int kind = 0; kind < plugin_msgs::kLevelHandoverCount; ++kind)
            EXPECT_EQ(rule.for_asset(static_cast<LevelHandover>(kind)), rule);
    }
    // Unresolved, auto shifts as for an unknown handover (before): no ramp past its switch.
    const auto shifts = plugin_msgs::transition_shifts(plugin_msgs::TransitionPlacement::automatic, 1.0f);
    EXPECT_EQ(shifts.small, 0.0f);
    EXPECT_EQ(shifts.large, 0.0f);
}

TEST(SplatLodMsgs, LodSettingsEnumsTravelAsNames) {
    LodSettings settings;
    settings.rule.mode = LodMode::insert_large;
    settings.upscaler = Upscaler::lanczos3;
    const json j = settings;
    EXPECT_EQ(j.at("mode"), "insert_large");
    EXPECT_EQ(j.at("upscaler"), "lanczos3");
    EXPECT_EQ(to_string(LodMode::filter_small), "filter_small");
}

TEST(SplatLodMsgs, LodSettingsRejectABudgetThatIsNotACount) {
    expect_rejected<LodSettings>({
        {R"({"splat_budget": -5})", "lod_settings.splat_budget: expected a non-negative integer, got -5"},
        {R"({"splat_budget": 1.5})", "lod_settings.splat_budget: expected a non-negative integer"},
        {R"({"splat_budget": 5000000000})", "lod_settings.splat_budget: 5000000000 is out of range"},
        {R"({"splat_budget": "200k"})", "lod_settings.splat_budget"},
    });
}

TEST(SplatLodMsgs, LodSettingsRejectBadEnumNamesNamingTheKey) {
    expect_rejected<LodSettings>({
        {R"({"mode": "ultra"})", "lod_settings.mode: unknown value 'ultra'"},
        {R"({"mode": 2})", "lod_settings.mode"},
        {R"({"upscaler": "nearest"})", "lod_settings.upscaler: unknown value 'nearest'"},
    });
    // The message lists what would have been accepted.
    EXPECT_NE(parse_error<LodSettings>(R"({"upscaler": "Spline"})").find("spline, bicubic, bilinear, lanczos3"),
              std::string::npos);
}

TEST(SplatLodMsgs, LodSettingsRejectOutOfRangeValuesNamingTheKey) {
    expect_rejected<LodSettings>({
        {R"({"render_scale": 0})", "lod_settings.render_scale: must be in (0, 1]"},
        {R"({"render_scale": 1.5})", "lod_settings.render_scale"},
        {R"({"render_scale": -0.5})", "lod_settings.render_scale"},
        {R"({"render_scale": 1e300})", "lod_settings.render_scale"},
        {R"({"size_threshold_px": 0})", "lod_settings.size_threshold_px"},
        {R"({"size_threshold_px": -2})", "lod_settings.size_threshold_px"},
        {R"({"rel_min": 0})", "lod_settings.rel_min"},
        {R"({"rel_min": 2.0})", "lod_settings.rel_min: must be in (0, rel_max = 1.5]"},
        {R"({"rel_min": 0.5, "rel_max": 0.4})", "lod_settings.rel_min"},
        {R"({"rel_max": -1})", "lod_settings.rel_max"},
        {R"({"transition_band": -0.5})", "lod_settings.transition_band: must be in [0, 4.0] octaves of coverage"},
        {R"({"transition_band": 9})", "lod_settings.transition_band"},
        {R"({"overlap_transition_band": -1})", "lod_settings.overlap_transition_band: must be in [0, 4.0]"},
        {R"({"overlap_transition_band": 4.5})", "lod_settings.overlap_transition_band"},
        {R"({"transition_placement": "after"})", "transition_placement"},
        {R"({"transition_placement": 1})", "transition_placement"},
    });
}

TEST(SplatLodMsgs, LodSettingsRejectWrongTypesAndUnknownKeys) {
    expect_rejected<LodSettings>({
        {R"({"render_scale": "half"})", "lod_settings.render_scale: expected a number"},
        {R"({"mip_filter": 1})", "lod_settings.mip_filter: expected true or false"},
        {R"({"render_scal": 0.5})", "lod_settings.render_scal: unknown key"},
        {R"([1, 2])", "lod_settings: expected a JSON object"},
    });
}

TEST(SplatLodMsgs, LodSettingsValidateCatchesValuesSetInCode) {
    LodSettings settings;
    settings.render_scale = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(settings.validate().find("lod_settings.render_scale"), std::string::npos);
    settings = LodSettings{};
    settings.rule.size_threshold_px = std::numeric_limits<float>::infinity();
    EXPECT_NE(settings.validate().find("lod_settings.size_threshold_px"), std::string::npos);
    settings = LodSettings{};
    settings.rule.rel_min = settings.rule.rel_max;  // the upper end of (0, rel_max] is allowed
    EXPECT_EQ(settings.validate(), "");
}

TEST(SplatLodMsgs, StreamEventRoundTripsEveryEventType) {
    for (const auto type : {StreamEventType::requested, StreamEventType::loaded, StreamEventType::uploaded,
                            StreamEventType::evicted, StreamEventType::failed}) {
        StreamEvent event;
        event.chunk_id = "chunk_+003_-002";
        event.event = type;
        event.level = 3;
        event.bytes = 5'000'000'000ull;  // beyond 32 bits
        event.message = type == StreamEventType::failed ? "truncated file: \"x.ply\" at byte 17" : "";
        expect_round_trip(event);
    }
    EXPECT_EQ(json(StreamEvent{}).at("event"), "requested");
}

TEST(SplatLodMsgs, StreamEventRejectsBadValuesNamingTheKey) {
    expect_rejected<StreamEvent>({
        {R"({"event": "vanished"})", "stream_event.event: unknown value 'vanished'"},
        {R"({"level": 5})", "stream_event.level"},
        {R"({"level": -1})", "stream_event.level"},
        {R"({"level": 1.5})", "stream_event.level: expected an integer"},
        {R"({"bytes": -1})", "stream_event.bytes: expected a non-negative integer"},
        {R"({"chunk_id": 7})", "stream_event.chunk_id"},
        {R"({"chunk": "a"})", "stream_event.chunk: unknown key"},
    });
}

TEST(SplatLodMsgs, ResidencyReportRoundTrips) {
    ResidencyReport report;
    report.frame_index = 900;
    report.resident_bytes = 3'000'000'000ull;
    report.budget_bytes = 2'500'000'000ull;
    report.chunks = {4, 2, 57, 1};
    expect_round_trip(report);
    expect_round_trip(ResidencyReport{});
}

TEST(SplatLodMsgs, ResidencyReportRejectsBadValuesNamingTheKey) {
    expect_rejected<ResidencyReport>({
        {R"({"budget_bytes": -5})", "residency.budget_bytes"},
        {R"({"chunks": {"resident": -3}})", "residency.chunks.resident"},
        {R"({"chunks": {"evicting": 1}})", "residency.chunks.evicting: unknown key"},
        {R"({"chunks": 3})", "residency.chunks: expected a JSON object"},
    });
}
