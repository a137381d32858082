// Training cameras (training_cameras.h): COLMAP's text model gives the pose and field of view that the
// same camera has in INRIA cameras.json; folders are searched; bad files are refused naming file and line.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/training_cameras.h"
#include "test_support.h"

namespace fs = std::filesystem;
using splat_io_test::error_of;
using splat_lod::eval::CameraPose;

namespace {

// A camera at `centre` looking down at 30 degrees towards +x, as COLMAP writes it (world-to-camera
// quaternion and translation, OpenCV axes) and as INRIA's cameras.json does (camera-to-world rows).
struct Known {
    glm::dvec3 centre{1.0, 2.0, 3.0};
    glm::dmat3 camera_to_world;  // columns: the camera's x (right), y (down), z (forward) in the world
    Known() {
        const glm::dvec3 forward = glm::normalize(glm::dvec3(std::cos(glm::radians(30.0)), -0.5, 0.2));
        const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
        const glm::dvec3 down = glm::cross(forward, right);
        camera_to_world = glm::dmat3(right, down, forward);
    }
    std::string images_line(const std::string& camera_id) const {
        const glm::dmat3 world_to_camera = glm::transpose(camera_to_world);
        const glm::dquat q = glm::quat_cast(world_to_camera);
        const glm::dvec3 t = -(world_to_camera * centre);
        char line[256];
        std::snprintf(line, sizeof line, "7 %.17g %.17g %.17g %.17g %.17g %.17g %.17g %s frame_007.jpg\n", q.w, q.x,
                      q.y, q.z, t.x, t.y, t.z, camera_id.c_str());
        return line;
    }
    std::string inria_json() const {
        std::string rows;
        for (int r = 0; r < 3; ++r) {
            char row[128];
            std::snprintf(row, sizeof row, "%s[%.17g, %.17g, %.17g]", r ? ", " : "", camera_to_world[0][r],
                          camera_to_world[1][r], camera_to_world[2][r]);
            rows += row;
        }
        char text[512];
        std::snprintf(
            text, sizeof text,
            R"([{"id": 0, "img_name": "frame_007", "width": 1600, "height": 900, "position": [%.17g, %.17g, %.17g], "rotation": [%s], "fx": 1000, "fy": 1000}])",
            centre.x, centre.y, centre.z, rows.c_str());
        return text;
    }
};

constexpr const char* kCameras =
    "# Camera list\n1 PINHOLE 1600 900 1000 1000 800 450\n2 SIMPLE_RADIAL 800 450 500 400 225 0.01\n";

void expect_same(const CameraPose& a, const CameraPose& b) {
    EXPECT_NEAR(glm::length(a.eye - b.eye), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(a.forward - b.forward), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(a.up - b.up), 0.0f, 1e-5f);
    EXPECT_NEAR(a.fov_y, b.fov_y, 1e-6f);
}

}  // namespace

TEST(TrainingCameras, ColmapGivesThePoseOfTheSameCameraInCamerasJson) {
    const Known known;
    // Comments, and an image whose points line is empty followed by one with points.
    const std::string images =
        "# Image list\n" + known.images_line("1") + "\n" + known.images_line("2") + "100.5 200.5 -1 300 400 12\n";
    const auto colmap = splat_lod::eval::parse_colmap_cameras(images, kCameras, "images.txt", "cameras.txt");
    const auto inria = splat_lod::eval::parse_inria_cameras(known.inria_json(), "cameras.json");
    ASSERT_EQ(colmap.size(), 2u);
    // Written without points lines (one line per image): no image is lost.
    EXPECT_EQ(splat_lod::eval::parse_colmap_cameras(known.images_line("1") + known.images_line("2"), kCameras,
                                                    "images.txt", "cameras.txt")
                  .size(),
              2u);
    ASSERT_EQ(inria.size(), 1u);
    expect_same(colmap[0], inria[0]);
    expect_same(colmap[1], inria[0]);  // the other camera model has the same field of view
    EXPECT_EQ(colmap[0].name, "frame_007.jpg");
    EXPECT_NEAR(colmap[0].fov_y, 2.0 * std::atan(900.0 / 2000.0), 1e-6);
}

TEST(TrainingCameras, FoldersAreSearchedAndBadFilesNamed) {
    const fs::path dir = engine::test::output_dir("training_cameras");
    fs::remove_all(dir);
    fs::create_directories(dir / "colmap" / "sparse" / "0");
    fs::create_directories(dir / "inria");
    const Known known;
    engine::write_text_file_atomic(dir / "colmap" / "sparse" / "0" / "images.txt", known.images_line("1"));
    engine::write_text_file_atomic(dir / "colmap" / "sparse" / "0" / "cameras.txt", kCameras);
    engine::write_text_file_atomic(dir / "inria" / "cameras.json", known.inria_json());
    expect_same(splat_lod::eval::read_training_cameras(dir / "colmap").at(0),
                splat_lod::eval::read_training_cameras(dir / "inria").at(0));

    EXPECT_NE(error_of([&] { splat_lod::eval::read_training_cameras(dir); }).find("holds no cameras.json"),
              std::string::npos);
    fs::create_directories(dir / "lone");
    engine::write_text_file_atomic(dir / "lone" / "images.txt", known.images_line("1"));
    EXPECT_NE(error_of([&] {
                  splat_lod::eval::read_training_cameras(dir / "lone" / "images.txt");
              }).find("cameras.txt (the fields of view) is missing"),
              std::string::npos);
    const auto parse_error = [&](const std::string& images) {
        return error_of([&] { splat_lod::eval::parse_colmap_cameras(images, kCameras, "images.txt", "cameras.txt"); });
    };
    EXPECT_NE(parse_error("\n" + known.images_line("9")).find("images.txt: line 2: camera 9 is not in cameras.txt"),
              std::string::npos);
    EXPECT_NE(parse_error("1 0 0 0 0 1 2 3 1 a.jpg\n").find("line 1: the quaternion is zero"), std::string::npos);
    EXPECT_NE(parse_error("1 nan 0 0 0 1 2 3 1 a.jpg\n").find("line 1: \"nan\" is not a finite number"),
              std::string::npos);
    EXPECT_NE(parse_error("1 1 0 0 0 1 2\n").find("line 1: expected IMAGE_ID"), std::string::npos);
    EXPECT_NE(parse_error("# nothing\n").find("no image"), std::string::npos);
    EXPECT_NE(error_of([&] {
                  splat_lod::eval::parse_colmap_cameras(known.images_line("1"), "1 FANCY 4 4 1\n", "i", "c");
              }).find("c: line 1: unknown camera model \"FANCY\""),
              std::string::npos);
}
