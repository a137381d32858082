// The background reader of the chunk streamer (stream_reader.h) and the file-backed source.
#include "splat_lod/stream/stream_reader.h"

#include <algorithm>
#include <exception>
#include <utility>

#include "splat_lod/core/chunk_reader.h"

namespace splat_lod::world {

SplatCloud FileChunkSource::read(const std::filesystem::path& file, const ChunkEntry& chunk, std::uint64_t begin,
                                 std::uint64_t end) {
    return read_chunk_range(file, chunk, begin, end);
}

StreamReader::StreamReader(ChunkSource& source, Mode mode, Check check)
    : source_(source), mode_(mode), check_(std::move(check)) {
    if (mode_ == Mode::background_thread) thread_ = std::thread([this] { run(); });
}

StreamReader::~StreamReader() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
        queue_.clear();
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
}

void StreamReader::submit(ReadRequest request) {
    {
        std::lock_guard lock(mutex_);
        queue_.push_back(std::move(request));
    }
    wake_.notify_one();
}

std::size_t StreamReader::cancel(std::size_t chunk, int level) {
    std::lock_guard lock(mutex_);
    const auto removed =
        std::erase_if(queue_, [&](const ReadRequest& r) { return r.chunk == chunk && r.level == level; });
    if (queue_.empty() && !busy_) idle_.notify_all();
    return removed;
}

std::vector<ReadResult> StreamReader::take_finished() {
    if (mode_ == Mode::synchronous) {
        std::deque<ReadRequest> queued;
        {
            std::lock_guard lock(mutex_);
            queued.swap(queue_);
        }
        for (const ReadRequest& request : queued) {
            ReadResult result = execute(request);
            std::lock_guard lock(mutex_);
            finished_.push_back(std::move(result));
        }
    }
    std::lock_guard lock(mutex_);
    return std::exchange(finished_, {});
}

void StreamReader::wait_idle() {
    if (mode_ == Mode::synchronous) return;
    std::unique_lock lock(mutex_);
    idle_.wait(lock, [this] { return stop_ || (queue_.empty() && !busy_); });
}

void StreamReader::run() {
    std::unique_lock lock(mutex_);
    for (;;) {
        wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
        if (stop_) break;
        ReadRequest request = std::move(queue_.front());
        queue_.pop_front();
        busy_ = true;
        lock.unlock();
        ReadResult result = execute(request);
        lock.lock();
        busy_ = false;
        if (!stop_) finished_.push_back(std::move(result));
        if (queue_.empty()) idle_.notify_all();
    }
    busy_ = false;
    idle_.notify_all();
}

ReadResult StreamReader::execute(const ReadRequest& request) {
    ReadResult result;
    result.request = request;
    try {
        result.gaussians =
            std::make_shared<SplatCloud>(source_.read(request.file, *request.entry, request.begin, request.end));
        if (check_) result.error = check_(*result.gaussians, request);
        if (!result.error.empty()) result.gaussians.reset();
    } catch (const std::exception& e) {
        result.error = e.what();
    } catch (...) {
        result.error = "unknown error (not a std::exception)";
    }
    return result;
}

}  // namespace splat_lod::world
