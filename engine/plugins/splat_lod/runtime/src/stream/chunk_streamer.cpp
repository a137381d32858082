// The chunk streamer's frame (chunk_streamer.h): the steps that move data between the reader, the
// sink and the bus. What is wanted and what is evicted first is decided in stream_plan.cpp.
#include "splat_lod/stream/chunk_streamer.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "splat_lod/core/chunk_reader.h"
#include "splat_lod/core/gaussian_extent.h"
#include "splat_lod/msgs/lod_settings.h"
#include "stream_state.h"

namespace splat_lod::world {
namespace {

using plugin_msgs::StreamEvent;
using plugin_msgs::StreamEventType;

std::string part_label(std::uint32_t part, std::size_t count) {
    return count > 1 ? "part " + std::to_string(part + 1) + "/" + std::to_string(count) : std::string();
}

// A compressed chunk's Gaussians come back quantised, so one near a stream level's boundary may reach
// a level further or nearer than the one it was filed under. What the streaming decisions rely on is
// that the level's bounds in the manifest hold for each of them (world_manifest.h), which the writer
// makes sure of (chunk_writer.h): checked here instead of the stream level.
std::string check_bounds(const SplatCloud& cloud, const ReadRequest& request) {
    const ChunkLevel& bound = request.entry->levels[static_cast<std::size_t>(request.level - 1)];
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const double extent = gaussian_extent(cloud.log_scales[i], cloud.opacity_logits[i]);
        const float coverage_min = cloud.coverage_min[i];
        const bool per_coverage_holds =
            bound.extent_per_min_coverage_max < 0.0f ||
            (coverage_min > 0.0f && extent / coverage_min <= bound.extent_per_min_coverage_max);
        if (extent > bound.extent_max || !per_coverage_holds)
            return "record " + std::to_string(request.begin + i) +
                   " is outside the bounds the manifest gives stream level " + std::to_string(request.level);
    }
    return {};
}

// Every Gaussian of a level's range must have that stream level under the manifest's rule (within
// its bounds for a compressed chunk): the manifest and the file agree.
std::string check_part(const SplatCloud& cloud, const ReadRequest& request, const StreamLevelRule& rule) {
    const std::uint64_t expected = request.end - request.begin;
    if (cloud.size() != expected)
        return "records [" + std::to_string(request.begin) + ", " + std::to_string(request.end) + ") decoded to " +
               std::to_string(cloud.size()) + " Gaussians, expected " + std::to_string(expected);
    if (cloud.lod_level.size() != cloud.size()) return "the decoded Gaussians have no lod_level values";
    if (request.entry->codec == ChunkCodec::compact) return check_bounds(cloud, request);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const int level = stream_level(gaussian_reach(cloud, i, rule), rule);
        if (level != request.level)
            return "record " + std::to_string(request.begin + i) + " has stream level " + std::to_string(level) +
                   " but the manifest puts records [" + std::to_string(request.begin) + ", " +
                   std::to_string(request.end) + ") in stream level " + std::to_string(request.level);
    }
    return {};
}

}  // namespace

std::string_view to_string(DropReason reason) {
    switch (reason) {
        case DropReason::unneeded:
            return "no longer needed";
        case DropReason::memory:
            return "memory budget";
        case DropReason::outranked:
            return "outside the memory budget's plan";
        case DropReason::failure:
            return "the chunk failed";
        case DropReason::release_all:
            return "release_all";
        case DropReason::resplit:
            return "upload budget changed";
    }
    return "";
}

bool LevelSlot::active() const {
    return std::any_of(parts.begin(), parts.end(), [](const PartSlot& p) { return p.phase != PartPhase::idle; });
}
bool LevelSlot::complete() const {
    return std::all_of(parts.begin(), parts.end(), [](const PartSlot& p) { return p.phase == PartPhase::uploaded; });
}
bool LevelSlot::any_uploaded() const {
    return parts_in(PartPhase::uploaded) > 0;
}
std::size_t LevelSlot::parts_in(PartPhase phase) const {
    return static_cast<std::size_t>(
        std::count_if(parts.begin(), parts.end(), [phase](const PartSlot& p) { return p.phase == phase; }));
}

