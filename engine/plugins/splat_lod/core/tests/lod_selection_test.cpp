#include <cmath>

#include <gtest/gtest.h>

#include "splat_lod/core/lod_selection.h"

using plugin_msgs::LodMode;
using splat_lod::lod_selected;
using splat_lod::LodRule;

TEST(LodSelection, CoverageOfAnIsotropicGaussianIsItsLevelSetDiameter) {
    // Σ = σ²I: α falls to 1/255 at r² = σ²·L, so S = 2σ·sqrt(L), L = 2 ln(255 o).
    const double sigma = 3.0, opacity = 0.8;
    const double expected = 2.0 * sigma * std::sqrt(2.0 * std::log(255.0 * opacity));
    EXPECT_NEAR(splat_lod::pixel_coverage(sigma * sigma, 0.0, sigma * sigma, opacity), expected, 1e-12);
    // An ellipse: the shorter of the two axis chords.
    EXPECT_NEAR(splat_lod::pixel_coverage(100.0, 0.0, 4.0, opacity),
                2.0 * 2.0 * std::sqrt(2.0 * std::log(255.0 * opacity)), 1e-12);
    EXPECT_EQ(splat_lod::pixel_coverage(4.0, 0.0, 4.0, 1.0 / 255.0), 0.0);  // never visible
    EXPECT_EQ(splat_lod::pixel_coverage(4.0, 4.0, 4.0, 0.5), 0.0);          // degenerate
}

TEST(LodSelection, ModesChooseLevels) {
    LodRule rule;
    rule.mode = LodMode::baseline;
    EXPECT_TRUE(lod_selected(rule, 1, 0.1, 5.0, 10.0));  // no filter at all
    EXPECT_FALSE(lod_selected(rule, 2, 8.0, 5.0, 10.0));
    rule.mode = LodMode::insert_large;
    EXPECT_TRUE(lod_selected(rule, 3, 100.0, 5.0, 10.0));
    rule.mode = LodMode::filter_small;
    EXPECT_FALSE(lod_selected(rule, 2, 8.0, 5.0, 10.0));   // finest level only
    EXPECT_FALSE(lod_selected(rule, 1, 1.0, 5.0, 10.0));   // too small: 1/5 < 0.5 and 1 < S_T
    EXPECT_TRUE(lod_selected(rule, 1, 100.0, 5.0, 10.0));  // finest is never too large
}

// The hard rule: full with no transition band.
static LodRule hard_rule() {
    LodRule rule;  // full, S_T 2, rel_min 0.5, rel_max 1.5, levels 1..4
    rule.transition_band = 0.0;
    return rule;
}

TEST(LodSelection, FullRuleWithExemptions) {
    const LodRule rule = hard_rule();
    EXPECT_TRUE(lod_selected(rule, 2, 8.0, 5.0, 10.0));
    EXPECT_FALSE(lod_selected(rule, 2, 16.0, 5.0, 10.0));  // 1.6 > rel_max
    EXPECT_TRUE(lod_selected(rule, 2, 15.0, 5.0, 10.0));   // 1.5 = rel_max
    EXPECT_FALSE(lod_selected(rule, 2, 1.9, 5.0, 10.0));   // 0.38 < rel_min and below S_T
    EXPECT_TRUE(lod_selected(rule, 2, 2.0, 5.0, 10.0));    // S >= S_T keeps it
    EXPECT_TRUE(lod_selected(rule, 2, 2.5, 5.0, 10.0));    // S / S_min = 0.5
    EXPECT_TRUE(lod_selected(rule, 4, 0.01, 5.0, 10.0));   // coarsest is never too small
    EXPECT_FALSE(lod_selected(rule, 4, 30.0, 5.0, 10.0));
    EXPECT_TRUE(lod_selected(rule, 1, 300.0, 5.0, 10.0));  // finest is never too large
    EXPECT_TRUE(lod_selected(rule, 3, 0.01, -1.0, -1.0));  // unset bounds filter nothing
    EXPECT_TRUE(lod_selected(rule, 2, 0.01, 5.0, 10.0, /*coarsest_level=*/2));
}

