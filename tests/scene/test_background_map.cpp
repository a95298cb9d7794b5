// load_background_map: PCD points to oriented discs. Normals, radii and reflectance are checked
// against the plane, the grid spacing and the intensities the test wrote, computed by hand.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "ladarsim/core/input_error.h"
#include "ladarsim/scene/background_map.h"
#include "../support/shared_data.h"
#include "../support/skip.h"

using namespace ladarsim::scene;
using ladarsim::InputError;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

struct PcdPoint {
    double x, y, z, intensity = 0.0;
};

/// A fresh directory for one test's files, removed at the end of the test.
struct TempDir {
    fs::path path;
    TempDir() {
        std::random_device rd;
        path = fs::temp_directory_path() / ("ladarsim-test-background-" + std::to_string(rd()));
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
};

/// Writes an ASCII PCD with double coordinates (so geo-referenced values survive the file).
fs::path write_pcd(const fs::path& file, const std::vector<PcdPoint>& points, bool with_intensity) {
    std::ofstream out(file);
    out << "# .PCD v0.7\nVERSION 0.7\n";
    out << (with_intensity ? "FIELDS x y z intensity\nSIZE 8 8 8 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
                           : "FIELDS x y z\nSIZE 8 8 8\nTYPE F F F\nCOUNT 1 1 1\n");
    out << "WIDTH " << points.size() << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << points.size()
        << "\nDATA ascii\n";
    out << std::setprecision(17);
    for (const auto& p : points) {
        out << p.x << ' ' << p.y << ' ' << p.z;
        if (with_intensity) out << ' ' << p.intensity;
        out << '\n';
    }
    return file;
}

/// Writes the same points as a PLY vertex list with x y z intensity (doubles and a float),
/// ASCII or little-endian binary.
fs::path write_ply(const fs::path& file, const std::vector<PcdPoint>& points, bool binary) {
    std::ofstream out(file, std::ios::binary);
    out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\nelement vertex " << points.size()
        << "\nproperty double x\nproperty double y\nproperty double z\nproperty float intensity\nend_header\n";
    out << std::setprecision(17);
    for (const auto& p : points) {
        if (binary) {
            const double xyz[3] = {p.x, p.y, p.z};
            const float i = static_cast<float>(p.intensity);
            out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
            out.write(reinterpret_cast<const char*>(&i), sizeof i);
        } else {
            out << p.x << ' ' << p.y << ' ' << p.z << ' ' << p.intensity << '\n';
        }
    }
    return file;
}

/// nx by ny nodes with spacings sx, sy, on the plane z = a x + b y + c, starting at (x0, y0).
std::vector<PcdPoint> grid(int nx, int ny, double sx, double sy, double a = 0.0, double b = 0.0, double c = 0.0,
                           double x0 = 0.0, double y0 = 0.0) {
    std::vector<PcdPoint> pts;
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const double dx = i * sx, dy = j * sy;
            pts.push_back({x0 + dx, y0 + dy, a * dx + b * dy + c});
        }
    }
    return pts;
}

}  // namespace

TEST_CASE("background_map: normals of a tilted plane equal its analytic normal, at geo-referenced coordinates",
          "[background_map]") {
    TempDir dir;
    // z = a x + b y + c (x, y relative to the grid origin) has normal (-a, -b, 1) / |(-a, -b, 1)|.
    const double a = 0.3, b = -0.2, c = 150.0;
    // UTM-sized coordinates: float32 has a 0.5 m ulp at 5e6 m, so only a recentred fit passes.
    const double x0 = 500000.25, y0 = 5000000.5;
    const auto pts = grid(15, 12, 0.5, 0.5, a, b, c, x0, y0);
    BackgroundOptions options;
    options.offset_m = Eigen::Vector3d(-500000.0, -5000000.0, 10.0);
    BackgroundLoadReport report;
    const BackgroundMap map = load_background_map(write_pcd(dir.path / "plane.pcd", pts, false), options, &report);

    REQUIRE(map.points_world.size() == pts.size());
    REQUIRE(map.normals.size() == pts.size());
    CHECK(report.points_loaded == pts.size());
    CHECK(report.degenerate_normals == 0);
    CHECK(report.nonfinite_dropped == 0);
    const Eigen::Vector3f expected = Eigen::Vector3f(static_cast<float>(-a), static_cast<float>(-b), 1.0f).normalized();
    for (std::size_t i = 0; i < pts.size(); ++i) {
        // Offset applied in double: the file point plus the offset, exactly as computed here.
        CHECK(map.points_world[i].x() == pts[i].x + options.offset_m.x());
        CHECK(map.points_world[i].y() == pts[i].y + options.offset_m.y());
        CHECK(map.points_world[i].z() == pts[i].z + options.offset_m.z());
        CHECK((map.normals[i] - expected).norm() < 1e-4f);
    }
}

