// Output safety proven by killing the real tools: splat_bake and splat_world run as child processes
// and are SIGKILLed at several points (at once, during the work, and as close to the write or the
// commit as polling gets). The output they had before must come through byte for byte (or, killed
// after the commit, the new output must be complete), it must still load, and the next complete
// run must leave only its own files. The tools' paths come from CMakeLists.txt here.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "engine/assets/mesh_asset.h"
#include "engine/core/file_io.h"
#include "splat_lod/core/chunk_reader.h"
#include "splat_lod/core/world_manifest.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;
namespace sw = splat_lod::world;
using Clock = std::chrono::steady_clock;

std::string file_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A tool run as a child process: stdout to /dev/null, stderr to `log` (read while it runs).
class Process {
public:
    Process(const std::vector<std::string>& argv, const fs::path& log) : log_(log) {
        pid_ = ::fork();
        if (pid_ == 0) {
            const int out = ::open("/dev/null", O_WRONLY);
            const int err = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            ::dup2(out, STDOUT_FILENO);
            ::dup2(err, STDERR_FILENO);
            std::vector<char*> args;
            for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
            args.push_back(nullptr);
            ::execv(args[0], args.data());
            ::_exit(127);
        }
    }
    ~Process() {
        if (running()) kill();
    }
    Process(const Process&) = delete;
    Process& operator=(const Process&) = delete;

    bool running() {
        if (done_) return false;
        if (::waitpid(pid_, &status_, WNOHANG) == pid_) done_ = true;
        return !done_;
    }
    // Polls (busy, to be as close as possible) until `condition` holds; false when the process
    // ended first or after `timeout_s`.
    bool wait_for(const std::function<bool()>& condition, double timeout_s = 60.0) {
        const auto start = Clock::now();
        while (std::chrono::duration<double>(Clock::now() - start).count() < timeout_s) {
            if (condition()) return true;
            if (!running()) return condition();
        }
        return false;
    }
    bool log_has(const std::regex& pattern) { return std::regex_search(file_bytes(log_), pattern); }
    void kill() {
        if (running()) ::kill(pid_, SIGKILL);
        finish();
    }
    int finish() {  // waits; the exit code, or 128 + signal
        if (!done_) ::waitpid(pid_, &status_, 0);
        done_ = true;
        return WIFEXITED(status_) ? WEXITSTATUS(status_) : 128 + WTERMSIG(status_);
    }
    bool killed() {
        finish();
        return WIFSIGNALED(status_);
    }
    std::string log() const { return file_bytes(log_); }

private:
    fs::path log_;
    pid_t pid_ = -1;
    int status_ = 0;
    bool done_ = false;
};

int run_to_end(const std::vector<std::string>& argv, const fs::path& log) {
    return Process(argv, log).finish();
}

bool has_temporary_of(const fs::path& file) {
    std::error_code ec;
    for (const auto& item : fs::directory_iterator(file.parent_path(), ec))
        if (item.path().filename().string().rfind(file.filename().string() + ".tmp-", 0) == 0) return true;
    return false;
}

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

