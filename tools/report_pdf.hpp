// rad-report --pdf: the page printed by headless Chromium (A4, the page's own print rules).
#pragma once
#include <filesystem>
#include <string>

namespace rad::tool {

// Prints `html` to `pdf` with Chromium ($RAD_CHROMIUM, else chromium, chromium-browser or
// google-chrome on PATH), in a private temporary folder, with no network. SystemError when
// Chromium is missing (saying how to get it), fails or takes over `timeout_seconds`.
void print_pdf(const std::string& html, const std::filesystem::path& pdf,
               int timeout_seconds = 300);

} // namespace rad::tool
