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

// Appends an SVG path command and its point to `d`: "M12.00 3.50" (`mark` 'M' or 'L'). Piece by
// piece: GCC 12 warns, wrongly, of overlap in "M" + std::string.
inline void path_to(std::string& d, char mark, double x, double y) {
    d += mark;
    d += px(x);
    d += ' ';
    d += px(y);
}

// A number the user wrote or a round one (a requirement, a contour level, a legend tick), as
// short as it is.
inline std::string short_number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

} // namespace rad::report_text