ChunkStreamer::State::State(WorldManifest world, std::filesystem::path root, StreamerSettings s, ChunkSource& src,
                            ResidencySink& snk, engine::MessageBus* message_bus)
    : manifest(std::move(world)), folder(std::move(root)), settings(s), sink(snk), bus(message_bus) {
    validate(settings);
    chunks.resize(manifest.chunks.size() + manifest.groups.size());
    for (std::size_t c = 0; c < chunks.size(); ++c) {
        ChunkSlot& slot = chunks[c];
        const bool group = c >= manifest.chunks.size();
        slot.entry = group ? &manifest.groups[c - manifest.chunks.size()] : &manifest.chunks[c];
        slot.depth = slot.entry->depth;
        slot.file = folder / slot.entry->file;
        if (std::string problem = check_chunk_entry(*slot.entry); !problem.empty()) {
            ++permanent_failures[group ? 1 : 0];
            slot.failed = slot.failure_permanent = true;
            slot.failed_level = kLevels;
            slot.failure = slot.file.string() + ": " + problem;
            continue;
        }
        layout_levels(slot);
    }
    link_groups();
    if (bus) {
        // The rule the splat pass draws with: the latest LodSettings now, and every later one from the
        // next update on.
        if (const auto lod = bus->latest<plugin_msgs::LodSettings>()) settings.rule = *(bus_rule = lod->rule);
        lod_subscription = bus->subscribe<plugin_msgs::LodSettings>([this](const plugin_msgs::LodSettings& lod) {
            StreamerSettings next = pending_settings ? *pending_settings : settings;
            next.rule = *(bus_rule = lod.rule);
            pending_settings = next;
        });
    }
    report.budget_bytes = settings.memory_budget_bytes;
    // Decoded parts are checked on the reader's thread, off the frame.
    reader = std::make_unique<StreamReader>(
        src, settings.background_thread ? StreamReader::Mode::background_thread : StreamReader::Mode::synchronous,
        [rule = manifest.stream_levels](const SplatCloud& cloud, const ReadRequest& request) {
            return check_part(cloud, request, rule);
        });
}

// Splits each inactive level into parts of at most one frame's upload budget.
void ChunkStreamer::State::layout_levels(ChunkSlot& slot) const {
    const std::uint64_t max_part =
        max_gaussians_within(settings.upload_budget_bytes_per_frame, settings.gpu_sh_degree, settings.gpu_pages);
    for (int l = 1; l <= kLevels; ++l) {
        LevelSlot& s = slot.level(l);
        if (s.active()) continue;
        std::tie(s.begin, s.end) = level_range(*slot.entry, l);
        s.planned_bytes = 0;  // each part is stored in its own pages
        s.parts.clear();
        for (std::uint64_t first = 0; first < s.end - s.begin; first += max_part) {
            s.parts.push_back({PartPhase::idle, first, std::min(max_part, s.end - s.begin - first), nullptr, 0});
            s.planned_bytes += gpu_bytes(s.parts.back().count, settings.gpu_sh_degree, settings.gpu_pages);
        }
    }
}

void ChunkStreamer::State::apply_pending_settings() {
    if (!pending_settings) return;
    const bool resplit = pending_settings->upload_budget_bytes_per_frame != settings.upload_budget_bytes_per_frame;
    settings = *std::exchange(pending_settings, std::nullopt);
    report.budget_bytes = settings.memory_budget_bytes;
    if (!resplit) return;
    const std::uint64_t max_part =
        max_gaussians_within(settings.upload_budget_bytes_per_frame, settings.gpu_sh_degree, settings.gpu_pages);
    for (std::size_t c = 0; c < chunks.size(); ++c) {
        ChunkSlot& slot = chunks[c];
        if (slot.failure_permanent) continue;
        // A level still loading with parts too large for the new budget starts again.
        for (int l = kLevels; l >= 1; --l) {
            const LevelSlot& s = slot.level(l);
            const bool too_large = std::any_of(s.parts.begin(), s.parts.end(), [&](const PartSlot& p) {
                return p.phase != PartPhase::uploaded && p.count > max_part;
            });
            if (s.active() && too_large) {
                drop_levels(c, l, DropReason::resplit);
                break;
            }
        }
        layout_levels(slot);
    }
}

void ChunkStreamer::State::report_construction_failures() {
    if (std::exchange(permanent_failures_reported, true)) return;
    if (permanent_failures[0] + permanent_failures[1] == 0) return;
    for (const ChunkSlot& slot : chunks) {
        if (!slot.failure_permanent) continue;
        ++stats.failures;
        engine::log_warning("splat_lod: chunk " + slot.entry->id + " skipped: " + slot.failure);
        emit({slot.entry->id, StreamEventType::failed, 0, 0, slot.failure});
    }
}

