// Dataset directories: which existing paths may be replaced, staging and the final swap, and a
// recorded dataset as detect/ reads it.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/frame_pcd.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/dataset/manifest.h"
#include "../support/input_error_of.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using ladarsim::test::ScratchDir;

namespace {

/// What a previous run left: `names` listed as written by ladarsim.
void list_as_owned(const std::filesystem::path& dir, const std::vector<std::string>& names) {
    std::ofstream list(dir / kOwnedList);
    for (const auto& n : names) list << n << "\n";
}

}  // namespace

TEST_CASE("an absent, empty or earlier dataset directory may be replaced, and anything else is refused", "[dataset_directory]") {
    const ScratchDir dir;
    CHECK(checked_dataset_dir(dir / "new") == dir / "new");
    CHECK(checked_dataset_dir((dir / "new").string() + "/") == dir / "new");
    std::filesystem::create_directories(dir / "empty");
    CHECK(checked_dataset_dir(dir / "empty") == dir / "empty");
    std::filesystem::create_directories(dir / "earlier");
    std::ofstream(dir / "earlier" / "manifest.json") << "{}";
    list_as_owned(dir / "earlier", {"manifest.json", "frames"});
    CHECK(checked_dataset_dir(dir / "earlier") == dir / "earlier");

    std::filesystem::create_directories(dir / "photos");
    std::ofstream(dir / "photos" / "holiday.jpg") << "not ours";
    const InputError e = test::input_error_of([&] { checked_dataset_dir(dir / "photos"); });
    CHECK(e.file() == (dir / "photos").string());
    CHECK(e.field() == "--out");
    CHECK_THAT(e.problem(), Catch::Contains("refusing to replace"));
    std::filesystem::create_directories(dir / "earlier" / "frames");
    std::ofstream(dir / "earlier" / "frames" / "000000.pcd") << "ours";
    CHECK(checked_dataset_dir(dir / "earlier") == dir / "earlier");
    std::ofstream(dir / "earlier" / "frames" / "mine.txt") << "not ours";
    CHECK_THAT(test::input_error_of([&] { checked_dataset_dir(dir / "earlier"); }).problem(), Catch::Contains("frames/mine.txt"));
    std::ofstream(dir / "file") << "x";
    CHECK(test::input_error_of([&] { checked_dataset_dir(dir / "file"); }).field() == "--out");
}

TEST_CASE("a manifest.json alone does not make a directory ladarsim's, nor a name a file", "[dataset_directory]") {
    const ScratchDir dir;
    std::filesystem::create_directories(dir / "project");
    std::ofstream(dir / "project" / "manifest.json") << R"({"name": "my web app"})";
    CHECK_THAT(test::input_error_of([&] { checked_dataset_dir(dir / "project"); }).problem(), Catch::Contains("refusing to replace"));
    // A file of the user's named as a render's, in a directory ladarsim wrote: refused by name.
    list_as_owned(dir / "project", {"frames"});
    std::ofstream(dir / "project" / "background.pcd") << "mine";
    const InputError e = test::input_error_of([&] { checked_dataset_dir(dir / "project"); });
    CHECK_THAT(e.problem(), Catch::Contains("background.pcd") && Catch::Contains("manifest.json"));
}

TEST_CASE("the staging directory replaces ladarsim's listed entries, keeps the user's and leaves nothing beside it", "[dataset_directory]") {
    const ScratchDir dir;
    const auto out = dir / "run";
    CHECK(staging_dir(out) == dir / "run.partial");
    std::filesystem::create_directories(out / "frames");
    std::ofstream(out / "frames" / "000009.pcd") << "old";
    std::ofstream(out / "manifest.json") << "old";
    std::ofstream(out / "detections-vrbnn.json") << "old";
    std::ofstream(out / "detections-handlabelled.json") << "mine";
    std::ofstream(out / "NOTES.txt") << "mine";
    std::filesystem::create_directories(out / "analysis");
    list_as_owned(out, {"frames", "manifest.json", "detections-vrbnn.json"});
    std::filesystem::create_directories(staging_dir(out) / "frames");
    std::ofstream(staging_dir(out) / "manifest.json") << "{}";
    CHECK(swap_in_dataset(staging_dir(out), out) ==
          std::vector<std::string>{"NOTES.txt", "analysis/", "detections-handlabelled.json"});
    CHECK(read_json(out / "manifest.json") == nlohmann::json::object());
    CHECK_FALSE(std::filesystem::exists(out / "frames" / "000009.pcd"));
    CHECK_FALSE(std::filesystem::exists(out / "detections-vrbnn.json"));
    CHECK(std::filesystem::exists(out / "NOTES.txt"));
    CHECK(std::filesystem::exists(out / "analysis"));
    CHECK(owned_entries(out) == std::vector<std::string>{"frames", "manifest.json"});
    CHECK_FALSE(std::filesystem::exists(staging_dir(out)));
    CHECK_FALSE(std::filesystem::exists(dir / "run.old"));
}

