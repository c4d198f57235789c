// EN 17037's sunlight exposure: how long the sun reaches a reference point inside a window
// (the centre of its width, 1.2 m or more above the floor and 0.3 m above the sill) on one day
// from 1 February to 21 March under a cloudless sky, counting only the sun above a minimum
// altitude (the standard gives it by latitude); levels by the hours: minimum 1.5, medium 3,
// high 4.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/sky.hpp"
#include "radiosity/vec.hpp"

#include <memory>
#include <string>
#include <vector>

namespace rad {

class RayScene;
class SpecularSurfaces;

struct SunlightDay {
    LocalTime date;  // the day (hour unused)
    int minutes = 0; // minutes the sun reached the point, sampled at each minute's middle
    double hours() const { return minutes / 60.0; }
};

struct SunlightExposure {
    std::vector<SunlightDay> days; // in order
    SunlightDay best;              // the day with the most (the first of equals)
    // "high" (4 h or more), "medium" (3 h), "minimum" (1.5 h) or "none", for the best day.
    const char* level() const;
};

// The sun reaches `point` when it stands `min_altitude_deg` or more above the horizon and a ray
// toward its centre leaves the scene straight (through openings and panes of glass; a
// mirror's image is not the sun's exposure). Every minute of each day of `days` (local standard
// time at `where`), in `frame`'s compass. Parallel over the days; deterministic.
class SunlightScene {
  public:
    explicit SunlightScene(const radfmt::MeshData& mesh);
    ~SunlightScene();
    SunlightExposure exposure(const Vec3& point, const Location& where, const SkyFrame& frame,
                              const std::vector<LocalTime>& days, double min_altitude_deg) const;

  private:
    std::unique_ptr<RayScene> scene_;
    std::unique_ptr<SpecularSurfaces> specular_;
};

// The days EN 17037 lets one choose from: 1 February to 21 March of `year`.
std::vector<LocalTime> en17037_sunlight_days(int year);

} // namespace rad
