// gl::Buffer::ensure_size grows by 1.5x steps; the grown size must stay clearable as a whole by
// glClearNamedBufferData with a 4-byte format. It once was not (6·k bytes): the clear failed
// with GL_INVALID_VALUE and left old data, which the splat pass then read as tile counts of
// Gaussians it had not projected (a streamed world's key count exploded after an eviction).
#include <cstdint>
#include <vector>

#include "engine/gl/gl.h"
#include "engine/gl/objects.h"
#include "gpu_fixture.h"

class GlBufferTest : public engine::test::GpuTest {};

TEST_F(GlBufferTest, AGrownBufferCanBeClearedWhole) {
    engine::gl::Buffer buffer(engine::gl::NoCreate);
    buffer.ensure_size(9729 * 4, "test buffer");  // an odd number of words
    buffer.ensure_size(9730 * 4, "test buffer");  // grows by half: 9729 · 6 bytes before rounding
    ASSERT_EQ(buffer.size() % 16, 0u) << buffer.size();
    ASSERT_GE(buffer.size(), 9730u * 4u);
    const std::vector<std::uint32_t> ones(buffer.size() / 4, 1u);
    buffer.upload(0, buffer.size(), ones.data());
    while (glGetError() != GL_NO_ERROR) {
    }
    glClearNamedBufferData(buffer.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    std::vector<std::uint32_t> read(ones.size(), 7u);
    glGetNamedBufferSubData(buffer.id(), 0, static_cast<GLsizeiptr>(buffer.size()), read.data());
    for (std::size_t i = 0; i < read.size(); ++i) ASSERT_EQ(read[i], 0u) << "word " << i;
}
