// The world folder's lock (world_lock.h): flock() on the folder itself.
#include "splat_lod/core/world_lock.h"

#include <cerrno>
#include <cstring>
#include <utility>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "engine/core/error.h"

namespace splat_lod::world {

WorldFolderLock::WorldFolderLock(const std::filesystem::path& folder, Mode mode)
    : folder_(folder), fd_(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ < 0) {
        problem_ = "cannot open the world's folder: " + std::string(std::strerror(errno));
        return;
    }
    if (::flock(fd_, (mode == Mode::write ? LOCK_EX : LOCK_SH) | LOCK_NB) == 0) return;
    const int error = errno;
    if (error != EWOULDBLOCK) {
        problem_ = "cannot lock the world's folder: " + std::string(std::strerror(error));
    } else if (mode == Mode::stream) {
        problem_ =
            "the world generator is writing into this folder (it holds the folder's lock); wait for it "
            "to finish";
    } else if (::flock(fd_, LOCK_SH | LOCK_NB) == 0) {
        // Only readers hold it: a program is streaming the world.
        problem_ =
            "a program is streaming this world (it holds the folder's shared lock); close it, or generate "
            "into another folder";
    } else {
        problem_ =
            "another run of the world generator is writing into this folder (it holds the folder's lock); "
            "wait for it or choose another folder";
    }
    ::close(std::exchange(fd_, -1));  // also drops the probing shared lock
}

WorldFolderLock::~WorldFolderLock() {
    if (fd_ >= 0) ::close(fd_);
}

void WorldFolderLock::require() const {
    if (!held()) engine::fail(folder_.string() + ": " + problem_);
}

}  // namespace splat_lod::world
