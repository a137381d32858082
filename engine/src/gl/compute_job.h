#pragma once
// What the engine's GPU jobs (radix_sort.cpp, prefix_scan.cpp) share: setting a uint uniform, checking
// a caller's count word, and the first step of each job, a one-invocation program that turns the
// count on the GPU into the job's indirect dispatch arguments.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/core/error.h"
#include "engine/gl/objects.h"
#include "engine/gl/shader_library.h"

namespace engine::gl::detail {

inline void set_uint(const Program& program, const char* name, std::uint32_t value) {
    glProgramUniform1ui(program.id(), glGetUniformLocation(program.id(), name), value);
}

// Throws "<prefix><what> offset N is not a 4-byte-aligned word inside its buffer of M bytes" unless
// `offset` addresses a whole uint inside `buffer`.
inline void check_word(const Buffer& buffer, std::size_t offset, const std::string& prefix, const char* what) {
    if (!buffer || offset % 4 != 0 || offset + 4 > buffer.size())
        engine::fail(prefix + what + " offset " + std::to_string(offset) +
                     " is not a 4-byte-aligned word inside its buffer of " + std::to_string(buffer.size()) + " bytes");
}

// Runs `program` (reads u_count_index, u_max_count) with the count word's buffer at `count_binding` and
// the job's argument buffer at `arguments_binding`, then makes its writes visible to shaders and to
// indirect dispatches.
inline void record_dispatch_arguments(const Program& program, const Buffer& count_buffer, std::size_t count_offset,
                                      std::uint32_t max_count, GLuint count_binding, const Buffer& arguments,
                                      GLuint arguments_binding) {
    glUseProgram(program.id());
    set_uint(program, "u_count_index", static_cast<std::uint32_t>(count_offset / 4));
    set_uint(program, "u_max_count", max_count);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, count_binding, count_buffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, arguments_binding, arguments.id());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

}  // namespace engine::gl::detail
