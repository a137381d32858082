#pragma once
// Who may use a world's folder at a time. The world generator writes and removes files there only
// while it holds an exclusive flock() on the folder; a program streaming the world holds a shared
// one for as long as it streams. So a regeneration can never remove the files under a running game
// (it fails at once, saying a program is streaming the world), a game never starts on a world that
// is being rewritten, and two generators never write into one folder. The kernel releases a lock
// when its process exits or dies, so a killed program never leaves a folder locked. Any number of
// programs may stream one world together. (Advisory: programs that do not take the lock are not
// stopped.)
#include <filesystem>
#include <string>

namespace splat_lod::world {

class WorldFolderLock {
public:
    enum class Mode { stream, write };

    // Tries once, without waiting: held() says whether the lock was taken, problem() why not.
    WorldFolderLock(const std::filesystem::path& folder, Mode mode);
    ~WorldFolderLock();  // releases the lock
    WorldFolderLock(const WorldFolderLock&) = delete;
    WorldFolderLock& operator=(const WorldFolderLock&) = delete;

    bool held() const { return fd_ >= 0; }
    const std::string& problem() const { return problem_; }
    // Throws engine::Error "<folder>: <problem>" unless the lock is held.
    void require() const;

private:
    std::filesystem::path folder_;
    int fd_ = -1;
    std::string problem_;
};

}  // namespace splat_lod::world
