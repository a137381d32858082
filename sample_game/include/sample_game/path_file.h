#pragma once
// A walkthrough path from a file (sample_game --path FILE), so that any world can be walked along a
// path of the user's choosing, and two worlds along the same one (sample_game --write-path FILE writes
// a world's own path). JSON, one of:
//   poses: [{"eye": [x, y, z], "forward": [x, y, z], "segment": "ground"}, …]  one per frame, used as given
//   keys:  [{"eye": [x, y, z], "look": [x, y, z], "segment": "ground"}, …]     sampled over the frames
//          asked for with the segments' usual shares (camera_path.h)
// "segment" is ground, canopy, flyout, overview or return (the summary's segments); every entry is one or
// the other kind. Errors name the file, the entry and the problem.
#include <filesystem>
#include <vector>

#include "sample_game/camera_path.h"

namespace sample_game {

// The poses of the file: its poses (their count whatever `frames` says), or its keys sampled over `frames`.
std::vector<PathPose> read_path_file(const std::filesystem::path& file, int frames);

// Writes poses in the first form (atomically).
void write_path_file(const std::filesystem::path& file, const std::vector<PathPose>& poses);

}  // namespace sample_game