using splat_lod::lod_weight;

TEST(LodWeight, HardSwitchingIsTheSelectionRule) {
    LodRule rule = hard_rule();
    for (const auto mode : {LodMode::baseline, LodMode::filter_small, LodMode::insert_large, LodMode::full}) {
        rule.mode = mode;
        for (int level = 1; level <= 4; ++level)
            for (const double s : {0.01, 1.9, 2.0, 2.5, 8.0, 15.0, 16.0, 300.0})
                EXPECT_EQ(lod_weight(rule, level, s, 5.0, 10.0), lod_selected(rule, level, s, 5.0, 10.0) ? 1.0 : 0.0);
    }
    // The band applies in mode full only: the other modes stay on/off.
    LodRule smooth;
    smooth.mode = LodMode::filter_small;
    EXPECT_EQ(lod_weight(smooth, 1, 1.9, 5.0, 10.0), 0.0);
}

TEST(LodWeight, PlacedBeforeTheRampsLieOnTheFineSideOfEachSwitch) {
    // The default, auto, weighs a cloud whose level handover is not known as `before`, and so does an
    // unresolved auto rule.
    const LodRule defaults;
    ASSERT_EQ(defaults.transition_placement, plugin_msgs::TransitionPlacement::automatic) << "the default";
    ASSERT_EQ(defaults.for_asset(plugin_msgs::LevelHandover::unknown).transition_placement,
              plugin_msgs::TransitionPlacement::before);
    LodRule rule;
    rule.transition_band = 1.0;
    for (const double s : {1.0, 1.2, 1.5, 15.0, 20.0, 25.0})
        for (const int level : {1, 2})
            EXPECT_EQ(lod_weight(rule, level, s, 2.0, 10.0),
                      lod_weight(rule.for_asset(plugin_msgs::LevelHandover::unknown), level, s, 2.0, 10.0));
    rule.transition_placement = plugin_msgs::TransitionPlacement::before;
    // Too large: switch at S = S_max·rel_max = 15; 1 up to there (as the hard rule), then down to 0 at
    // 30, one octave past it.
    EXPECT_DOUBLE_EQ(lod_weight(rule, 2, 15.0, -1.0, 10.0), 1.0);
    EXPECT_DOUBLE_EQ(lod_weight(rule, 2, 15.0 / std::sqrt(2.0), -1.0, 10.0), 1.0);
    EXPECT_NEAR(lod_weight(rule, 2, 15.0 * std::sqrt(2.0), -1.0, 10.0), 0.5, 1e-12);
    EXPECT_NEAR(lod_weight(rule, 2, 15.0 * std::pow(2.0, 0.25), -1.0, 10.0), 0.75, 1e-12);
    EXPECT_DOUBLE_EQ(lod_weight(rule, 2, 30.0, -1.0, 10.0), 0.0);
    // Too small: switch at max(S/S_T, S/(S_min·rel_min)) = 1, here S = 1 (S_min 2, below S_T): 0 from
    // there down (as the hard rule calls it too small), 1 from one octave above it.
    EXPECT_DOUBLE_EQ(lod_weight(rule, 1, 1.0, 2.0, -1.0), 0.0);
    EXPECT_DOUBLE_EQ(lod_weight(rule, 1, 1.0 / std::sqrt(2.0), 2.0, -1.0), 0.0);
    EXPECT_NEAR(lod_weight(rule, 1, std::pow(2.0, 0.25), 2.0, -1.0), 0.25, 1e-12);
    EXPECT_NEAR(lod_weight(rule, 1, std::sqrt(2.0), 2.0, -1.0), 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(lod_weight(rule, 1, 2.0, 2.0, -1.0), 1.0);
    // Where S_T decides (S / S_T above S / (S_min·rel_min)), the switch is at S = S_T.
    EXPECT_DOUBLE_EQ(lod_weight(rule, 1, 2.0, 100.0, -1.0), 0.0);
    EXPECT_NEAR(lod_weight(rule, 1, 2.0 * std::sqrt(2.0), 100.0, -1.0), 0.5, 1e-12);
    // Exemptions: the finest is never too large, the coarsest never too small, unset bounds filter nothing.
    EXPECT_DOUBLE_EQ(lod_weight(rule, 1, 1000.0, -1.0, 10.0), 1.0);
    EXPECT_DOUBLE_EQ(lod_weight(rule, 4, 0.001, 5.0, -1.0), 1.0);
    EXPECT_DOUBLE_EQ(lod_weight(rule, 3, 0.001, -1.0, -1.0), 1.0);
    // A wider band fades over more octaves.
    rule.transition_band = 2.0;
    EXPECT_NEAR(lod_weight(rule, 2, 15.0 * std::sqrt(2.0), -1.0, 10.0), 0.75, 1e-12);
}

// full_hard is full with hard switching whatever the band: the weights of full with band 0.
TEST(LodWeight, FullHardIgnoresTheBand) {
    LodRule hard;
    hard.mode = plugin_msgs::LodMode::full_hard;
    hard.transition_band = 1.0;
    LodRule band_zero;
    band_zero.transition_band = 0.0;
    LodRule smooth;
    smooth.transition_band = 1.0;
    int differ = 0;
    for (int i = 0; i <= 400; ++i) {
        const double s = std::pow(2.0, -4.0 + 12.0 * i / 400.0);
        for (const int level : {1, 2, 3, 4}) {
            EXPECT_EQ(lod_weight(hard, level, s, 2.0, 4.0), lod_weight(band_zero, level, s, 2.0, 4.0));
            differ += lod_weight(hard, level, s, 2.0, 4.0) != lod_weight(smooth, level, s, 2.0, 4.0);
        }
    }
    EXPECT_GT(differ, 0) << "the band matters in full, so the comparison is not vacuous";
}

// A Gaussian fading out where its replacement fades in: on a dolly both coverages scale by the same
// factor, so when the fine one's "too small" switch and the coarse one's "too large" switch fall at the
// same distance the weights are ramp(y) and ramp(−y) of one log distance y: placed before (or centred
// on) the switches they sum to 1 everywhere, equal the hard rule outside the band and change
// continuously (by at most |Δlog2 S| / band).
TEST(LodWeight, FineAndCoarseWeightsSumToOneAcrossTheBand) {
    for (const double band : {0.5, 1.0, 2.0})
        for (const auto placement :
             {plugin_msgs::TransitionPlacement::before, plugin_msgs::TransitionPlacement::centred}) {
            SCOPED_TRACE("band " + std::to_string(band) + ", " + std::string(plugin_msgs::to_string(placement)));
            LodRule rule;
            rule.transition_band = static_cast<float>(band);
            rule.transition_placement = placement;
            LodRule hard = rule;
            hard.transition_band = 0.0;
            const double shift = plugin_msgs::transition_shifts(placement, static_cast<float>(band)).small;
            // Fine: S = t, S_min = 2, switch where t / (2·rel_min) = 1 (t = 1, below S_T). Coarse: S = 16·t,
            // S_max = 16 / rel_max, switch at t = 1 too.
            const double fine_min = 2.0, coarse_max = 16.0 / 1.5;
            double previous_fine = -1.0;
            for (int i = 0; i <= 4000; ++i) {
                const double t = std::pow(2.0, -4.0 + 8.0 * i / 4000.0);  // the dolly: coverage ∝ t
                const double fine = lod_weight(rule, 1, t, fine_min, -1.0);
                const double coarse = lod_weight(rule, 2, 16.0 * t, -1.0, coarse_max);
                ASSERT_NEAR(fine + coarse, 1.0, 1e-9) << "t " << t;
                const double y = std::log2(t);
                if (y < -shift - 1e-9 || y > band - shift + 1e-9) {
                    EXPECT_EQ(fine, lod_selected(hard, 1, t, fine_min, -1.0) ? 1.0 : 0.0);
                    EXPECT_EQ(coarse, lod_selected(hard, 2, 16.0 * t, -1.0, coarse_max) ? 1.0 : 0.0);
                }
                if (std::abs(y + shift) < 1e-3) {
                    EXPECT_NEAR(fine, 0.0, 1e-2) << "0 where the band begins";
                }
                if (std::abs(y - band + shift) < 1e-3) {
                    EXPECT_NEAR(fine, 1.0, 1e-2) << "1 where it ends";
                }
                if (previous_fine >= 0.0) {
                    EXPECT_LE(std::abs(fine - previous_fine), 8.0 / 4000.0 / band + 1e-9);
                }
                previous_fine = fine;
            }
        }
}

// Placed inside: a fine Gaussian fades out over the band before its "too small" switch, a
// coarse one fades in over the band past its "too large" switch. Both ramps lie where the hard rule
// draws the Gaussian, so the weight is never above the hard rule's (nothing drawn that it does not
// draw), equals it outside the bands, is continuous, and a hand-over at one coverage dips: the fine
// one is gone at the switch and the coarse one only begins there.
TEST(LodWeight, PlacedInsideTheRampsLieWhereTheHardRuleDraws) {
    LodRule rule;
    rule.transition_placement = plugin_msgs::TransitionPlacement::inside;
    rule.transition_band = 1.0;
    const LodRule hard = hard_rule();
    // Too large: switch at S = S_max·rel_max = 15: 0 from there up, 1 from one octave below it.
    EXPECT_DOUBLE_EQ(lod_weight(rule, 2, 15.0, -1.0, 10.0), 0.0);
    EXPECT_NEAR(lod_weight(rule, 2, 15.0 / std::sqrt(2.0), -1.0, 10.0), 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(lod_weight(rule, 2, 7.5, -1.0, 10.0), 1.0);
    // Too small: as placed before: 0 at the switch (S = 1 here), 1 from one octave above.
    EXPECT_DOUBLE_EQ(lod_weight(rule, 1, 1.0, 2.0, -1.0), 0.0);
    EXPECT_NEAR(lod_weight(rule, 1, std::sqrt(2.0), 2.0, -1.0), 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(lod_weight(rule, 1, 2.0, 2.0, -1.0), 1.0);
    int inside_band = 0;
    double previous = -1.0;
    for (int i = 0; i <= 4000; ++i) {
        const double s = std::pow(2.0, -3.0 + 10.0 * i / 4000.0);
        for (const int level : {1, 2, 3, 4}) {
            const double w = lod_weight(rule, level, s, 1.0, 6.0);
            const double h = lod_selected(hard, level, s, 1.0, 6.0) ? 1.0 : 0.0;
            ASSERT_LE(w, h) << "level " << level << " S " << s;
            if (w > 0.0 && w < 1.0) ++inside_band;
        }
        const double w2 = lod_weight(rule, 2, s, 1.0, 6.0);
        // Level 2's bands: "too small" for S in (0.5, 1) (y = log2(2S) in (0, 1)), "too large" for S in
        // (4.5, 9) (x = log2(S / 9) in (−1, 0)); outside them, at both ends of each fade, the hard rule.
        if ((s < 0.5 || s > 1.0) && (s < 4.5 || s > 9.0)) {
            EXPECT_EQ(w2, lod_selected(hard, 2, s, 1.0, 6.0) ? 1.0 : 0.0) << "S " << s;
        }
        if (previous >= 0.0) {
            EXPECT_LE(std::abs(w2 - previous), 10.0 / 4000.0 / rule.transition_band + 1e-9) << "continuous";
        }
        previous = w2;
    }
    EXPECT_GT(inside_band, 100) << "the comparison is not vacuous";
    // A hand-over at one coverage (the pair of FineAndCoarseWeightsSumToOneAcrossTheBand): the two sum
    // to 1 outside both bands and to less inside them, 0 at the shared switch.
    EXPECT_DOUBLE_EQ(lod_weight(rule, 1, 1.0, 2.0, -1.0) + lod_weight(rule, 2, 16.0, -1.0, 16.0 / 1.5), 0.0);
    EXPECT_DOUBLE_EQ(lod_weight(rule, 1, 4.0, 2.0, -1.0) + lod_weight(rule, 2, 64.0, -1.0, 16.0 / 1.5), 1.0);
    EXPECT_DOUBLE_EQ(lod_weight(rule, 1, 0.25, 2.0, -1.0) + lod_weight(rule, 2, 4.0, -1.0, 16.0 / 1.5), 1.0);
}

// Levels whose ranges overlap: on a dolly the fine Gaussian's "too small" switch comes `overlap` octaves
// after its coarse replacement's "too large" one (y = log2 t, the fine switch at y = 0, the coarse one at
// y = overlap). Placed inside, the fine ramp is y ∈ [0, b] and the coarse one [overlap − b, overlap], so
// where both are partial they sum to overlap / b: the double cover is thinned when the levels overlap by
// less than a band. Staggered, the fine ramp is centred on its switch, y ∈ [−b/2, b/2], and they sum to
// (overlap + b/2) / b: thinned only below half a band. Both are continuous, equal the hard rule outside
// their bands, and hand over from fine alone to coarse alone (1 at both ends).
TEST(LodWeight, StaggeredThinsTheDoubleCoverOnlyBelowHalfABand) {
    using plugin_msgs::TransitionPlacement;
    for (const double band : {0.5, 1.0})
        for (const double overlap : {0.2, 0.4, 0.75, 1.5})
            for (const auto placement : {TransitionPlacement::inside, TransitionPlacement::staggered}) {
                SCOPED_TRACE("band " + std::to_string(band) + ", overlap " + std::to_string(overlap) + ", " +
                             std::string(plugin_msgs::to_string(placement)));
                LodRule rule;
                rule.transition_band = static_cast<float>(band);
                rule.transition_placement = placement;
                const LodRule hard = hard_rule();
                const double fine_min = 2.0, coarse_max = 16.0 * std::exp2(overlap) / 1.5;
                const double shift = plugin_msgs::transition_shifts(placement, static_cast<float>(band)).small;
                double lowest = 2.0, previous = -1.0;
                for (int i = 0; i <= 8000; ++i) {
                    const double y = -4.0 + 8.0 * i / 8000.0, t = std::exp2(y);
                    const double fine = lod_weight(rule, 1, t, fine_min, -1.0);
                    const double coarse = lod_weight(rule, 2, 16.0 * t, -1.0, coarse_max);
                    lowest = std::min(lowest, fine + coarse);
                    if (y < -shift - 1e-9 || y > band - shift + 1e-9) {
                        EXPECT_EQ(fine, lod_selected(hard, 1, t, fine_min, -1.0) ? 1.0 : 0.0) << "y " << y;
                    }
                    if (y < overlap - band - 1e-9 || y > overlap + 1e-9) {
                        EXPECT_EQ(coarse, lod_selected(hard, 2, 16.0 * t, -1.0, coarse_max) ? 1.0 : 0.0) << "y " << y;
                    }
                    if (previous >= 0.0) {
                        EXPECT_LE(std::abs(fine + coarse - previous), 2.0 * 8.0 / 8000.0 / band + 1e-9);
                    }
                    previous = fine + coarse;
                }
                EXPECT_DOUBLE_EQ(
                    lod_weight(rule, 1, 1.0 / 16.0, fine_min, -1.0) + lod_weight(rule, 2, 1.0, -1.0, coarse_max), 1.0)
                    << "coarse alone far away";
                EXPECT_DOUBLE_EQ(
                    lod_weight(rule, 1, 16.0, fine_min, -1.0) + lod_weight(rule, 2, 256.0, -1.0, coarse_max), 1.0)
                    << "fine alone near";
                const double expected = std::min(1.0, (overlap + shift) / band);
                EXPECT_NEAR(lowest, expected, 2e-3) << "the deepest thinning";
            }
}
