// The viewer page: HTML around the embedded glb, the camera, and the bundled viewer script.
#include "radiosity/bake.hpp"
#include "radiosity/base64.hpp"
#include "radiosity/error.hpp"

#include <string_view>

// The bundled viewer (web/viewer/main.js with three.js), put into the library at build time
// by the assembler (viewer_script.S); empty when the build had no web/node_modules.
extern "C" const char radiosity_viewer_script[];
extern "C" const char radiosity_viewer_script_end[];

namespace rad {

namespace {

// Text inside <script> or <title> must not close it early.
std::string escape_for_html(std::string_view text, std::string_view closing) {
    std::string out;
    out.reserve(text.size());
    std::size_t from = 0;
    for (std::size_t at; (at = text.find(closing, from)) != std::string_view::npos; from = at + 1) {
        out.append(text.substr(from, at + 1 - from)); // through the '<'
        out += '\\';
    }
    out.append(text.substr(from));
    return out;
}

std::string escape_text(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '&')
            out += "&amp;";
        else
            out += c;
    }
    return out;
}

} // namespace

std::string viewer_page(const std::vector<std::uint8_t>& glb, const std::string& config_json,
                        const std::string& title) {
    const std::string_view script(radiosity_viewer_script, std::size_t(radiosity_viewer_script_end -
                                                                       radiosity_viewer_script));
    if (script.empty())
        throw InputError("this rad-bake was built without the viewer script (web/node_modules "
                         "was missing): run scripts/install-deps, then scripts/build");
    std::string page =
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
        "<title>" +
        escape_text(title) +
        "</title>\n<style>\n"
        "html, body { margin: 0; height: 100%; overflow: hidden; background: #000; }\n"
        "#view { display: block; width: 100%; height: 100%; }\n"
        "#panel { position: absolute; top: 8px; left: 8px; padding: 6px 10px;\n"
        "  background: rgba(0, 0, 0, 0.55); color: #eee; font: 13px sans-serif; }\n"
        "#panel label { display: grid; grid-template-columns: 7em 10em 3em; gap: 6px;\n"
        "  align-items: center; }\n"
        "</style>\n</head>\n<body>\n<canvas id=\"view\"></canvas>\n"
        "<div id=\"panel\"></div>\n"
        "<script id=\"radiosity-config\" type=\"application/json\">" +
        escape_for_html(config_json, "</") +
        "</script>\n<script id=\"radiosity-glb\" type=\"application/octet-stream\">\n" +
        base64(glb) + "</script>\n<script>\n" + escape_for_html(script, "</script") +
        "\n</script>\n</body>\n</html>\n";
    return page;
}

} // namespace rad