TEST_CASE("background_map: normals point up whichever way the fit returns them", "[background_map]") {
    TempDir dir;
    // A steep plane z = -2 x: normal (2, 0, 1)/sqrt(5) after flipping to +z.
    const auto pts = grid(8, 8, 1.0, 1.0, -2.0, 0.0, 0.0);
    const BackgroundMap map = load_background_map(write_pcd(dir.path / "steep.pcd", pts, false), {});
    for (const auto& n : map.normals) {
        CHECK(n.x() == Approx(2.0 / std::sqrt(5.0)).margin(1e-5));
        CHECK(n.y() == Approx(0.0).margin(1e-5));
        CHECK(n.z() == Approx(1.0 / std::sqrt(5.0)).margin(1e-5));
    }
}

TEST_CASE("background_map: a ground-based scan's rings give discs facing its scanner, not edge-on", "[background_map]") {
    // A spinning scanner 1.6 m over flat ground: channels at -15, -13 and -11 deg sample it along
    // rings 0.2 deg apart in azimuth, ranges with 1 cm of noise. Each point's nearest neighbours
    // lie on its own ring, that is on the cone its channel swept, so their plane fit contains
    // the lines of sight.
    TempDir dir;
    const Eigen::Vector3d scanner(0.0, 0.0, 1.6);
    std::vector<PcdPoint> pts;
    for (double el_deg : {-15.0, -13.0, -11.0}) {
        const double el = el_deg * M_PI / 180.0;
        for (int k = 0; k < 1800; ++k) {
            const double az = 2.0 * M_PI * k / 1800.0;
            const double range = -scanner.z() / std::sin(el) + 0.01 * std::sin(37.0 * k + el_deg);
            const Eigen::Vector3d p = scanner + range * Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
            pts.push_back({p.x(), p.y(), p.z()});
        }
    }
    const fs::path file = write_pcd(dir.path / "rings.pcd", pts, false);
    auto edge_on = [&](const BackgroundMap& map) {
        std::size_t count = 0;
        for (std::size_t i = 0; i < pts.size(); ++i) {
            const Eigen::Vector3f view = (scanner - map.points_world[i]).normalized().cast<float>();
            count += std::abs(map.normals[i].dot(view)) < 0.1f;
        }
        return count;
    };
    // Read as an airborne survey, most discs are edge-on to the beams that recorded them.
    CHECK(edge_on(load_background_map(file, {})) > pts.size() / 2);

    BackgroundOptions options;
    options.scanner_position_m = scanner;
    BackgroundLoadReport report;
    const BackgroundMap map = load_background_map(file, options, &report);
    CHECK(edge_on(map) == 0);
    CHECK(report.scan_line_normals + report.degenerate_normals > pts.size() / 2);
    for (std::size_t i = 0; i < pts.size(); ++i)
        REQUIRE(map.normals[i].dot((scanner - map.points_world[i]).normalized().cast<float>()) > 0.0f);
}

