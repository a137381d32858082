// The RAII wrappers' type traits are checked without a GL context.
#include <type_traits>

#include <gtest/gtest.h>

#include "engine/gl/objects.h"

namespace gl = engine::gl;

template <class T>
constexpr bool move_only = !std::is_copy_constructible_v<T> && !std::is_copy_assignable_v<T> &&
                           std::is_nothrow_move_constructible_v<T> && std::is_nothrow_move_assignable_v<T>;

static_assert(move_only<gl::Buffer>);
static_assert(move_only<gl::Texture>);
static_assert(move_only<gl::Framebuffer>);
static_assert(move_only<gl::Program>);
static_assert(move_only<gl::VertexArray>);
static_assert(move_only<gl::Query>);
static_assert(move_only<gl::Fence>);

TEST(GlObjects, NoCreateObjectsAreEmptyAndMoveWithoutAContext) {
    gl::Buffer a{gl::NoCreate};
    EXPECT_FALSE(a);
    EXPECT_EQ(a.id(), 0u);
    gl::Buffer b = std::move(a);
    EXPECT_EQ(b.id(), 0u);
    EXPECT_EQ(b.release(), 0u);
    gl::Texture t{gl::NoCreate};
    EXPECT_FALSE(t);
    gl::Fence f;
    EXPECT_FALSE(f.pending());
    EXPECT_TRUE(f.signalled());
}
