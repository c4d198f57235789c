// The sky and the sun: where the sun is (NREL's Solar Position Algorithm), how bright each
// direction of the sky is (the CIE standard general skies, the traditional CIE overcast sky,
// Perez's all-weather sky, a uniform sky) and the ground below the horizon. Directions are
// given in the scene's frame: +Y up, north along -Z turned by the frame's north angle.
#pragma once
#include "radiosity/vec.hpp"

#include <array>
#include <optional>
#include <string>

namespace rad {

// Where and when, for the sun: local standard time at a time zone (hours east of UTC).
struct Location {
    double latitude = 0;     // degrees, north positive
    double longitude = 0;    // degrees, east positive
    double time_zone = 0;    // hours, east of UTC positive (UTC-7: -7)
    double elevation = 0;    // m
    double pressure = 1010;  // mbar, for refraction
    double temperature = 10; // degrees C, for refraction
};
struct LocalTime {
    int year = 2000, month = 1, day = 1;
    double hour = 12; // local standard time, fractional hours
};

// The sun seen from the ground: topocentric, refraction included (SPA, Reda and Andreas
// 2008; within 0.0003 degrees from -2000 to 6000). Azimuth from north towards east.
struct SunPosition {
    double zenith = 90, azimuth = 180; // degrees
    double earth_sun_distance = 1;     // AU
    double altitude() const { return 90 - zenith; }
};
// `delta_t`: TT - UT in seconds (about 69 in the 2020s; SPA's own example uses 67).
SunPosition solar_position(const Location& where, const LocalTime& when, double delta_t = 69);

// The scene's compass: +Y up; true north is -Z turned `north_deg` degrees towards +X
// (clockwise seen from above).
struct SkyFrame {
    double north_deg = 0;
    Vec3 north() const;
    Vec3 east() const;
    // The unit direction at `altitude` and `azimuth` (degrees; azimuth from north to east).
    Vec3 direction(double altitude_deg, double azimuth_deg) const;
    // Altitude and azimuth (degrees) of a unit direction.
    void angles(const Vec3& d, double& altitude_deg, double& azimuth_deg) const;
};

// Luminance (cd/m^2) of every direction of the sky above the horizon, and of the ground
// below it (uniform: reflectance x the global horizontal illuminance / pi). The sun's disc
// is not part of it (see sun_illuminance).
class Sky {
  public:
    enum class Model { uniform, cie_overcast, cie_standard, perez };
    // Luminance relative to the zenith (CIE) or in the model's own scale (Perez), for a
    // direction of altitude > 0 given by its zenith angle and angle to the sun (radians).
    double relative(double zenith, double to_sun) const;
    // The same from their cosines (what a direction gives without trigonometry).
    double relative_cos(double cos_zenith, double cos_to_sun) const;
    // Luminance towards the unit direction `d` (in `frame`): sky above, ground below.
    double luminance(const Vec3& d) const;
    double luminance_at(double altitude_deg, double azimuth_deg) const; // above the horizon
    // The sky's illuminance on an unobstructed horizontal plane (lux), its integral.
    double horizontal_illuminance() const { return horizontal_; }
    double zenith_luminance() const { return scale_ * relative(0, sun_zenith_rad()); }
    // Illuminance of the sun's beam on a plane facing it (lux); 0 when the model has no sun
    // or the sun is down.
    double sun_normal_illuminance() const { return sun_normal_lux_; }
    Vec3 sun_direction() const { return sun_direction_; }
    bool sun_up() const { return sun_.zenith < 90; }
    double ground_luminance() const { return ground_; }
    const SkyFrame& frame() const { return frame_; }
    Model model() const { return model_; }
    std::string describe() const;

    // A sky of luminance `luminance` everywhere above the horizon.
    static Sky uniform(double luminance, const SkyFrame& frame, double ground_reflectance);
    // Moon and Spencer's overcast sky, (1 + 2 cos Z) / 3 of the zenith's, with horizontal
    // illuminance `lux` (7 pi Lz / 9).
    static Sky cie_overcast(double lux, const SkyFrame& frame, double ground_reflectance);
    // The CIE standard general sky `type` (1..15, ISO 15469:2004 / CIE S 011) with the sun
    // at `sun`, scaled to horizontal illuminance `lux` (of the sky alone).
    static Sky cie_standard(int type, const SunPosition& sun, double lux, const SkyFrame& frame,
                            double ground_reflectance);
    // Perez's all-weather sky (1993) from direct normal and diffuse horizontal irradiance
    // (W/m^2), with the sun: Perez's 1990 luminous efficacies give the illuminances
    // (`dew_point` in degrees C for the precipitable water; `day_of_year` for the Earth's
    // distance). The sun's beam is its direct normal illuminance. At the model's edges (see
    // docs/daylight.md): with no diffuse irradiance and the sun up, the beam keeps the clearest
    // bin's efficacy (it was dropped); where Perez's distribution for the hour's clearness and
    // brightness is negative over the whole sky, the brightness its parameters are taken at
    // is raised until it is not (gendaylit's rule for low brightness, extended), and said by
    // adjusted().
    static Sky perez(double direct_normal, double diffuse_horizontal, const SunPosition& sun,
                     int day_of_year, double dew_point, const SkyFrame& frame,
                     double ground_reflectance);
    // A Perez sky whose distribution needed a raised brightness (perez): what was done, else "".
    const std::string& adjusted() const { return adjusted_; }

