#pragma once
// A recorded point cloud (PCD) turned into oriented, sized, coloured discs for the ray tracer.
#include <cstddef>
#include <filesystem>
#include <optional>

#include <Eigen/Core>

#include "ladarsim/scene/scene.h"

namespace ladarsim::scene {

struct BackgroundOptions {
    /// Multiplies every coordinate of the file first: its units in metres (0.3048 for a map in
    /// international feet).
    double scale = 1.0;
    /// Added to every (scaled) point, so a map in local coordinates can be placed in the world.
    Eigen::Vector3d offset_m = Eigen::Vector3d::Zero();
    /// Turns the placed map about the vertical through its points' centroid, from +x towards +y
    /// (as an object's yaw), so that one survey can be seen from many directions; the scanner
    /// position turns with it. 0 leaves every point exactly where scale and offset put it.
    double heading_deg = 0.0;
    /// Neighbours (the point itself included) in each local plane fit for the normal.
    int normal_neighbours = 8;
    /// When set, every point gets this reflectance and the file's intensity is ignored.
    std::optional<double> reflectance;
    /// Reflectance given to the file's highest intensity when reflectance comes from intensity:
    /// rho = reflectance_at_max_intensity * I / I_max. 0.6 is the upper end of the 1550 nm
    /// estimates for the bright surfaces of an airborne scan (concrete, light roofing, grass);
    /// recorded intensity also carries range and incidence effects, so this is a rough map.
    double reflectance_at_max_intensity = 0.6;
    /// When set, rho = min(1, reflectance_per_intensity * I) instead: for sensors whose intensity
    /// is a calibrated reflectivity, e.g. 0.01 for Velodyne's byte (0-100 % diffuse, above 100
    /// retro-reflectors).
    std::optional<double> reflectance_per_intensity;
    /// Where the scanner that recorded the map stood (world coordinates, after scale and offset,
    /// before the heading turns it with the map),
    /// for maps from a ground-based scanner: normals are turned to face it instead of up, and a
    /// point whose plane fit the scanner would see edge-on (neighbours along one scan line, spread
    /// only by range noise: an artefact of the sampling) gets a disc facing the scanner.
    /// Unset: an airborne survey.
    std::optional<Eigen::Vector3d> scanner_position_m;
};

/// What loading found, for the log and for tests.
struct BackgroundLoadReport {
    std::size_t points_loaded = 0;
    std::size_t nonfinite_dropped = 0;     ///< points with a NaN/inf coordinate
    std::size_t degenerate_normals = 0;    ///< neighbourhood not spanning a plane: normal set to +z (or facing the scanner)
    std::size_t scan_line_normals = 0;     ///< with a scanner position: fits seen edge-on from it, replaced
    std::size_t radii_clamped = 0;         ///< disc radii pulled into [0.25, 3] x the median radius
    bool reflectance_from_intensity = false;
};

/// Disc radius of the map's points is sqrt((d1^2 + d2^2 + d3^2 + d4^2) / 8), d1..d4 the distances
/// to the four nearest neighbours: on a rectangular grid of spacings sx, sy it is the half
/// diagonal sqrt(sx^2 + sy^2) / 2, the smallest disc about a node that covers its cell, so
/// neighbouring discs overlap just enough to leave no holes for rays to leak through. Radii are
/// then clamped to [0.25, 3] x the map's median radius: stacked duplicate points would otherwise
/// get vanishing discs, and an isolated stray return a disc filling the sky.
inline constexpr double kMinRadiusOfMedian = 0.25;
inline constexpr double kMaxRadiusOfMedian = 3.0;

/// Reads a PCD file (any read_pcd reads: fields x y z, optional intensity), a PLY file (vertex
/// properties x y z, optional intensity; any numeric type; ASCII or binary) or an uncompressed LAS
/// file (formats 0-3, 6-8; intensity used) into a BackgroundMap:
/// points offset into the world (double precision), unit normals from a least-squares plane
/// through the `normal_neighbours` nearest points, flipped to point up (+z) because the map is an
/// airborne, top-down scan; disc radii as above; reflectance from intensity when the file has it
/// (and `options.reflectance` is unset), else `options.reflectance` or kDefaultReflectance.
/// Throws InputError naming the file for a missing, unreadable or empty file.
BackgroundMap load_background_map(const std::filesystem::path& file, const BackgroundOptions& options,
                                  BackgroundLoadReport* report = nullptr);

}  // namespace ladarsim::scene
