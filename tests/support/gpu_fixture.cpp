#include "gpu_fixture.h"

#include <cstdlib>

#include "test_support.h"

namespace engine::test {

HeadlessGlContext& gl_context() {
    static std::unique_ptr<HeadlessGlContext> context = HeadlessGlContext::create(true);
    return *context;
}

::testing::AssertionResult matches_golden(const Image& actual, const std::string& name,
                                          const GoldenTolerance& tolerance) {
    const auto golden_path = source_dir() / "golden" / (name + ".png");
    const char* update = std::getenv("ENGINE_UPDATE_GOLDEN");
    if (update != nullptr && update[0] == '1') {
        write_png(golden_path, actual);
        return ::testing::AssertionSuccess() << "updated " << golden_path;
    }
    const auto out = output_dir("golden");
    if (!std::filesystem::exists(golden_path)) {
        write_png(out / (name + ".actual.png"), actual);
        return ::testing::AssertionFailure() << "no golden " << golden_path << " (actual written to "
                                             << out / (name + ".actual.png") << "; ENGINE_UPDATE_GOLDEN=1 creates it)";
    }
    const Image golden = read_png(golden_path);
    if (golden.width != actual.width || golden.height != actual.height) {
        write_png(out / (name + ".actual.png"), actual);
        return ::testing::AssertionFailure() << name << ": size " << actual.width << "x" << actual.height
                                             << " differs from the golden's " << golden.width << "x" << golden.height;
    }
    const ImageDifference d = compare_images(actual, golden, tolerance.channel_threshold);
    if (d.psnr_db >= tolerance.min_psnr_db && d.fraction_over_threshold <= tolerance.max_fraction_differing)
        return ::testing::AssertionSuccess();
    write_png(out / (name + ".actual.png"), actual);
    write_png(out / (name + ".diff.png"), d.visual);
    return ::testing::AssertionFailure() << name << ": PSNR " << d.psnr_db << " dB (need >= " << tolerance.min_psnr_db
                                         << "), " << d.fraction_over_threshold * 100.0
                                         << "% of pixels differ by more than " << tolerance.channel_threshold
                                         << " (allowed " << tolerance.max_fraction_differing * 100.0
                                         << "%); actual and diff images in " << out;
}

}  // namespace engine::test
