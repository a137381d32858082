#pragma once
// Whole-file reads and crash-safe writes. Errors name the file and the reason.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace engine {

std::vector<std::uint8_t> read_binary_file(const std::filesystem::path& path);
std::string read_text_file(const std::filesystem::path& path);

// Replaces `path` with `bytes` so that, whatever happens, `path` holds either its previous content
// or all of the new one:
//   1. missing folders are created, each parent synced after a child is made;
//   2. the bytes go to a new temporary "<path>.tmp-<pid>-<n>" in the same folder (created
//      exclusively: never an existing file), with the permission bits of the file it replaces
//      (a new file gets 0666 less the umask); ownership is the writer's;
//   3. the temporary is synced (fsync) and renamed over `path`, then the folder is synced, so the
//      new file survives a power loss once this returns, not only a kill.
// On any error the temporary is removed and engine::Error names the file and the reason. A kill
// (SIGKILL, power loss) before the rename leaves the temporary behind: remove_stale_temporaries.
// A symbolic link at `path` is replaced by the file (its target is left alone).
void write_file_atomic(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
void write_text_file_atomic(const std::filesystem::path& path, const std::string& text);

// Removes the temporaries that write_file_atomic left for `path` in runs that were killed: those
// whose writing process no longer runs on this machine (a live process's temporary is kept, it may
// still be writing). Returns how many were removed; errors are ignored (a leftover only costs space).
std::size_t remove_stale_temporaries(const std::filesystem::path& path);

// fsync of a folder: makes the creation, renaming or removal of its entries durable. Throws
// engine::Error naming the folder when it cannot be opened or synced.
void sync_folder(const std::filesystem::path& folder);

}  // namespace engine