TEST(OutputSafetyKill, AKilledBakeLeavesThePreviousOutputByteForByte) {
    const fs::path dir = engine::test::output_dir("output_safety_kill");
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path scene = dir / "garden.ply", output = dir / "out.lod.ply", reference = dir / "reference.lod.ply";
    ASSERT_EQ(
        run_to_end({SPLAT_SYNTH_PATH, "--out", scene.string(), "--seed", "3", "--detail", "0.1"}, dir / "synth.log"),
        0);
    const auto bake = [&](const fs::path& out, std::vector<std::string> settings) {
        std::vector<std::string> argv = {SPLAT_BAKE_PATH, "--input", scene.string(), "--output", out.string(),
                                         "--threads",     "1"};
        argv.insert(argv.end(), settings.begin(), settings.end());
        return argv;
    };
    const std::vector<std::string> old_settings = {"--refine-iterations", "0"};
    const std::vector<std::string> new_settings = {"--refine-iterations",
                                                   "10",
                                                   "--refine-cameras",
                                                   "4",
                                                   "--width",
                                                   "128",
                                                   "--height",
                                                   "128",
                                                   "--cells",
                                                   "adaptive"};
    ASSERT_EQ(run_to_end(bake(output, old_settings), dir / "old.log"), 0);
    const std::string old_bytes = file_bytes(output);
    auto start = Clock::now();
    ASSERT_EQ(run_to_end(bake(reference, new_settings), dir / "reference.log"), 0);
    const double bake_seconds = seconds_since(start);
    const std::string new_bytes = file_bytes(reference);
    ASSERT_NE(old_bytes, new_bytes);
    std::cout << "bake: " << old_bytes.size() << " bytes before, " << new_bytes.size() << " after a " << bake_seconds
              << " s bake\n";

    // Each kill point: when to kill, and whether the new output may already be in place then.
    struct KillPoint {
        std::string name;
        std::function<bool(Process&)> reach;  // false: the bake ended before the point
        bool may_have_replaced;
    };
    const auto after = [](double seconds) {
        return [seconds](Process& p) {
            const auto from = Clock::now();
            return p.wait_for([&] { return seconds_since(from) >= seconds; });
        };
    };
    const std::vector<KillPoint> points = {
        {"at once", [](Process&) { return true; }, false},
        {"loading the scene", [](Process& p) { return p.wait_for([&] { return p.log_has(std::regex("Gaussians")); }); },
         false},
        {"first bake stage", [](Process& p) { return p.wait_for([&] { return p.log_has(std::regex("%")); }); }, false},
        {"half-way", after(0.5 * bake_seconds), true},
        {"near the end", after(0.9 * bake_seconds), true},
        // Killed as soon as the temporary appears (it lives while the bytes are written and synced);
        // tried until it was seen once, as the write may also finish between two looks.
        {"temporary file seen", [&](Process& p) { return p.wait_for([&] { return has_temporary_of(output); }); }, true},
    };
    int temporaries_seen = 0;
    for (std::size_t k = 0, tries = 0; k < points.size(); ++k) {
        const KillPoint& point = points[k];
        Process p(bake(output, new_settings), dir / "killed.log");
        const bool reached = point.reach(p);
        p.kill();
        const std::string now = file_bytes(output);
        if (point.name.rfind("temporary", 0) == 0 && reached) ++temporaries_seen;
        std::cout << "killed " << point.name << (reached ? "" : " (the bake ended first)") << ": output "
                  << (now == old_bytes   ? "unchanged"
                      : now == new_bytes ? "replaced by the complete new bake"
                                         : "DAMAGED")
                  << "\n";
        if (!point.may_have_replaced) {
            EXPECT_TRUE(reached) << point.name;
            EXPECT_TRUE(now == old_bytes) << point.name << ": the killed bake changed the output";
        } else {
            EXPECT_TRUE(now == old_bytes || now == new_bytes)
                << point.name << ": the output is neither the old nor the new bake";
        }
        if (now != old_bytes)
            engine::write_text_file_atomic(output, old_bytes);  // the next kill starts from the old output
        if (point.name == "temporary file seen" && temporaries_seen == 0 && ++tries < 5) --k;
    }
    EXPECT_GE(temporaries_seen, 1) << "never killed while the temporary existed";

    // A later bake succeeds and removes what the killed ones left.
    const bool leftovers = has_temporary_of(output);
    std::cout << "temporaries of killed bakes before the next bake: " << (leftovers ? "yes" : "none") << "\n";
    ASSERT_EQ(run_to_end(bake(output, new_settings), dir / "final.log"), 0);
    EXPECT_TRUE(file_bytes(output) == new_bytes);
    EXPECT_FALSE(has_temporary_of(output)) << "temporaries of killed bakes were left";
}

