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

TEST(LodSelection, FullRuleWithExemptions) {
    const LodRule rule;  // full, S_T 2, rel_min 0.5, rel_max 1.5, levels 1..4
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
    LodRule two_levels = rule;
    two_levels.coarsest_level = 2;
    EXPECT_TRUE(lod_selected(two_levels, 2, 0.01, 5.0, 10.0));
}
