#pragma once
// Models ladarsim builds from code, so the default scenario needs no downloaded assets. Reflectances
// are 1550 nm estimates (docs/materials in ../shared/design/physics.md); scenarios override them.
#include <filesystem>

#include "ladarsim/scene/mesh.h"

namespace ladarsim::scene {

/// Revolutions per second of the bundled quadcopter's rotors (5580 rpm, within a small drone's
/// 4000-10000 rpm): not a multiple of the 10 and 20 Hz frame rates, so that a frame does not
/// always catch the blades at the same angle.
inline constexpr double kRotorRevolutionsPerSecond = 93.0;

/// A 0.30 m quadcopter (rotor tip to rotor tip along x and y), centred on the origin, nose +x:
/// a white plastic body and arms (0.6, like a consumer quadcopter's shell) with black plastic
/// motors and two-bladed rotors (0.06). One animation turns the rotors at
/// kRotorRevolutionsPerSecond, neighbours in opposite senses: each pulse sees the blades where
/// they are when it is fired.
Model make_quadcopter();

/// Rolling ground from x = -100 m to 3000 m and y = -600 m to 600 m on a 20 m grid, within 2 m
/// of z = 0 except a ridge 80-150 m high between x = 2000 m and 2800 m (the backdrop behind a
/// 2 km target). Grass and soil, 0.3.
Model make_terrain();

/// A square plate of side `side_m` in the model's y-z plane, centred on the origin, facing +-x:
/// the paper's abstraction of a target.
Model make_plate(double side_m, double reflectance);

/// A sphere of the given diameter centred on the origin (a UV sphere of 32 segments), one
/// material of the given reflectance.
Model make_sphere(double diameter_m, double reflectance);

/// A closed box, base on z = 0 and centred on the origin in x and y; concrete, 0.35.
Model make_box_building(double length_m, double width_m, double height_m);

/// A trunk and a conical crown, base on z = 0: bark 0.25, foliage 0.3.
Model make_tree(double height_m);

/// Wingbeat of the bundled bird: 6 Hz, a pigeon's or a crow's (birds of 0.3-0.6 m span beat
/// their wings 3-8 times a second), below the 10 Hz Nyquist limit of a 20 Hz frame rate.
inline constexpr double kBirdWingbeatHz = 6.0;
/// The wings' angle above the horizontal is kWingMeanDeg + kWingAmplitudeDeg * sin(2 pi f t):
/// from 25 deg below to 65 deg above, higher on the upstroke as a flapping bird's are.
inline constexpr double kWingMeanDeg = 20.0;
inline constexpr double kWingAmplitudeDeg = 45.0;

/// A bird of the given wingspan (0.2-0.6 m): an ellipsoid body and two flat wings; feathers 0.35.
/// The mesh holds the wings level; one animation beats them about hinges at the body at
/// kBirdWingbeatHz.
Model make_bird(double wingspan_m);

/// A light aircraft, 7.2 m long, 11 m span: box fuselage, wing, tailplane and fin; white paint 0.6.
Model make_light_aircraft();

/// An airliner the size of an A320 (37.6 m long, 34 m span); white paint 0.6.
Model make_airliner();

/// A cloud: a closed, flattened ellipsoid (diameter x diameter x 0.6 diameter) whose material is a
/// volume medium of the given extinction and a lidar ratio of 20 sr (water cloud).
Model make_cloud(double diameter_m, double extinction_per_m);

/// Writes quadcopter.glb, terrain.glb, building.glb (20 x 12 x 15 m), tree.glb (8 m),
/// tower.glb (30 x 30 x 80 m), bird.glb (0.4 m), light_aircraft.glb, airliner.glb and cloud.glb
/// (60 m, 30 /km) into `dir`.
void write_default_assets(const std::filesystem::path& dir);

}  // namespace ladarsim::scene
