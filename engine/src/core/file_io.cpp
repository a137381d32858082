#include "engine/core/file_io.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cstring>
#include <fstream>
#include <system_error>
#include <utility>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include "engine/core/error.h"

namespace engine {
namespace {

namespace fs = std::filesystem;

constexpr const char* kTemporaryInfix = ".tmp-";

std::string reason() {
    return std::strerror(errno);
}

// Numbers the temporaries of this process: threads may write files of one folder at once.
std::atomic<std::uint64_t> temporary_serial{0};

// Closes the descriptor on scope exit; the writer closes explicitly (release) to check the result.
class Descriptor {
public:
    explicit Descriptor(int fd) : fd_(fd) {}
    ~Descriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    int get() const { return fd_; }
    int release() { return std::exchange(fd_, -1); }

private:
    int fd_;
};

fs::path folder_of(const fs::path& path) {
    return path.parent_path().empty() ? fs::path(".") : path.parent_path();
}

// Creates `folder` and its missing parents, syncing each parent after a folder was made in it: a
// file synced later into the new folder is then reachable after a power loss too.
void create_folders(const fs::path& folder) {
    std::error_code ec;
    if (folder.empty() || fs::is_directory(folder, ec)) return;
    if (folder.has_parent_path() && folder.parent_path() != folder) create_folders(folder.parent_path());
    if (::mkdir(folder.c_str(), 0777) != 0 && errno != EEXIST)
        fail(folder.string() + ": cannot create folder: " + reason());
    if (!fs::is_directory(folder, ec)) fail(folder.string() + ": cannot create folder: a file of that name exists");
    sync_folder(folder_of(folder));  // also when another thread made it first: it may not have synced yet
}

// A new temporary beside `path`, opened exclusively (O_EXCL): a leftover of an earlier process that
// had the same pid is never written into, another writer's file never shared.
std::pair<fs::path, int> create_temporary(const fs::path& path) {
    for (int attempt = 0; attempt < 1000; ++attempt) {
        fs::path temporary = path;
        temporary += kTemporaryInfix + std::to_string(::getpid()) + "-" + std::to_string(temporary_serial.fetch_add(1));
        const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) return {temporary, fd};
        if (errno != EEXIST) fail(temporary.string() + ": cannot create: " + reason());
    }
    fail(path.string() + ": cannot create a temporary file beside it: every name tried exists");
}

void write_all(int fd, const fs::path& file, std::span<const std::uint8_t> bytes) {
    std::size_t done = 0;
    while (done < bytes.size()) {
        const std::size_t part = std::min<std::size_t>(bytes.size() - done, std::size_t{1} << 30);
        const ssize_t written = ::write(fd, bytes.data() + done, part);
        if (written < 0 && errno == EINTR) continue;
        if (written <= 0) fail(file.string() + ": write failed at byte " + std::to_string(done) + ": " + reason());
        done += static_cast<std::size_t>(written);
    }
}

// The writer's pid in a temporary's name, "<file>.tmp-<pid>-<n>" (or "<file>.tmp-<pid>", the
// form of earlier versions); 0 when `name` is not a temporary of the file `prefix` names.
pid_t temporary_writer(const std::string& name, const std::string& prefix) {
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return 0;
    const char* const last = name.data() + name.size();
    long long pid = 0;
    const auto [end, error] = std::from_chars(name.data() + prefix.size(), last, pid);
    if (error != std::errc() || pid <= 0 || pid > INT_MAX) return 0;
    if (end != last) {
        unsigned long long serial = 0;
        if (*end != '-') return 0;
        const auto [serial_end, serial_error] = std::from_chars(end + 1, last, serial);
        if (serial_error != std::errc() || serial_end != last) return 0;
    }
    return static_cast<pid_t>(pid);
}

}  // namespace

std::vector<std::uint8_t> read_binary_file(const std::filesystem::path& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) fail(path.string() + ": is a directory, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path.string() + ": cannot open: " + reason());
    in.seekg(0, std::ios::end);
    const auto size = static_cast<std::size_t>(in.tellg());
    in.seekg(0, std::ios::beg);
    std::vector<std::uint8_t> bytes(size);
    if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
        fail(path.string() + ": read failed: " + reason());
    return bytes;
}

std::string read_text_file(const std::filesystem::path& path) {
    const auto bytes = read_binary_file(path);
    return std::string(bytes.begin(), bytes.end());
}

void sync_folder(const std::filesystem::path& folder) {
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) fail(folder.string() + ": cannot open the folder to sync it: " + reason());
    const Descriptor descriptor(fd);
    // EINVAL: the file system has no folder sync (and nothing to lose by it).
    if (::fsync(fd) != 0 && errno != EINVAL) fail(folder.string() + ": cannot sync the folder: " + reason());
}

void write_file_atomic(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
    if (path.has_parent_path()) create_folders(path.parent_path());
    struct stat previous {};
    const bool replacing = ::stat(path.c_str(), &previous) == 0 && S_ISREG(previous.st_mode);
    auto [temporary, fd] = create_temporary(path);
    Descriptor file(fd);
    try {
        // The replaced file's permission bits, not its set-id or sticky bits (these are data files).
        if (replacing && ::fchmod(file.get(), previous.st_mode & 0777) != 0)
            fail(temporary.string() + ": cannot set the permissions of " + path.string() + ": " + reason());
        write_all(file.get(), temporary, bytes);
        // The data must be on disk before the rename makes it the file: otherwise a power loss
        // could leave `path` renamed but empty (delayed allocation).
        if (::fsync(file.get()) != 0) fail(temporary.string() + ": cannot sync to disk: " + reason());
        if (::close(file.release()) != 0) fail(temporary.string() + ": write failed on close: " + reason());
        if (::rename(temporary.c_str(), path.c_str()) != 0) fail(path.string() + ": cannot replace: " + reason());
    } catch (...) {
        ::unlink(temporary.c_str());
        throw;
    }
    sync_folder(folder_of(path));  // the rename itself
}

void write_text_file_atomic(const std::filesystem::path& path, const std::string& text) {
    write_file_atomic(path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

std::size_t remove_stale_temporaries(const std::filesystem::path& path) {
    const std::string prefix = path.filename().string() + kTemporaryInfix;
    std::size_t removed = 0;
    std::error_code ec;
    for (fs::directory_iterator it(folder_of(path), ec), end; !ec && it != end; it.increment(ec)) {
        const pid_t writer = temporary_writer(it->path().filename().string(), prefix);
        // kill(pid, 0) fails with ESRCH only when no such process exists (EPERM: it runs as
        // another user). A killed writer that its parent has not reaped yet still counts as running.
        if (writer == 0 || ::kill(writer, 0) == 0 || errno != ESRCH) continue;
        std::error_code remove_error;
        if (it->is_regular_file(remove_error) && fs::remove(it->path(), remove_error)) ++removed;
    }
    return removed;
}

}  // namespace engine
