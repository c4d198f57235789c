// EN 17037's sunlight exposure (sunlight_exposure.hpp): the minutes of each day the sun reaches
// a point, and the level of the best day.
#include "radiosity/sunlight_exposure.hpp"

#include "radiosity/rays.hpp"
#include "radiosity/specular.hpp"

#include <tbb/parallel_for.h>

#include <cmath>
#include <numbers>

namespace rad {
namespace {
// A ray toward the sun counts when it leaves the scene within this of the sun's centre: only a
// straight path does (a pane keeps the direction; a mirror turns it).
const double kStraight = std::cos(1e-6);

int days_in(int year, int month) {
    static constexpr int days[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    return month == 2 && leap ? 29 : days[month - 1];
}
} // namespace

const char* SunlightExposure::level() const {
    if (best.hours() >= 4) return "high";
    if (best.hours() >= 3) return "medium";
    if (best.hours() >= 1.5) return "minimum";
    return "none";
}

std::vector<LocalTime> en17037_sunlight_days(int year) {
    std::vector<LocalTime> out;
    for (int month = 2; month <= 3; ++month)
        for (int day = 1; day <= (month == 2 ? days_in(year, 2) : 21); ++day)
            out.push_back({year, month, day, 12});
    return out;
}

SunlightScene::SunlightScene(const radfmt::MeshData& mesh)
    : scene_(std::make_unique<RayScene>(mesh)),
      specular_(std::make_unique<SpecularSurfaces>(mesh)) {}

SunlightScene::~SunlightScene() = default;

SunlightExposure SunlightScene::exposure(const Vec3& point, const Location& where,
                                         const SkyFrame& frame, const std::vector<LocalTime>& days,
                                         double min_altitude_deg) const {
    SunlightExposure out;
    out.days.resize(days.size());
    tbb::parallel_for(std::size_t(0), days.size(), [&](std::size_t d) {
        auto& day = out.days[d];
        day.date = days[d];
        for (int minute = 0; minute < 24 * 60; ++minute) {
            LocalTime when = days[d];
            when.hour = (minute + 0.5) / 60;
            const auto sun = solar_position(where, when);
            if (sun.altitude() < min_altitude_deg) continue;
            const Vec3 toward = frame.direction(sun.altitude(), sun.azimuth);
            bool reached = false;
            follow_specular(
                *scene_, *specular_, point, toward, radfmt::Rgb{{1, 1, 1}}, kDefaultSpecularDepth,
                [](const PathHit&) {},
                [&](const Vec3& leaving, const radfmt::Rgb& w) {
                    reached = reached || (dot(leaving, toward) >= kStraight &&
                                          (w[0] > 0 || w[1] > 0 || w[2] > 0));
                });
            day.minutes += reached;
        }
    });
    if (!out.days.empty()) out.best = out.days.front();
    for (const auto& day : out.days)
        if (day.minutes > out.best.minutes) out.best = day;
    return out;
}

} // namespace rad