TEST_CASE("a file is replaced only when ladarsim wrote it, or with --force", "[dataset_directory]") {
    const ScratchDir dir;
    CHECK_NOTHROW(check_replaceable(dir / "new.json", "--out", false));
    std::ofstream(dir / "mine.json") << "mine";
    CHECK_THAT(test::input_error_of([&] { check_replaceable(dir / "mine.json", "--out", false); }).problem(),
               Catch::Contains("--force"));
    CHECK_NOTHROW(check_replaceable(dir / "mine.json", "--out", true));
    CHECK_THAT(test::input_error_of([&] { check_replaceable(dir.path(), "--out", true); }).problem(), Catch::Contains("is a directory"));
    CHECK_THAT(test::input_error_of([&] { check_replaceable(dir / "absent" / "e.png", "--plot", false); }).problem(),
               Catch::Contains("does not exist"));
    // Recorded in a directory of ladarsim's: then it is ladarsim's to replace.
    list_as_owned(dir.path(), {"frames"});
    record_owned(dir / "mine.json");
    CHECK_NOTHROW(check_replaceable(dir / "mine.json", "--out", false));
}

TEST_CASE("a second writer of one output is refused while the first holds its staging directory", "[dataset_directory]") {
    const ScratchDir dir;
    const StagingDir first(dir / "out");
    std::ofstream(first.path() / "frame") << "the first run's";
    const InputError e = test::input_error_of([&] { StagingDir second(dir / "out"); });
    CHECK(e.field() == "--out");
    CHECK_THAT(e.problem(), Catch::Contains("another ladarsim run"));
    CHECK(std::filesystem::exists(first.path() / "frame"));
}

TEST_CASE("a recorded dataset: its frames, and a manifest naming the source and the sensor", "[dataset_directory]") {
    const ScratchDir dir;
    std::vector<Frame> frames(2);
    frames[1].index = 1;
    frames[1].start_time_s = 0.1;
    frames[1].end_time_s = 0.2;
    Return r;
    r.position_sensor = {1.0f, 2.0f, 3.0f};
    frames[1].returns = {r, r};
    const nlohmann::json sensor = {{"preset", "recorder"},
                                   {"derived", {{"beams_az", 1800}, {"beams_el", 16}, {"field_az_deg", 360.0},
                                                {"field_el_deg", 32.0}, {"divergence_mrad", 3.0}}}};
    write_recorded_dataset(frames, sensor, dir / "rec", dir / "capture.pcap");
    CHECK(read_frame_pcd(dir / "rec" / "frames" / "000000.pcd").empty());
    CHECK(read_frame_pcd(dir / "rec" / "frames" / "000001.pcd").size() == 2);
    const nlohmann::json manifest = read_json(dir / "rec" / "manifest.json");
    CHECK(manifest.at("sensor") == sensor);
    CHECK(manifest.at("recorded_from") == (dir / "capture.pcap").string());
    CHECK(manifest.at("frames").at(1).at("returns") == 2);
    CHECK(manifest.at("software").at("name") == "ladarsim");
    CHECK_FALSE(std::filesystem::exists(dir / "rec.partial"));
    // What detect/ needs of it: the sensor's geometry, and no gimbal pointing for recorded frames.
    const Manifest m = read_manifest(dir / "rec" / "manifest.json");
    CHECK(m.sensor.beams_az == 1800);
    CHECK(m.pointing.size() == 2);
    CHECK_FALSE(m.pointing[1]);

    std::filesystem::create_directories(dir / "photos");
    std::ofstream(dir / "photos" / "holiday.jpg") << "not ours";
    CHECK_THROWS_AS(write_recorded_dataset(frames, sensor, dir / "photos", dir / "capture.pcap"), InputError);
    CHECK(std::filesystem::exists(dir / "photos" / "holiday.jpg"));
}

TEST_CASE("a mount point is a directory on another device than its parent, refused as --out", "[dataset_directory]") {
    // The CLI test mounts a tmpfs where a private mount namespace can be had; this checks the
    // detection itself on the device ids of a directory and its parent.
    const ScratchDir dir;
    std::filesystem::create_directories(dir / "plain");
    CHECK_FALSE(is_mount_point(dir / "plain"));
    CHECK(is_mount_point("/proc"));  // procfs: always its own file system on Linux
    const InputError e = test::input_error_of([&] { checked_dataset_dir("/proc"); });
    CHECK(e.field() == "--out");
    CHECK_THAT(e.problem(), Catch::Contains("mount point"));
}

TEST_CASE("an --out through a symbolic link is the link's target, and a link to nothing is refused", "[dataset_directory]") {
    const ScratchDir dir;
    std::filesystem::create_directories(dir / "target");
    std::filesystem::create_directory_symlink(dir / "target", dir / "link");
    CHECK(checked_dataset_dir(dir / "link") == std::filesystem::canonical(dir / "target"));
    std::filesystem::create_directory_symlink(dir / "nowhere", dir / "dangling");
    CHECK_THAT(test::input_error_of([&] { checked_dataset_dir(dir / "dangling"); }).problem(), Catch::Contains("link to nothing"));
}
