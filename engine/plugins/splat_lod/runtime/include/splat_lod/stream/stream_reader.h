#pragma once
// The chunk streamer's reader: a queue of range reads served by one background thread (or, for
// tests and tools, run inside take_finished() on the caller's thread), results handed back in
// completion order. It knows nothing about levels' meaning or budgets; the streamer does.
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "splat_lod/stream/stream_interfaces.h"

namespace splat_lod::world {

struct ReadRequest {
    std::size_t chunk = 0;  // index into the manifest's chunks
    int level = 4;
    std::uint32_t part = 0;
    std::uint64_t generation = 0;       // the streamer's per-level counter, to recognise stale results
    const ChunkEntry* entry = nullptr;  // owned by the streamer, alive as long as the reader
    std::filesystem::path file;         // manifest folder / entry->file
    std::uint64_t begin = 0, end = 0;   // Gaussians [begin, end) of the file
};

struct ReadResult {
    ReadRequest request;
    std::shared_ptr<SplatCloud> gaussians;  // null on failure
    std::string error;                      // the source's message on failure
};

class StreamReader {
public:
    enum class Mode { background_thread, synchronous };

    // `check` (may be empty) runs on the reader's thread after each successful read and returns what
    // is wrong with the decoded Gaussians, or an empty string; a problem becomes the result's error.
    using Check = std::function<std::string(const SplatCloud&, const ReadRequest&)>;
    StreamReader(ChunkSource& source, Mode mode, Check check = {});
    // Drops the queued reads, lets the one in progress finish, joins the thread.
    ~StreamReader();
    StreamReader(const StreamReader&) = delete;
    StreamReader& operator=(const StreamReader&) = delete;

    void submit(ReadRequest request);
    // Drops the queued (not yet started) reads of that level; returns how many. A read already in
    // progress still delivers its result, which the caller recognises by its generation.
    std::size_t cancel(std::size_t chunk, int level);
    // The reads finished since the last call. In synchronous mode, runs every queued read first.
    std::vector<ReadResult> take_finished();
    // Blocks until nothing is queued or being read (returns at once in synchronous mode).
    void wait_idle();

private:
    void run();
    ReadResult execute(const ReadRequest& request);

    ChunkSource& source_;
    Mode mode_;
    Check check_;
    std::mutex mutex_;
    std::condition_variable wake_;  // work queued or stop requested
    std::condition_variable idle_;  // the queue ran empty and nothing is being read
    std::deque<ReadRequest> queue_;
    std::vector<ReadResult> finished_;
    bool busy_ = false;
    bool stop_ = false;
    std::thread thread_;  // last: started after every other member exists
};

}  // namespace splat_lod::world
