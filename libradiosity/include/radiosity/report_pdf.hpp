// The report as a PDF: the page printed by headless Chromium (A4, the page's own print
// rules), the browser a dependency found at run time (rad-report --pdf).
#pragma once
#include <filesystem>
#include <string>

namespace rad {

// Prints `html` to `pdf` with Chromium ($RAD_CHROMIUM, else chromium, chromium-browser or
// google-chrome on PATH), in a private temporary folder, with no network. SystemError when
// Chromium is missing (saying how to get it), fails or takes over `timeout_seconds`.
void print_pdf(const std::string& html, const std::filesystem::path& pdf,
               int timeout_seconds = 300);

} // namespace rad