    // A clear day for a place and time with no weather file: CIE type 12 (the standard
    // clear sky) with the IES clear-sky daylight availability (IES Lighting Handbook): the
    // sky's horizontal illuminance 800 + 15500 sqrt(sin a) lux and the sun's beam
    // 127500 exp(-0.21 / sin a) lux at solar altitude a (dark with the sun down). The viewer
    // page relights with the same sky.
    static Sky clear(const SunPosition& sun, const SkyFrame& frame, double ground_reflectance);
    // The same for the IES Lighting Handbook's other two daylight-availability conditions: a
    // partly cloudy day (CIE type 7, the sky 300 + 45000 sin a lux, the beam 127500 exp(-0.80
    // / sin a) lux) and an overcast one (CIE type 1, 300 + 21000 sin a lux, no beam).
    enum class Day { clear, partly_cloudy, overcast };
    static Sky of_day(Day day, const SunPosition& sun, const SkyFrame& frame,
                      double ground_reflectance);
    // A day's CIE type, its sky's horizontal illuminance A + B sin(a)^p as {A, B, p}, and its
    // beam's extinction c in 127500 exp(-c / sin a) (0: no beam): what the viewer page
    // evaluates as the chain does.
    struct DayAvailability {
        int cie_type;
        std::array<double, 3> diffuse;
        double extinction;
        const char* name;
    };
    static DayAvailability availability(Day day);

    // The 15 CIE types' gradation and indicatrix parameters a, b, c, d, e.
    static std::array<double, 5> cie_parameters(int type);

  private:
    double sun_zenith_rad() const;
    void normalise_to(double lux);
    void normalise_to(double lux, double integral); // relative_integral() already known
    double relative_integral() const;               // the horizontal illuminance at scale 1
    void set_ground(double reflectance);
    Model model_ = Model::uniform;
    SkyFrame frame_;
    SunPosition sun_;
    Vec3 sun_direction_{0, 1, 0};
    std::array<double, 5> p_{}; // the model's parameters a..e
    double scale_ = 1;          // luminance = scale_ x relative
    double cie_zenith_ = 1;     // CIE: phi(0) f(Zs), relative's denominator
    double horizontal_ = 0, ground_ = 0, sun_normal_lux_ = 0;
    std::string name_, adjusted_;
};

// The Earth's eccentricity correction (r0 / r)^2 on `day_of_year` (Spencer 1971).
double eccentricity(int day_of_year);
// Kasten and Young's relative optical air mass at a zenith angle (degrees).
double air_mass(double zenith_deg);

// A sky named on a command line: "uniform[:L]" (L cd/m^2, default 10000 / pi),
// "cie-overcast[:LUX]", "cie:TYPE[:LUX]" (LUX: the sky's horizontal illuminance, default
// 10000), "perez:DNI,DHI" (W/m^2), "clear" (Sky::clear). The CIE standard and Perez skies need
// `sun`; Perez also the day of the year. InputError naming what is wrong and the forms accepted,
// and for a value past what a sky keeps (L over 1e6 cd/m^2, LUX over 1e6 lx, DNI or DHI over
// 1500 W/m^2, any below 0).
Sky parse_sky(const std::string& spec, const SunPosition* sun, int day_of_year,
              const SkyFrame& frame, double ground_reflectance);
// "LAT,LON,TZ[,ELEVATION]" (degrees north, east, hours east of UTC, m from -500 to 9000).
Location parse_location(const std::string& text);
// "YYYY-MM-DD" (a day of the calendar, year 1 to 9999) and "HH:MM" (local standard time,
// 00:00 to 24:00) into a LocalTime.
LocalTime parse_local_time(const std::string& date, const std::string& time);
// "ALT,AZ" degrees (azimuth from north towards east) into a sun position.
SunPosition parse_sun(const std::string& text);
// The sun a command line names: --sun ALT,AZ, or --date and --time at --location (or, without
// it, the place of the weather file `epw`); none when neither is given. Sets `day_of_year`
// (172 without a date). InputError for what does not go together.
struct SunArguments {
    std::string sun, date, time, location, epw;
};
std::optional<SunPosition> sun_from(const SunArguments& a, int& day_of_year);

} // namespace rad