void ChunkStreamer::State::emit(StreamEvent event) {
    events.push_back(event);
    if (bus) bus->publish(events.back());
}

void ChunkStreamer::State::drop_levels(std::size_t chunk, int level, DropReason reason) {
    ChunkSlot& slot = chunks[chunk];
    for (int l = 1; l <= level; ++l) {
        LevelSlot& s = slot.level(l);
        if (!s.active()) continue;
        const bool uploaded = s.any_uploaded();
        ++s.generation;
        reader->cancel(chunk, l);
        for (PartSlot& part : s.parts) {
            part.phase = PartPhase::idle;
            part.gaussians.reset();
            part.bytes = 0;
        }
        const std::uint64_t freed = std::exchange(s.resident_bytes, 0);
        resident -= freed;
        s.frames_outside_keep = 0;
        if (!uploaded) continue;
        sink.release(slot.entry->id, l);
        if (reason == DropReason::memory) ++stats.levels_evicted_for_memory;
        if (reason == DropReason::unneeded) ++stats.levels_released_unneeded;
        emit({slot.entry->id, StreamEventType::evicted, l, freed, std::string(to_string(reason))});
    }
}

void ChunkStreamer::State::fail_chunk(std::size_t chunk, int level, const std::string& problem) {
    ChunkSlot& slot = chunks[chunk];
    const std::string file = slot.file.string();
    slot.failure = problem.find(file) == std::string::npos ? file + ": " + problem : problem;
    slot.failed = true;
    slot.failed_level = std::max(slot.failed_level, level);
    slot.failed_frame = frame;
    drop_levels(chunk, slot.failed_level, DropReason::failure);
    ++stats.failures;
    engine::log_warning("splat_lod: chunk " + slot.entry->id + " level " + std::to_string(level) +
                        " failed and is skipped: " + slot.failure);
    emit({slot.entry->id, StreamEventType::failed, level, 0, slot.failure});
}

void ChunkStreamer::State::release_unwanted() {
    for (const std::size_t c : work) {
        ChunkSlot& slot = chunks[c];
        if (slot.failure_permanent) continue;
        for (int l = 1; l <= kLevels; ++l) {
            const LevelSlot& s = slot.level(l);
            if (!s.active()) continue;
            if (!s.wanted)
                drop_levels(c, l, DropReason::unneeded);
            else if (!s.target && !s.complete())
                drop_levels(c, l, DropReason::outranked);
        }
    }
}

void ChunkStreamer::State::collect_reads() {
    for (ReadResult& result : reader->take_finished()) {
        const ReadRequest& request = result.request;
        LevelSlot& s = chunks[request.chunk].level(request.level);
        if (request.generation != s.generation || request.part >= s.parts.size() ||
            s.parts[request.part].phase != PartPhase::requested) {
            ++stats.reads_discarded;
            continue;
        }
        if (!result.error.empty()) {
            fail_chunk(request.chunk, request.level, result.error);
            continue;
        }
        PartSlot& part = s.parts[request.part];
        part.phase = PartPhase::loaded;
        part.bytes = gpu_bytes(result.gaussians->size(), settings.gpu_sh_degree, settings.gpu_pages);
        part.gaussians = std::move(result.gaussians);
        const ChunkEntry& entry = *chunks[request.chunk].entry;
        emit({entry.id, StreamEventType::loaded, request.level, entry.disk_bytes(part.count),
              part_label(request.part, s.parts.size())});
    }
}

void ChunkStreamer::State::upload_loaded() {
    frame_uploaded = 0;
    for (const PlannedLevel& p : order) {
        ChunkSlot& slot = chunks[p.chunk];
        LevelSlot& s = slot.level(p.level);
        if (!s.target || slot.blocked(p.level)) continue;
        bool coarser_complete = true;
        for (int l = p.level + 1; l <= kLevels; ++l) coarser_complete = coarser_complete && slot.level(l).complete();
        if (!coarser_complete) continue;
        for (std::uint32_t i = 0; i < s.parts.size(); ++i) {
            PartSlot& part = s.parts[i];
            if (part.phase == PartPhase::uploaded) continue;
            if (part.phase != PartPhase::loaded) break;
            // Strict priority: the first part that does not fit ends this frame's uploads.
            if (frame_uploaded + part.bytes > settings.upload_budget_bytes_per_frame) return;
            if (!make_room(part.bytes)) return;
            const LevelPart upload{slot.entry->id,
                                   p.level,
                                   i,
                                   static_cast<std::uint32_t>(s.parts.size()),
                                   part.first,
                                   s.end - s.begin,
                                   part.gaussians,
                                   part.bytes,
                                   slot.shown,
                                   part_opacity(slot, p.level)};
            try {
                sink.upload(upload);
            } catch (const std::exception& e) {
                fail_chunk(p.chunk, p.level, std::string("upload failed: ") + e.what());
                break;
            }
            part.phase = PartPhase::uploaded;
            part.gaussians.reset();
            s.resident_bytes += part.bytes;
            resident += part.bytes;
            frame_uploaded += part.bytes;
            stats.uploaded_bytes_total += part.bytes;
            stats.peak_resident_bytes = std::max(stats.peak_resident_bytes, resident);
            emit({slot.entry->id, StreamEventType::uploaded, p.level, part.bytes, part_label(i, s.parts.size())});
        }
    }
}