TEST_CASE("background_map: a scanner position leaves true surface normals alone, turned to face it", "[background_map]") {
    // A tilted grid (a real two-dimensional neighbourhood) seen from a scanner below its plane:
    // the analytic normal, flipped towards the scanner rather than up.
    TempDir dir;
    const double a = 0.3, b = -0.2;
    const fs::path file = write_pcd(dir.path / "tilted.pcd", grid(12, 12, 0.5, 0.5, a, b, 0.0), false);
    BackgroundOptions options;
    options.scanner_position_m = Eigen::Vector3d(3.0, 3.0, -20.0);
    BackgroundLoadReport report;
    const BackgroundMap map = load_background_map(file, options, &report);
    CHECK(report.scan_line_normals == 0);
    const Eigen::Vector3f expected = -Eigen::Vector3f(static_cast<float>(-a), static_cast<float>(-b), 1.0f).normalized();
    for (const auto& n : map.normals) CHECK((n - expected).norm() < 1e-4f);
}

TEST_CASE("background_map: points on a line have no plane, so their normals are +z and counted", "[background_map]") {
    TempDir dir;
    std::vector<PcdPoint> line;
    for (int i = 0; i < 10; ++i) line.push_back({1.0 * i, 0.5 * i, 2.0});
    BackgroundLoadReport report;
    const BackgroundMap map = load_background_map(write_pcd(dir.path / "line.pcd", line, false), {}, &report);
    CHECK(report.degenerate_normals == line.size());
    for (const auto& n : map.normals) CHECK(n == Eigen::Vector3f::UnitZ());
}

TEST_CASE("background_map: disc radii on a square grid, by hand", "[background_map]") {
    TempDir dir;
    const double s = 0.4;
    const int nx = 10, ny = 8;
    BackgroundLoadReport report;
    const BackgroundMap map =
        load_background_map(write_pcd(dir.path / "grid.pcd", grid(nx, ny, s, s, 0, 0, 100.0), false), {}, &report);
    CHECK(report.radii_clamped == 0);
    // r = sqrt(sum of the 4 nearest squared distances / 8):
    //   interior node: 4 neighbours at s               -> sqrt(4 s^2 / 8) = s / sqrt(2)
    //   edge node: 3 at s, then a diagonal at sqrt(2) s -> sqrt(5 s^2 / 8)
    //   corner: 2 at s, 1 at sqrt(2) s, 1 at 2 s        -> sqrt(8 s^2 / 8) = s
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const int on_edges = (i == 0 || i == nx - 1) + (j == 0 || j == ny - 1);
            const double expected = on_edges == 0 ? s / std::sqrt(2.0) : on_edges == 1 ? s * std::sqrt(5.0 / 8.0) : s;
            INFO("node " << i << ", " << j);
            CHECK(map.radii_m[static_cast<std::size_t>(j * nx + i)] == Approx(expected).epsilon(1e-5));
        }
    }
}

TEST_CASE("background_map: on a rectangular grid the interior radius is the half diagonal of a cell",
          "[background_map]") {
    TempDir dir;
    const double sx = 0.3, sy = 0.5;
    const int nx = 9, ny = 9;
    const BackgroundMap map =
        load_background_map(write_pcd(dir.path / "rect.pcd", grid(nx, ny, sx, sy), false), {});
    const double half_diagonal = std::hypot(sx, sy) / 2.0;
    for (int j = 1; j < ny - 1; ++j) {
        for (int i = 1; i < nx - 1; ++i) {
            CHECK(map.radii_m[static_cast<std::size_t>(j * nx + i)] == Approx(half_diagonal).epsilon(1e-5));
        }
    }
}

