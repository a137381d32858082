#pragma once
// A contact sheet of frames from the path: labelled thumbnails in a grid, so that the whole
// walkthrough can be looked at in one picture.
#include <filesystem>
#include <string>
#include <vector>

#include "engine/render/image.h"

namespace sample_game {

class FrameSheet {
public:
    explicit FrameSheet(int thumbnail_width = 240, int columns = 5);
    // Keeps an area-averaged thumbnail of `frame` with its label ("f40 overview").
    void add(const engine::Image& frame, const std::string& label);
    // A black tile with only its label, so that the grid's rows stay aligned where a frame is missing.
    void add_blank(const std::string& label);
    bool empty() const { return tiles_.empty(); }
    // Writes the grid as PNG (atomically); throws engine::Error naming the file.
    void write(const std::filesystem::path& path) const;

private:
    struct Tile {
        engine::Image image;
        std::string label;
    };
    int thumbnail_width_;
    int columns_;
    std::vector<Tile> tiles_;
};

}  // namespace sample_game