namespace {

// A world on disk as its manifest names it: the manifest's bytes, and each named file's bytes by
// its role (chunk id or mesh file name), which does not depend on the generation folder.
struct WorldSnapshot {
    std::string manifest;
    std::uint64_t seed = 0;
    std::map<std::string, std::string> by_role;
    std::set<std::string> paths;  // the named files, relative
};

WorldSnapshot snapshot(const fs::path& world) {
    WorldSnapshot s;
    s.manifest = file_bytes(world / sw::kManifestFileName);
    const sw::WorldManifest m = sw::read_world_manifest(world / sw::kManifestFileName);
    s.seed = m.seed;
    const auto add = [&](const std::string& role, const fs::path& file) {
        EXPECT_TRUE(fs::is_regular_file(world / file)) << file << " is missing";
        s.by_role[role] = file_bytes(world / file);
        s.paths.insert(file.generic_string());
    };
    for (const sw::ChunkEntry& c : m.chunks) add(c.id, c.file);
    for (const sw::ChunkEntry& g : m.groups) add(g.id, g.file);
    for (const sw::Prop& p : m.props) add(p.mesh.filename().string(), p.mesh);
    if (!m.terrain_mesh.empty()) add(m.terrain_mesh.filename().string(), m.terrain_mesh);
    return s;
}

// The world loads as a reader would: every chunk and group whole through the chunk reader, every mesh through
// the engine's glTF loader.
void expect_loads(const fs::path& world) {
    const sw::WorldManifest m = sw::read_world_manifest(world / sw::kManifestFileName);
    for (const auto* list : {&m.chunks, &m.groups})
        for (const sw::ChunkEntry& c : *list)
            EXPECT_EQ(sw::read_chunk_range(world / c.file, c, 0, c.prefix_count[0]).size(), c.prefix_count[0]) << c.id;
    std::set<fs::path> meshes;
    for (const sw::Prop& p : m.props) meshes.insert(p.mesh);
    if (!m.terrain_mesh.empty()) meshes.insert(m.terrain_mesh);
    for (const fs::path& mesh : meshes) EXPECT_GT(engine::load_gltf(world / mesh).triangle_count(), 0u) << mesh;
}

std::set<std::string> files_in(const fs::path& folder) {
    std::set<std::string> files;
    for (const auto& item : fs::recursive_directory_iterator(folder))
        if (!item.is_directory()) files.insert(fs::relative(item.path(), folder).generic_string());
    return files;
}

// Only the world remains in `world`: world.json and its generation folder, which holds the files
// the manifest names (and the prop meshes the layout did not place).
void expect_only_the_world(const fs::path& world) {
    const WorldSnapshot s = snapshot(world);
    const std::string generation = fs::path(*s.paths.begin()).begin()->string();
    std::set<std::string> top;
    for (const auto& item : fs::directory_iterator(world)) top.insert(item.path().filename().string());
    EXPECT_EQ(top, (std::set<std::string>{sw::kManifestFileName, generation})) << "leftovers beside the world";
    const std::set<std::string> files = files_in(world);
    for (const std::string& named : s.paths) EXPECT_TRUE(files.count(named)) << named;
    for (const std::string& file : files)
        EXPECT_TRUE(file == sw::kManifestFileName || s.paths.count(file) || file.find("/meshes/") != std::string::npos)
            << file << " was left";
}

std::vector<std::string> world_command(const fs::path& out, std::uint64_t seed, bool force) {
    std::vector<std::string> argv = {SPLAT_WORLD_PATH,
                                     "--out",
                                     out.string(),
                                     "--seed",
                                     std::to_string(seed),
                                     "--size",
                                     "96",
                                     "--chunk",
                                     "32",
                                     "--density",
                                     "0.1",
                                     "--refine-iterations",
                                     "3",
                                     "--bake-width",
                                     "128",
                                     "--bake-height",
                                     "128",
                                     "--threads",
                                     "2"};
    if (force) argv.push_back("--force");
    return argv;
}

// The world in `world` is `expected` exactly: the same manifest bytes, every file it names with
// the same bytes, and it loads.
void expect_intact(const fs::path& world, const WorldSnapshot& expected, const std::string& when) {
    SCOPED_TRACE(when);
    ASSERT_TRUE(fs::exists(world / sw::kManifestFileName)) << "world.json is gone";
    const WorldSnapshot now = snapshot(world);
    EXPECT_TRUE(now.manifest == expected.manifest) << "world.json changed";
    EXPECT_TRUE(now.by_role == expected.by_role) << "a file the manifest names changed";
    expect_loads(world);
}

// A world seeded 11 and the reference bytes of the seed-12 world, made in two folders of `dir`.
struct KillSetup {
    fs::path world;
    std::map<std::uint64_t, WorldSnapshot> reference;  // by seed: the complete world's files
    double run_seconds = 0.0;
};

KillSetup kill_setup(const fs::path& dir) {
    fs::create_directories(dir);
    KillSetup k;
    k.world = dir / "world";
    const auto start = Clock::now();
    EXPECT_EQ(run_to_end(world_command(dir / "reference_12", 12, false), dir / "reference.log"), 0);
    k.run_seconds = seconds_since(start);
    EXPECT_EQ(run_to_end(world_command(k.world, 11, false), dir / "first.log"), 0);
    k.reference[11] = snapshot(k.world);
    k.reference[12] = snapshot(dir / "reference_12");
    std::cout << "a tiny world takes " << k.run_seconds << " s\n";
    return k;
}

}  // namespace

