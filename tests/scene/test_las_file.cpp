// LAS reading: hand-built files of every supported format, and the recorded Autzen LAS against
// its PCD conversion.
#include <catch2/catch.hpp>

#include <cstring>
#include <fstream>

#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include "ladarsim/core/input_error.h"
#include "ladarsim/scene/background_map.h"
#include "ladarsim/scene/las_file.h"
#include "../support/scratch_dir.h"
#include "../support/shared_data.h"
#include "../support/skip.h"

using namespace ladarsim;

namespace {

template <typename T>
void put(std::vector<char>& b, std::size_t at, T v) {
    if (b.size() < at + sizeof v) b.resize(at + sizeof v);
    std::memcpy(b.data() + at, &v, sizeof v);
}

/// A LAS 1.`minor` file of `format` holding two points, written field by field from the specification.
std::filesystem::path write_las(const std::filesystem::path& file, int minor, int format) {
    const std::uint16_t header = minor == 4 ? 375 : 227;
    const std::uint16_t length = format <= 3 ? (format == 0 ? 20 : format == 1 ? 28 : format == 2 ? 26 : 34)
                                             : (format == 6 ? 30 : format == 7 ? 36 : 38);
    std::vector<char> b(header, 0);
    std::memcpy(b.data(), "LASF", 4);
    b[24] = 1;
    b[25] = static_cast<char>(minor);
    put<std::uint16_t>(b, 94, header);
    put<std::uint32_t>(b, 96, header);
    b[104] = static_cast<char>(format);
    put<std::uint16_t>(b, 105, length);
    put<std::uint32_t>(b, 107, minor == 4 ? 0u : 2u);
    if (minor == 4) put<std::uint64_t>(b, 247, 2);
    put<double>(b, 131, 0.01);
    put<double>(b, 139, 0.01);
    put<double>(b, 147, 0.001);
    put<double>(b, 155, 1000.0);
    put<double>(b, 163, 2000.0);
    put<double>(b, 171, 0.0);
    const std::int32_t xyz[2][3] = {{150, -250, 12345}, {-1, 0, -7}};
    for (int p = 0; p < 2; ++p) {
        const std::size_t r = header + static_cast<std::size_t>(p) * length;
        b.resize(r + length, 0);
        for (int k = 0; k < 3; ++k) put<std::int32_t>(b, r + 4 * k, xyz[p][k]);
        put<std::uint16_t>(b, r + 12, static_cast<std::uint16_t>(100 * (p + 1)));
        b[r + (format <= 3 ? 15 : 16)] = static_cast<char>(format <= 3 ? 2 : 6);
    }
    std::ofstream(file, std::ios::binary).write(b.data(), static_cast<std::streamsize>(b.size()));
    return file;
}

}  // namespace

TEST_CASE("LAS formats 0-3 and 6-8, versions 1.2-1.4: scaled coordinates, intensity, class", "[las]") {
    const test::ScratchDir dir;
    for (int minor : {2, 3, 4}) {
        for (int format : {0, 1, 2, 3, 6, 7, 8}) {
            if (format >= 6 && minor < 4) continue;
            INFO("LAS 1." << minor << " format " << format);
            const auto cloud = scene::read_las(write_las(dir / "t.las", minor, format));
            REQUIRE(cloud.points.size() == 2);
            CHECK(cloud.points[0].isApprox(Eigen::Vector3d(1001.5, 1997.5, 12.345), 1e-12));
            CHECK(cloud.points[1].isApprox(Eigen::Vector3d(999.99, 2000.0, -0.007), 1e-12));
            CHECK(cloud.intensity[1] == 200);
            CHECK(cloud.classification[0] == (format <= 3 ? 2 : 6));
        }
    }
    std::ofstream(dir / "bad.las") << "LASX and more bytes than a header needs .........................................";
    CHECK_THROWS_AS(scene::read_las(dir / "bad.las"), InputError);
    CHECK_THROWS_AS(scene::read_las(dir / "missing.las"), InputError);
}

TEST_CASE("the Autzen LAS and its PCD conversion hold the same points", "[las]") {
    const std::filesystem::path base = test::shared_data("autzen");
    if (!std::filesystem::exists(base / "autzen_trim.las")) LADARSIM_SKIP("shared data not present: " << base);
    const auto las = scene::read_las(base / "autzen_trim.las");
    pcl::PointCloud<pcl::PointXYZ> pcd;
    REQUIRE(pcl::io::loadPCDFile(base.string() + "/autzen_trim.pcd", pcd) == 0);
    REQUIRE(las.points.size() == 110000);
    REQUIRE(pcd.size() == las.points.size());
    // Its README: x_m = (X_ft - 636000) * 0.3048, y_m = (Y_ft - 848900) * 0.3048, z_m = Z_ft * 0.3048.
    double worst = 0.0;
    for (std::size_t i = 0; i < las.points.size(); ++i) {
        const Eigen::Vector3d& f = las.points[i];
        const Eigen::Vector3d m((f.x() - 636000.0) * 0.3048, (f.y() - 848900.0) * 0.3048, f.z() * 0.3048);
        worst = std::max(worst, (m - Eigen::Vector3d(pcd[i].x, pcd[i].y, pcd[i].z)).norm());
    }
    CHECK(worst < 1e-3);  // float32 in the PCD
    // The same conversion as background-map options loads the LAS where the PCD loads.
    scene::BackgroundOptions options;
    options.scale = 0.3048;
    options.offset_m = Eigen::Vector3d(-636000.0 * 0.3048, -848900.0 * 0.3048, 0.0);
    const auto from_las = scene::load_background_map(base / "autzen_trim.las", options);
    const auto from_pcd = scene::load_background_map(base / "autzen_trim.pcd", scene::BackgroundOptions{});
    REQUIRE(from_las.points_world.size() == from_pcd.points_world.size());
    CHECK((from_las.points_world[123] - from_pcd.points_world[123]).norm() < 1e-3);
}
