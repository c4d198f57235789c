// Numbers as the report's page writes them (internal header).
#pragma once
#include <cstdio>
#include <string>

namespace rad::report_text {

// `decimals` after the point, no exponent.
inline std::string fixed(double v, int decimals) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, v);
    return text;
}

// An SVG coordinate in pixels.
inline std::string px(double v) {
    return fixed(v, 2);
}

// A number the user wrote or a round one (a requirement, a contour level, a legend tick), as
// short as it is.
inline std::string short_number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

} // namespace rad::report_text
