// The GL census (engine/gl/gl_census.h) counts what the driver holds: objects made and deleted show
// up in it, with the bytes of their storage, so a soak run's "no growth" means something.
#include "engine/gl/gl_census.h"

#include "engine/core/process_memory.h"
#include "engine/gl/gl.h"
#include "engine/gl/objects.h"
#include "gpu_fixture.h"

class GlCensusTest : public engine::test::GpuTest {};

TEST_F(GlCensusTest, CountsObjectsAndTheirBytesAsTheyComeAndGo) {
    const engine::gl::GlCensus before = engine::gl::take_gl_census();
    {
        engine::gl::Buffer a("census a"), b("census b");
        a.storage(1000);
        b.storage(1u << 20);
        engine::gl::Texture texture(GL_TEXTURE_2D, "census texture");
        glTextureStorage2D(texture.id(), 2, GL_RGBA8, 64, 32);  // 64·32·4 + 32·16·4 bytes
        engine::gl::Framebuffer framebuffer("census framebuffer");
        engine::gl::VertexArray vertex_array("census vertex array");
        engine::gl::Query query(GL_TIME_ELAPSED, "census query");
        const engine::gl::GlCensus during = engine::gl::take_gl_census();
        EXPECT_EQ(during.buffers, before.buffers + 2);
        EXPECT_EQ(during.buffer_bytes, before.buffer_bytes + 1000 + (1u << 20));
        EXPECT_EQ(during.textures, before.textures + 1);
        EXPECT_EQ(during.texture_bytes, before.texture_bytes + 64 * 32 * 4 + 32 * 16 * 4);
        EXPECT_EQ(during.framebuffers, before.framebuffers + 1);
        EXPECT_EQ(during.vertex_arrays, before.vertex_arrays + 1);
        EXPECT_EQ(during.queries, before.queries + 1);
        EXPECT_EQ(during.objects(), before.objects() + 6);
        EXPECT_FALSE(during.same_objects(before));
        EXPECT_NE(during.describe().find("buffers"), std::string::npos);
    }
    const engine::gl::GlCensus after = engine::gl::take_gl_census();
    EXPECT_TRUE(after.same_objects(before)) << after.describe() << " against " << before.describe();
    EXPECT_EQ(after.buffer_bytes, before.buffer_bytes);
    EXPECT_EQ(after.texture_bytes, before.texture_bytes);
}

TEST_F(GlCensusTest, FindsObjectsBeyondAGapOfDeletedNames) {
    // Names freed in between (shaders deleted after linking, buffers reallocated) leave holes; the
    // scan must look past them.
    std::vector<engine::gl::Buffer> buffers;
    for (int i = 0; i < 40; ++i) buffers.emplace_back("census hole");
    const engine::gl::GlCensus full = engine::gl::take_gl_census(64);
    for (int i = 0; i < 39; ++i) buffers[static_cast<std::size_t>(i)].reset();
    const engine::gl::GlCensus holed = engine::gl::take_gl_census(64);
    EXPECT_EQ(holed.buffers + 39, full.buffers);
}

TEST(ProcessMemoryTest, ReportsAResidentSizeThatGrowsWithTouchedMemory) {
    const engine::ProcessMemory before = engine::process_memory();
    ASSERT_GT(before.resident_bytes, 0u);
    EXPECT_GE(before.peak_resident_bytes, before.resident_bytes);
    EXPECT_GE(before.virtual_bytes, before.resident_bytes);
    std::vector<char> block(64u << 20, 1);  // touched: resident
    const engine::ProcessMemory after = engine::process_memory();
    EXPECT_GE(after.resident_bytes, before.resident_bytes + (48u << 20)) << static_cast<int>(block[12345]);
}