void ChunkStreamer::State::request_reads() {
    std::size_t in_flight = 0;
    for (const std::size_t c : work)
        for (const LevelSlot& s : chunks[c].levels)
            in_flight += s.parts_in(PartPhase::requested) + s.parts_in(PartPhase::loaded);
    const auto limit = static_cast<std::size_t>(settings.max_requests_in_flight);
    for (const PlannedLevel& p : order) {
        if (in_flight >= limit) return;
        ChunkSlot& slot = chunks[p.chunk];
        LevelSlot& s = slot.level(p.level);
        if (!s.target || slot.blocked(p.level)) continue;
        // Coarse before fine: every coarser level is loaded or on its way (or empty).
        bool coarser_on_way = true;
        for (int l = p.level + 1; l <= kLevels; ++l)
            coarser_on_way = coarser_on_way && (slot.level(l).active() || slot.level(l).parts.empty());
        if (!coarser_on_way) continue;
        for (std::uint32_t i = 0; i < s.parts.size() && in_flight < limit; ++i) {
            PartSlot& part = s.parts[i];
            if (part.phase != PartPhase::idle) continue;
            reader->submit({p.chunk, p.level, i, s.generation, slot.entry, slot.file, s.begin + part.first,
                            s.begin + part.first + part.count});
            part.phase = PartPhase::requested;
            ++in_flight;
            ++stats.reads_requested;
            emit({slot.entry->id, StreamEventType::requested, p.level, slot.entry->disk_bytes(part.count),
                  part_label(i, s.parts.size())});
        }
    }
}

void ChunkStreamer::State::publish_report(std::uint64_t frame_index) {
    plugin_msgs::ResidencyReport r;
    r.frame_index = frame_index;
    r.resident_bytes = resident;
    r.budget_bytes = settings.memory_budget_bytes;
    r.chunks.failed = permanent_failures[0];
    r.groups.failed = permanent_failures[1];
    for (const std::size_t c : work) {  // nothing else is requested, loaded, resident or drawn
        const ChunkSlot& slot = chunks[c];
        std::size_t requested = 0, loaded = 0;
        for (const LevelSlot& s : slot.levels) {
            requested += s.parts_in(PartPhase::requested);
            loaded += s.parts_in(PartPhase::loaded);
        }
        const LevelSlot& coarse = slot.level(kLevels);
        plugin_msgs::ChunkStateCounts& counts = slot.depth == 0 ? r.chunks : r.groups;
        counts.requested += requested > 0 ? 1u : 0u;
        counts.loaded += loaded > 0 ? 1u : 0u;
        counts.resident += !coarse.parts.empty() && coarse.complete() ? 1u : 0u;
        counts.failed += slot.failed && !slot.failure_permanent ? 1u : 0u;
        (slot.depth == 0 ? r.drawn_chunks : r.drawn_groups) += slot.drawn ? 1u : 0u;
    }
    report = r;
    if (bus) bus->publish(report);
}

ChunkStreamer::ChunkStreamer(WorldManifest manifest, std::filesystem::path folder, StreamerSettings settings,
                             ChunkSource& source, ResidencySink& sink, engine::MessageBus* bus)
    : state_(std::make_unique<State>(std::move(manifest), std::move(folder), settings, source, sink, bus)) {}

ChunkStreamer::~ChunkStreamer() = default;