TEST_CASE("background_map: duplicates and a stray point get radii clamped to the median's band", "[background_map]") {
    TempDir dir;
    const double s = 0.4;
    const int nx = 10, ny = 8;
    auto pts = grid(nx, ny, s, s);
    const PcdPoint node = pts[4 * nx + 5];
    for (int copy = 0; copy < 4; ++copy) pts.push_back(node);  // five points stacked on one node
    pts.push_back({2.0, 1.5, 50.0});                             // a stray return 50 m up
    BackgroundLoadReport report;
    const BackgroundMap map = load_background_map(write_pcd(dir.path / "clamp.pcd", pts, false), {}, &report);
    const double median = s / std::sqrt(2.0);  // interior nodes are the majority
    CHECK(report.radii_clamped == 6);
    CHECK(map.radii_m[4 * nx + 5] == Approx(kMinRadiusOfMedian * median).epsilon(1e-5));
    for (std::size_t k = pts.size() - 5; k < pts.size() - 1; ++k) {
        CHECK(map.radii_m[k] == Approx(kMinRadiusOfMedian * median).epsilon(1e-5));
    }
    CHECK(map.radii_m.back() == Approx(kMaxRadiusOfMedian * median).epsilon(1e-5));
    // Neighbours of the stacked node still see four points at s.
    CHECK(map.radii_m[4 * nx + 4] == Approx(median).epsilon(1e-5));
}

TEST_CASE("background_map: reflectance from intensity, from the option, or the default", "[background_map]") {
    TempDir dir;
    auto pts = grid(3, 3, 1.0, 1.0);
    const std::vector<double> intensity{0, 50, 100, 200, 25, -10, 150, 175, 80};
    for (std::size_t i = 0; i < pts.size(); ++i) pts[i].intensity = intensity[i];
    const fs::path with_i = write_pcd(dir.path / "i.pcd", pts, true);

    SECTION("rho = 0.6 I / I_max, negative intensity read as 0") {
        BackgroundLoadReport report;
        const BackgroundMap map = load_background_map(with_i, {}, &report);
        CHECK(report.reflectance_from_intensity);
        const std::vector<double> expected{0.0, 0.15, 0.3, 0.6, 0.075, 0.0, 0.45, 0.525, 0.24};
        for (std::size_t i = 0; i < pts.size(); ++i) CHECK(map.reflectance[i] == Approx(expected[i]).epsilon(1e-6));
    }
    SECTION("a chosen brightest reflectance") {
        BackgroundOptions options;
        options.reflectance_at_max_intensity = 0.5;
        const BackgroundMap map = load_background_map(with_i, options);
        CHECK(map.reflectance[1] == Approx(0.5 * 50.0 / 200.0).epsilon(1e-6));
        CHECK(map.reflectance[3] == Approx(0.5).epsilon(1e-6));
    }
    SECTION("a calibrated reflectivity: rho = k I, at most 1") {
        BackgroundOptions options;
        options.reflectance_per_intensity = 0.01;  // Velodyne's byte: per cent, retro-reflectors above 100
        const BackgroundMap map = load_background_map(with_i, options);
        const std::vector<double> expected{0.0, 0.5, 1.0, 1.0, 0.25, 0.0, 1.0, 1.0, 0.8};
        for (std::size_t i = 0; i < pts.size(); ++i) CHECK(map.reflectance[i] == Approx(expected[i]).epsilon(1e-6));
    }
    SECTION("a constant reflectance overrides the intensity") {
        BackgroundOptions options;
        options.reflectance = 0.12;
        BackgroundLoadReport report;
        const BackgroundMap map = load_background_map(with_i, options, &report);
        CHECK_FALSE(report.reflectance_from_intensity);
        for (float r : map.reflectance) CHECK(r == Approx(0.12));
    }
    SECTION("no intensity field: the default reflectance") {
        const BackgroundMap map = load_background_map(write_pcd(dir.path / "no_i.pcd", pts, false), {});
        for (float r : map.reflectance) CHECK(r == Approx(kDefaultReflectance));
    }
}

