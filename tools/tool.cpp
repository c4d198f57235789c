#include "tool.hpp"

#include "radfmt/container.hpp"
#include "radiosity/error.hpp"
#include "radiosity/numbers.hpp"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <iostream>

namespace rad::tool {

int parse_arguments(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 1;
    }
    return -1;
}

int run_tool(const char* tool, const std::function<int()>& body) {
    radfmt::install_cleanup_handlers();
    // A reader that goes away (rad-info --csv | head) is a normal end, not a crash: write
    // errors come back as EPIPE instead of killing the process.
    std::signal(SIGPIPE, SIG_IGN);
    try {
        const int rc = body();
        std::cout.flush();
        if (!std::cout && errno == EPIPE) return 0;
        return rc;
    } catch (const InputError& e) {
        std::cerr << tool << ": error: " << e.what() << '\n';
        return 1;
    } catch (const radfmt::FormatError& e) {
        std::cerr << tool << ": error: " << e.what() << '\n';
        return 1;
    } catch (const SystemError& e) {
        std::cerr << tool << ": system error: " << e.what() << '\n';
        return 2;
    } catch (const radfmt::WriteError& e) {
        std::cerr << tool << ": system error: " << e.what() << '\n';
        return 2;
    } catch (const std::bad_alloc&) {
        std::cerr << tool << ": system error: out of memory\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << tool << ": internal error: " << e.what() << '\n';
        return 3;
    }
}

CLI::Validator finite_range(double lo, double hi) {
    char description[96];
    std::snprintf(description, sizeof description, "NUMBER in [%g, %g]", lo, hi);
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            double value = 0;
            if (!parse_number(text, value) || value < lo || value > hi) {
                char message[160];
                std::snprintf(message, sizeof message, "'%s' is not a number in [%g, %g]",
                              text.c_str(), lo, hi);
                return message;
            }
            return {};
        },
        description);
}

std::string one_of(const std::vector<std::string>& names) {
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i)
        out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return out;
}

std::uint64_t parse_size(const std::string& text, const std::string& option) {
    std::size_t split = 0;
    while (split < text.size() && (std::isdigit(static_cast<unsigned char>(text[split])) ||
                                   text[split] == '.' || text[split] == 'e' || text[split] == '+'))
        ++split;
    double value = 0;
    if (!parse_number(text.substr(0, split), value))
        throw InputError(option + ": '" + text + "' is not a size (e.g. 8G, 512M)");
    const std::string unit = text.substr(split);
    double scale = 1;
    if (unit == "K" || unit == "KiB" || unit == "k")
        scale = 1024.0;
    else if (unit == "M" || unit == "MiB")
        scale = 1024.0 * 1024;
    else if (unit == "G" || unit == "GiB")
        scale = 1024.0 * 1024 * 1024;
    else if (unit == "T" || unit == "TiB")
        scale = 1024.0 * 1024 * 1024 * 1024;
    else if (!unit.empty() && unit != "B")
        throw InputError(option + ": unknown unit '" + unit + "' in '" + text +
                         "' (use K, M, G or T)");
    const double bytes = value * scale;
    if (!(bytes >= 1) || bytes > 1e18)
        throw InputError(option + ": '" + text + "' must be between 1 B and 1e18 B");
    return static_cast<std::uint64_t>(bytes);
}

} // namespace rad::tool