void ChunkStreamer::update(const StreamView& view) {
    State& s = *state_;
    check_view(view);
    s.frame = view.frame_index;
    s.events.clear();
    s.apply_pending_settings();
    s.report_construction_failures();
    s.retry_failed();
    s.group_cell_scale = view.cut_scale;
    s.plan(view);
    s.release_unwanted();
    s.collect_reads();
    s.enforce_memory_budget();
    s.upload_loaded();
    s.decide_drawn();
    s.advance_fades();
    s.request_reads();
    ++s.stats.updates;
    s.stats.nodes_last_update = s.work.size();
    s.stats.uploaded_bytes_last_update = s.frame_uploaded;
    s.stats.max_uploaded_bytes_per_update = std::max(s.stats.max_uploaded_bytes_per_update, s.frame_uploaded);
    s.publish_report(view.frame_index);
    s.keep_live();
}

void ChunkStreamer::wait_idle() {
    state_->reader->wait_idle();
}

void ChunkStreamer::release_all() {
    State& s = *state_;
    s.events.clear();
    for (std::size_t c = 0; c < s.chunks.size(); ++c) s.drop_levels(c, kLevels, DropReason::release_all);
    for (ChunkSlot& slot : s.chunks) {
        slot.drawn = slot.shown = false;
        slot.fade = 0.0f;
    }
}

void ChunkStreamer::set_settings(const StreamerSettings& settings) {
    validate(settings);
    if (settings.gpu_sh_degree != state_->settings.gpu_sh_degree)
        engine::fail("splat_lod::world::ChunkStreamer::set_settings(): gpu_sh_degree cannot change while streaming");
    if (settings.gpu_pages.page_gaussians != state_->settings.gpu_pages.page_gaussians ||
        settings.gpu_pages.page_overhead_bytes != state_->settings.gpu_pages.page_overhead_bytes ||
        settings.gpu_pages.storage != state_->settings.gpu_pages.storage)
        engine::fail("splat_lod::world::ChunkStreamer::set_settings(): gpu_pages cannot change while streaming");
    state_->pending_settings = settings;
    if (state_->bus_rule) state_->pending_settings->rule = *state_->bus_rule;  // the splat pass's, not a copy
}

const StreamerSettings& ChunkStreamer::settings() const {
    return state_->pending_settings ? *state_->pending_settings : state_->settings;
}
std::uint64_t ChunkStreamer::resident_bytes() const {
    return state_->resident;
}
std::size_t ChunkStreamer::chunk_count() const {
    return state_->manifest.chunks.size();
}
std::size_t ChunkStreamer::group_count() const {
    return state_->manifest.groups.size();
}
float ChunkStreamer::group_cell_scale() const {
    return state_->group_cell_scale;
}
const plugin_msgs::ResidencyReport& ChunkStreamer::residency() const {
    return state_->report;
}
const std::vector<plugin_msgs::StreamEvent>& ChunkStreamer::last_events() const {
    return state_->events;
}
const StreamerStats& ChunkStreamer::stats() const {
    return state_->stats;
}

std::optional<std::size_t> ChunkStreamer::find_chunk(std::string_view id) const {
    const auto& chunks = state_->chunks;
    const auto it = std::find_if(chunks.begin(), chunks.end(), [&](const ChunkSlot& e) { return e.entry->id == id; });
    if (it == chunks.end()) return std::nullopt;
    return static_cast<std::size_t>(it - chunks.begin());
}

ChunkStatus ChunkStreamer::chunk_status(std::size_t index) const {
    const ChunkSlot& slot = state_->chunks.at(index);
    ChunkStatus status;
    status.id = slot.entry->id;
    status.distance = nearest_distance(*slot.entry, state_->eye);  // also for a node the update did not look at
    status.finest_needed_level = slot.finest_needed;
    status.failed = slot.failed;
    status.failure = slot.failure;
    status.depth = slot.depth;
    status.in_cut = slot.in_cut;
    status.drawn = slot.drawn;
    bool prefix_resident = true;
    for (int l = kLevels; l >= 1; --l) {
        const LevelSlot& s = slot.level(l);
        LevelState& state = status.levels[static_cast<std::size_t>(l - 1)];
        if (!slot.failure_permanent && s.complete())
            state = LevelState::resident;
        else if (s.any_uploaded())
            state = LevelState::partial;
        else if (s.parts_in(PartPhase::loaded) > 0)
            state = LevelState::loaded;
        else if (s.parts_in(PartPhase::requested) > 0)
            state = LevelState::requested;
        else
            state = LevelState::absent;
        status.resident_bytes += s.resident_bytes;
        prefix_resident = prefix_resident && state == LevelState::resident;
        if (prefix_resident) status.finest_resident_level = l;
    }
    return status;
}

}  // namespace splat_lod::world