TEST(OutputSafetyKill, AWorldRunKilledMidWayLeavesThePreviousWorldIntact) {
    const fs::path dir = engine::test::output_dir("output_safety_kill");
    fs::remove_all(dir);
    const KillSetup k = kill_setup(dir);
    const WorldSnapshot& old = k.reference.at(11);
    ASSERT_NE(old.by_role.at("chunk_+000_+000"), k.reference.at(12).by_role.at("chunk_+000_+000"));

    struct KillPoint {
        std::string name;
        std::regex line;  // the progress line on stderr to kill at
    };
    const std::vector<KillPoint> points = {{"at once", std::regex("")},
                                           {"writing the meshes", std::regex("splat_world: meshes")},
                                           {"after some chunks", std::regex("chunks [3-8]/9")}};
    for (const KillPoint& point : points) {
        Process p(world_command(k.world, 12, true), dir / "killed.log");
        EXPECT_TRUE(p.wait_for([&] { return p.log_has(point.line); })) << point.name << ": " << p.log();
        p.kill();
        EXPECT_TRUE(p.killed()) << point.name;
        expect_intact(k.world, old, "killed " + point.name);
        // The kill came after files of the new world were written, next to the old ones.
        std::size_t new_chunks = 0;
        for (const std::string& file : files_in(k.world))
            if (!old.paths.count(file) && file.find(".splatc") != std::string::npos) ++new_chunks;
        std::cout << "killed " << point.name << ": old world intact, " << new_chunks
                  << " chunk files of the killed run left\n";
        if (point.name == "after some chunks") {
            EXPECT_GE(new_chunks, 3u);
        }
    }

    // A complete run replaces the world and removes every leftover of the killed runs.
    ASSERT_EQ(run_to_end(world_command(k.world, 12, true), dir / "final.log"), 0);
    EXPECT_TRUE(snapshot(k.world).by_role == k.reference.at(12).by_role);
    expect_only_the_world(k.world);
    expect_loads(k.world);
}

TEST(OutputSafetyKill, AWorldRunKilledAroundItsCommitLeavesOneCompleteWorld) {
    const fs::path dir = engine::test::output_dir("output_safety_kill");
    fs::remove_all(dir);
    const KillSetup k = kill_setup(dir);

    // Kills from just before the manifest is written (its progress line) to after the clean-up,
    // each run replacing whichever world the last one left with the other seed's.
    int kept = 0, replaced = 0, before_clean_up = 0;
    for (const double delay_ms : {0.0, 0.25, 0.5, 1.0, 2.0, 3.0, 5.0, 8.0, 12.0, 20.0, 40.0}) {
        const WorldSnapshot before = snapshot(k.world);
        const std::uint64_t seed = before.seed == 11 ? 12 : 11;
        Process p(world_command(k.world, seed, true), dir / "killed.log");
        ASSERT_TRUE(p.wait_for([&] { return p.log_has(std::regex("splat_world: manifest")); })) << p.log();
        const auto seen = Clock::now();
        p.wait_for([&] { return seconds_since(seen) * 1000.0 >= delay_ms; });
        p.kill();
        const std::string when = "killed " + std::to_string(delay_ms) + " ms after the manifest line";
        const WorldSnapshot now = snapshot(k.world);
        if (now.manifest == before.manifest) {
            ++kept;
            expect_intact(k.world, before, when);
        } else {
            ++replaced;
            SCOPED_TRACE(when);
            EXPECT_EQ(now.seed, seed);
            EXPECT_TRUE(now.by_role == k.reference.at(seed).by_role) << "the new world is not complete";
            expect_loads(k.world);
        }
        const std::size_t files = files_in(k.world).size();
        std::cout << when << ": " << (now.manifest == before.manifest ? "previous world kept" : "new world committed")
                  << ", " << files << " files in the folder\n";
        // Committed, but the previous generation is still there: killed before or during the clean-up.
        const fs::path previous = fs::path(*before.paths.begin()).begin()->string();
        if (now.manifest != before.manifest && fs::exists(k.world / previous)) ++before_clean_up;
    }
    std::cout << "previous world kept " << kept << " times, new world committed " << replaced << " times (killed "
              << before_clean_up << " times between the commit and the clean-up)\n";

    // The next run (cached or not) removes what the killed ones left.
    ASSERT_EQ(run_to_end(world_command(k.world, snapshot(k.world).seed, false), dir / "cached.log"), 0);
    expect_only_the_world(k.world);
    ASSERT_EQ(run_to_end(world_command(k.world, 13, false), dir / "final.log"), 0);
    expect_only_the_world(k.world);
    EXPECT_EQ(snapshot(k.world).seed, 13u);
    expect_loads(k.world);
}
