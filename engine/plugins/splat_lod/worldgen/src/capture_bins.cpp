// Chunk bins on disk and the far layer of a capture import (capture_bins.h).
#include "capture_bins.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <numeric>
#include <string>
#include <system_error>

#include "engine/core/error.h"
#include "splat_lod/core/world_manifest.h"

namespace splat_lod::world {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kFixedFloats = 14;  // position 3, rotation 4, log-scale 3, opacity 1, DC 3

}  // namespace

void append_gaussian(SplatCloud& to, const SplatCloud& from, std::size_t i) {
    to.positions.push_back(from.positions[i]);
    to.rotations.push_back(from.rotations[i]);
    to.log_scales.push_back(from.log_scales[i]);
    to.opacity_logits.push_back(from.opacity_logits[i]);
    to.sh_dc.push_back(from.sh_dc[i]);
    const std::size_t stride = from.sh_rest_stride();
    to.sh_rest.insert(to.sh_rest.end(), from.sh_rest.begin() + static_cast<std::ptrdiff_t>(i * stride),
                      from.sh_rest.begin() + static_cast<std::ptrdiff_t>((i + 1) * stride));
    to.lod_level.push_back(1);
    to.coverage_min.push_back(-1.0f);
    to.coverage_max.push_back(-1.0f);
}

ChunkBins::ChunkBins(fs::path folder, int sh_degree, std::uint64_t flush_bytes)
    : folder_(std::move(folder)), sh_degree_(sh_degree), flush_bytes_(std::max<std::uint64_t>(flush_bytes, 1)) {
    std::error_code ec;
    fs::create_directories(folder_, ec);
    if (ec) engine::fail(folder_.string() + ": cannot create the chunk bins' folder: " + ec.message());
}

std::size_t ChunkBins::floats_per_gaussian() const {
    return kFixedFloats + static_cast<std::size_t>(3 * sh_rest_coeffs(sh_degree_));
}

fs::path ChunkBins::file(const glm::ivec2& cell) const {
    return folder_ / (chunk_id(cell) + ".bin");
}

void ChunkBins::add(const glm::ivec2& cell, const SplatCloud& cloud, std::size_t i) {
    std::vector<float>& out = buffers_[{cell.y, cell.x}];
    const glm::vec3& p = cloud.positions[i];
    const Rotation& q = cloud.rotations[i];
    const glm::vec3& s = cloud.log_scales[i];
    const glm::vec3& c = cloud.sh_dc[i];
    out.insert(out.end(), {p.x, p.y, p.z, q.w, q.x, q.y, q.z, s.x, s.y, s.z, cloud.opacity_logits[i], c.x, c.y, c.z});
    const std::size_t stride = cloud.sh_rest_stride();
    out.insert(out.end(), cloud.sh_rest.begin() + static_cast<std::ptrdiff_t>(i * stride),
               cloud.sh_rest.begin() + static_cast<std::ptrdiff_t>((i + 1) * stride));
    ++counts_[{cell.y, cell.x}];
    buffered_bytes_ += floats_per_gaussian() * sizeof(float);
    if (buffered_bytes_ >= flush_bytes_) flush();
}

void ChunkBins::flush() {
    if (buffered_bytes_ > 0) ++flushes_;
    for (auto& [key, values] : buffers_) {
        if (values.empty()) continue;
        const fs::path path = file({key.second, key.first});
        std::ofstream out(path, std::ios::binary | std::ios::app);
        out.write(reinterpret_cast<const char*>(values.data()),
                  static_cast<std::streamsize>(values.size() * sizeof(float)));
        if (!out) engine::fail(path.string() + ": cannot write the chunk bin (disk full?)");
        values.clear();
        values.shrink_to_fit();
    }
    buffered_bytes_ = 0;
}

std::vector<glm::ivec2> ChunkBins::cells() const {
    std::vector<glm::ivec2> out;
    for (const auto& [key, count] : counts_) out.emplace_back(key.second, key.first);
    return out;
}

std::uint64_t ChunkBins::count(const glm::ivec2& cell) const {
    const auto it = counts_.find({cell.y, cell.x});
    return it == counts_.end() ? 0 : it->second;
}

std::uint64_t ChunkBins::largest() const {
    std::uint64_t most = 0;
    for (const auto& [key, count] : counts_) most = std::max(most, count);
    return most;
}

SplatCloud ChunkBins::read(const glm::ivec2& cell) const {
    const fs::path path = file(cell);
    const std::uint64_t n = count(cell);
    std::vector<float> values(static_cast<std::size_t>(n) * floats_per_gaussian());
    std::ifstream in(path, std::ios::binary);
    in.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(float)));
    if (!in || static_cast<std::size_t>(in.gcount()) != values.size() * sizeof(float))
        engine::fail(path.string() + ": the chunk bin does not hold its " + std::to_string(n) + " Gaussians");
    SplatCloud cloud;
    cloud.sh_degree = sh_degree_;
    cloud.resize(static_cast<std::size_t>(n));
    const std::size_t stride = cloud.sh_rest_stride();
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const float* v = values.data() + i * floats_per_gaussian();
        cloud.positions[i] = {v[0], v[1], v[2]};
        cloud.rotations[i] = {v[3], v[4], v[5], v[6]};
        cloud.log_scales[i] = {v[7], v[8], v[9]};
        cloud.opacity_logits[i] = v[10];
        cloud.sh_dc[i] = {v[11], v[12], v[13]};
        std::copy_n(v + kFixedFloats, stride, cloud.sh_rest.begin() + static_cast<std::ptrdiff_t>(i * stride));
    }
    return cloud;
}

void ChunkBins::remove(const glm::ivec2& cell) const {
    std::error_code ec;
    fs::remove(file(cell), ec);
}

FarLayer::FarLayer(int sh_degree, std::uint64_t cap) : cap_(cap) {
    cloud_.sh_degree = sh_degree;
}

void FarLayer::add(const SplatCloud& cloud, std::size_t i, float score) {
    append_gaussian(cloud_, cloud, i);
    scores_.push_back(score);
    if (scores_.size() >= 2 * std::max<std::uint64_t>(cap_, 1)) compact(cap_);
}

// Keeps the `keep` highest scores (ties: the earlier Gaussian), in the order they were added.
void FarLayer::compact(std::uint64_t keep) {
    if (scores_.size() <= keep) return;
    std::vector<std::uint32_t> order(scores_.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return scores_[a] > scores_[b]; });
    order.resize(static_cast<std::size_t>(keep));
    std::sort(order.begin(), order.end());
    dropped_ += scores_.size() - keep;
    cloud_ = cloud_.permuted(order);
    std::vector<float> scores;
    for (const std::uint32_t k : order) scores.push_back(scores_[k]);
    scores_ = std::move(scores);
}

SplatCloud FarLayer::finish() {
    compact(cap_);
    return std::move(cloud_);
}

}  // namespace splat_lod::world