TEST_CASE("background_map: a PLY map, ASCII or binary, is the same map as its PCD", "[background_map]") {
    TempDir dir;
    // A tilted plane far from the origin with varying intensity: every part of the map differs
    // from point to point.
    auto pts = grid(12, 9, 0.7, 0.5, 0.1, -0.05, 40.0, 512000.0, 4875000.0);
    for (std::size_t i = 0; i < pts.size(); ++i) pts[i].intensity = static_cast<double>((i * 37) % 200);
    const BackgroundMap pcd = load_background_map(write_pcd(dir.path / "m.pcd", pts, true), {});
    for (const bool binary : {false, true}) {
        INFO((binary ? "binary" : "ascii") << " PLY");
        const BackgroundMap ply = load_background_map(write_ply(dir.path / (binary ? "b.ply" : "a.ply"), pts, binary), {});
        REQUIRE(ply.points_world.size() == pcd.points_world.size());
        for (std::size_t i = 0; i < pts.size(); ++i) {
            CHECK((ply.points_world[i] - pcd.points_world[i]).norm() < 1e-9);
            CHECK((ply.normals[i] - pcd.normals[i]).norm() < 1e-6f);
            CHECK(ply.radii_m[i] == Approx(pcd.radii_m[i]).epsilon(1e-6));
            CHECK(ply.reflectance[i] == Approx(pcd.reflectance[i]).epsilon(1e-6));
        }
    }
    std::ofstream(dir.path / "broken.ply") << "ply\nformat ascii 1.0\nelement vertex 10\nproperty float x\nend_header\n1\n";
    CHECK_THROWS_WITH(load_background_map(dir.path / "broken.ply", {}), Contains("broken.ply"));
}

TEST_CASE("background_map: a map in any PCD encoding, organised with NaN beams, is the same map", "[background_map]") {
    // The PCD reader is read_pcd (tests/dataset/test_pcd_file.cpp): here only that the map uses
    // what it reads, whatever encoding PCL wrote.
    TempDir dir;
    const auto pts = grid(12, 9, 0.7, 0.5, 0.1, -0.05, 40.0);
    pcl::PointCloud<pcl::PointXYZI> organised(12, 10);
    for (std::size_t i = 0; i < pts.size(); ++i) {
        organised[i].x = static_cast<float>(pts[i].x);
        organised[i].y = static_cast<float>(pts[i].y);
        organised[i].z = static_cast<float>(pts[i].z);
        organised[i].intensity = static_cast<float>(i % 50);
    }
    for (std::size_t i = pts.size(); i < organised.size(); ++i) organised[i].x = std::numeric_limits<float>::quiet_NaN();
    organised.is_dense = false;
    REQUIRE(pcl::io::savePCDFileASCII((dir.path / "a.pcd").string(), organised) == 0);
    REQUIRE(pcl::io::savePCDFileBinary((dir.path / "b.pcd").string(), organised) == 0);
    REQUIRE(pcl::io::savePCDFileBinaryCompressed((dir.path / "c.pcd").string(), organised) == 0);
    BackgroundLoadReport binary_report;
    const BackgroundMap binary = load_background_map(dir.path / "b.pcd", {}, &binary_report);
    CHECK(binary_report.nonfinite_dropped == 12);
    REQUIRE(binary.points_world.size() == pts.size());
    BackgroundLoadReport report;
    const BackgroundMap compressed = load_background_map(dir.path / "c.pcd", {}, &report);
    CHECK(report.nonfinite_dropped == 12);
    CHECK(compressed.points_world == binary.points_world);
    CHECK(compressed.normals == binary.normals);
    CHECK(compressed.radii_m == binary.radii_m);
    CHECK(compressed.reflectance == binary.reflectance);
    // PCL writes ascii floats to 8 digits, not always enough to come back to the same float.
    const BackgroundMap ascii = load_background_map(dir.path / "a.pcd", {}, &report);
    CHECK(report.nonfinite_dropped == 12);
    REQUIRE(ascii.points_world.size() == pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) CHECK((ascii.points_world[i] - binary.points_world[i]).norm() < 1e-5);
}

