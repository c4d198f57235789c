// Radiance's view options: -vp -vd -vu -vh -vv, inline or from a view file.
#include "radiosity/view.hpp"

#include "radiosity/error.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/text_input.hpp"

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

namespace rad {

View parse_view(const std::string& text, const FileLoc& source, View view) {
    std::istringstream in(text);
    std::string word;
    auto number = [&](const std::string& option) {
        std::string token;
        double value = 0;
        if (!(in >> token)) throw InputError(source, option + " needs a number");
        if (!parse_number(token, value))
            throw InputError(source, option + ": '" + token + "' is not a number");
        if (!std::isfinite(value)) throw InputError(source, option + " must be finite");
        return value;
    };
    auto vector = [&](const std::string& option) {
        const double x = number(option), y = number(option), z = number(option);
        return Vec3{x, y, z};
    };
    while (in >> word) {
        if (word == "rvu" || word == "-vtv" || word.rfind("#", 0) == 0) continue;
        if (word == "-vp")
            view.position = vector(word);
        else if (word == "-vd")
            view.direction = vector(word);
        else if (word == "-vu")
            view.up = vector(word);
        else if (word == "-vh")
            view.horizontal_deg = number(word);
        else if (word == "-vv")
            view.vertical_deg = number(word);
        else
            throw InputError(source,
                             "unknown view option '" + word + "' (use -vp -vd -vu -vh -vv)");
    }
    if (length(view.direction) == 0) throw InputError(source, "view direction -vd is zero");
    if (length(cross(view.direction, view.up)) <= 1e-9 * length(view.direction) * length(view.up))
        throw InputError(source, "view up -vu is zero or parallel to the direction -vd");
    for (double angle : {view.horizontal_deg, view.vertical_deg})
        if (!(angle > 0 && angle < 180))
            throw InputError(source, "view angles -vh and -vv must be between 0 and 180 degrees");
    return view;
}

View read_view_file(const std::string& path) {
    // A folder, /dev/zero or a failed read is an error naming the file, never the default
    // camera; a view file that sets nothing is one too.
    LineReader in(path);
    std::string line;
    int set = 0;
    View view;
    while (in.next(line)) {
        const int number = in.line_number();
        const auto hash = line.find('#');
        if (hash != std::string::npos) line = line.substr(0, hash);
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        view = parse_view(line, FileLoc{path, number}, view);
        ++set;
    }
    if (set == 0) throw InputError(FileLoc{path}, "holds no view (-vp, -vd, ... on a line)");
    return view;
}

Vec3 view_ray(const View& view, double u, double v) {
    constexpr double kDeg = std::numbers::pi / 180;
    const Vec3 dir = normalized(view.direction);
    const Vec3 right = normalized(cross(dir, view.up));
    const Vec3 up = cross(right, dir);
    const double cx = (2 * u - 1) * std::tan(0.5 * view.horizontal_deg * kDeg);
    const double cy = (1 - 2 * v) * std::tan(0.5 * view.vertical_deg * kDeg);
    return normalized(dir + right * cx + up * cy);
}

} // namespace rad