TEST_CASE("background_map: bad files are InputErrors naming the file", "[background_map]") {
    TempDir dir;
    SECTION("missing") {
        const fs::path file = dir.path / "absent.pcd";
        try {
            load_background_map(file, {});
            FAIL("no error");
        } catch (const InputError& e) {
            CHECK(e.file() == file.string());
            CHECK_THAT(e.problem(), Contains("no such file"));
        }
    }
    SECTION("too few points") {
        CHECK_THROWS_AS(load_background_map(write_pcd(dir.path / "four.pcd", grid(2, 2, 1, 1), false), {}),
                        InputError);
    }
}

TEST_CASE("background_map: the recorded Autzen map", "[background_map][data]") {
    const fs::path file = ladarsim::test::shared_data("autzen/autzen_trim.pcd");
    if (!fs::exists(file)) LADARSIM_SKIP("shared data not present: " << file);
    BackgroundLoadReport report;
    const auto t0 = std::chrono::steady_clock::now();
    const BackgroundMap map = load_background_map(file, {}, &report);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    WARN("autzen_trim.pcd: " << map.points_world.size() << " points in " << seconds << " s, "
                             << report.degenerate_normals << " degenerate normals, " << report.radii_clamped
                             << " radii clamped");

    // The counts and the extent are those of the data's README.
    REQUIRE(map.points_world.size() == 110000);
    Eigen::AlignedBox3d box;
    for (const auto& p : map.points_world) box.extend(p);
    CHECK(box.min().x() == Approx(0.5).margin(0.05));
    CHECK(box.max().x() == Approx(359.4).margin(0.05));
    CHECK(box.min().y() == Approx(10.7).margin(0.05));
    CHECK(box.max().y() == Approx(182.2).margin(0.05));
    CHECK(box.min().z() == Approx(123.8).margin(0.05));
    CHECK(box.max().z() == Approx(158.7).margin(0.05));

    // Every normal unit length and not pointing down; the brightest point gets exactly 0.6.
    CHECK(report.reflectance_from_intensity);
    bool all_unit_and_up = true;
    for (const auto& n : map.normals) all_unit_and_up = all_unit_and_up && std::abs(n.norm() - 1.0f) < 1e-5f && n.z() >= 0.0f;
    CHECK(all_unit_and_up);
    const auto [lo, hi] = std::minmax_element(map.reflectance.begin(), map.reflectance.end());
    CHECK(*lo >= 0.0f);
    CHECK(*hi == Approx(0.6));
}

TEST_CASE("background_map: a heading turns the placed map and its scanner about the points' centroid", "[background_map]") {
    // A tilted 12 x 8 grid: turned a quarter, x - cx becomes -(y - cy) and y - cy becomes x - cx,
    // the tilt's normal turns with it, and a scanner beside the map turns too (the discs that
    // faced it still face it).
    TempDir dir;
    const double a = 0.3, b = -0.2;
    const fs::path file = write_pcd(dir.path / "tilted.pcd", grid(12, 8, 0.5, 0.5, a, b, 0.0, 10.0, 20.0), false);
    BackgroundOptions options;
    options.offset_m = Eigen::Vector3d(100.0, 0.0, 5.0);
    options.scanner_position_m = Eigen::Vector3d(100.0, 20.0, -20.0);
    const BackgroundMap still = load_background_map(file, options);
    options.heading_deg = 90.0;
    const BackgroundMap turned = load_background_map(file, options);
    REQUIRE(turned.points_world.size() == still.points_world.size());
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& p : still.points_world) centre += p / static_cast<double>(still.points_world.size());
    for (std::size_t i = 0; i < still.points_world.size(); ++i) {
        const Eigen::Vector3d d = still.points_world[i] - centre;
        CHECK((turned.points_world[i] - (centre + Eigen::Vector3d(-d.y(), d.x(), d.z()))).norm() < 1e-9);
        const Eigen::Vector3f n = still.normals[i];
        CHECK((turned.normals[i] - Eigen::Vector3f(-n.y(), n.x(), n.z())).norm() < 1e-4f);
        CHECK(turned.radii_m[i] == Approx(still.radii_m[i]).epsilon(1e-5));
    }
}
