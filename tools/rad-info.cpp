// rad-info: prints the header, provenance and summary of any file of the chain, or its
// data as CSV.
#include "radfmt/container.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/error.hpp"
#include "radiosity/photometry.hpp"
#include "radiosity/ugr_table.hpp"
#include "tool.hpp"

#include <cstdio>

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace {

// --check-inputs: each recorded input against the file at its path now.
int report_inputs(const std::string& path, const radfmt::Header& h,
                  const std::vector<std::string>& made_from) {
    std::vector<std::string> changed;
    for (const auto& file : made_from) {
        bool recorded = false;
        for (const auto& in : h.inputs) {
            std::error_code ec;
            recorded =
                recorded || in.path == file || std::filesystem::equivalent(in.path, file, ec);
        }
        if (!recorded)
            changed.push_back(file + " is not among its inputs (it was made from another file)");
    }
    for (const auto& in : h.inputs) {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(in.path, ec))
            changed.push_back(in.path + " is gone (recorded " + in.hash + ")");
        else if (const auto now = radfmt::hash_file(in.path); now != in.hash)
            changed.push_back(in.path + " has changed since (" + in.hash + " recorded, " + now +
                              " now)");
    }
    if (changed.empty()) {
        std::cout << path << ": its " << h.inputs.size() << " input(s) are the files it was made "
                  << "from\n";
        return 0;
    }
    std::string text;
    for (const auto& c : changed) text += (text.empty() ? "" : "; ") + c;
    throw rad::InputError(path + " was made from other inputs than those there now: " + text +
                          " (make it again)");
}

bool is_photometric_file(const std::string& path) {
    const auto extension = rad::tool::lower_extension(path);
    return extension == ".ies" || extension == ".ldt";
}

std::string number(double value, int decimals) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

// A photometric file: what it says of its light and opening, and its UGR table (CIE 190).
int report_photometry(const std::string& path, bool csv) {
    const auto p = rad::read_photometry_file(path);
    const auto table = rad::ugr_table(p);
    if (csv) {
        std::cout << rad::ugr_table_csv(table);
        return 0;
    }
    const double flux = p.flux();
    std::cout << "file:      " << path << '\n'
              << "kind:      photometry (" << p.edition << ", type "
              << "?CBA"[static_cast<int>(p.type)] << ")\n"
              << "flux:      " << number(flux, 0) << " lm from the intensities; lamps "
              << (p.lamp_lumens > 0 ? number(p.lamp_lumens, 0) + " lm"
                                    : std::string("not stated (absolute photometry)"))
              << "\n"
              << "opening:   " << number(p.length * 1000, 0)
              << (p.round ? " mm across (round)" : " x " + number(p.width * 1000, 0) + " mm")
              << ", " << number(p.height * 1000, 0) << " mm high\n";
    if (p.cct > 0) std::cout << "cct:       " << number(p.cct, 0) << " K\n";
    if (!p.colour_rendering.empty()) std::cout << "cri:       " << p.colour_rendering << '\n';
    for (const auto& w : rad::flux_warnings(p)) std::cout << "warning:   " << w << '\n';
    std::cout << '\n' << rad::ugr_table_text(table);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"Inspect any file of the radiosity chain (mesh, form factors, radiosity).\n"
                 "Prints the header (kind, version, provenance, input hashes, counts, sizes);\n"
                 "with --csv prints the data as CSV instead. A photometric file (.ies, .ldt):\n"
                 "its flux and luminous opening, and its UGR table by CIE 190's tabular method\n"
                 "(19 rooms, 5 reflectance combinations, viewed crosswise and endwise, S = 0.25H)\n"
                 "as data sheets print it; with --csv the table as rows\n"
                 "(x_h,y_h,view,ceiling,walls,floor,ugr,lb)."};
    std::string path;
    bool csv = false;
    app.add_option("FILE", path, "File to inspect")->required();
    std::string csv_help = "Print the data as CSV:";
    for (const auto& kind : radfmt::kind_table())
        csv_help += " " + std::string(kind.name) + ": " + std::string(kind.csv_columns) + ";";
    app.add_flag("--csv", csv, csv_help);
    bool check_inputs = false;
    app.add_flag("--check-inputs", check_inputs,
                 "Check that every input the file records is still the file it was made from "
                 "(its recorded path, from the current folder, with the same checksum), after "
                 "reading the whole file: exit 0 saying so, or 1 naming each input that changed "
                 "or is gone (the shard scripts use it: a part made from other inputs is not a "
                 "done shard)")
        ->excludes("--csv");
    std::vector<std::string> made_from;
    app.add_option("--made-from", made_from,
                   "With --check-inputs: this file must be among the inputs the file records (the "
                   "same file, unchanged): a part from another mesh's run is not this one's")
        ->needs("--check-inputs");
    if (int rc = rad::tool::parse_arguments(app, argc, argv); rc >= 0) return rc;

    return rad::tool::run_tool("rad-info", [&] {
        if (is_photometric_file(path)) {
            if (check_inputs)
                throw rad::InputError(path + ": a photometric file records no inputs; "
                                             "--check-inputs is for the chain's files");
            return report_photometry(path, csv);
        }
        if (csv) {
            std::ios::sync_with_stdio(false);
            radfmt::write_csv(path, std::cout);
            std::cout.flush();
            return 0;
        }
        // Read the whole file so checksums and structure are validated, not just the header.
        radfmt::Header h;
        const auto& kind = radfmt::kind_info(radfmt::read_header(path).kind);
        const auto summary = kind.summary(path, h);
        if (check_inputs) return report_inputs(path, h, made_from);
        std::cout << "file:      " << path << '\n'
                  << "kind:      " << radfmt::kind_name(h.kind) << " ("
                  << radfmt::kind_description(h.kind) << "), version " << h.version << '\n'
                  << "size:      " << std::filesystem::file_size(path) << " bytes (body "
                  << h.body_size << " bytes, " << h.body_hash << ")\n"
                  << "contents:  " << summary << '\n'
                  << "tool:      " << h.tool << '\n'
                  << "provenance:\n";
        int step = 1;
        for (const auto& c : h.provenance) std::cout << "  " << step++ << ". " << c << '\n';
        std::cout << "  " << step << ". " << h.command << "   (this file)\n";
        std::cout << "inputs:\n";
        if (h.inputs.empty()) std::cout << "  (none)\n";
        for (const auto& in : h.inputs) std::cout << "  " << in.hash << "  " << in.path << '\n';
        std::cout << "fields:\n";
        for (const auto& [k, v] : h.fields) std::cout << "  " << k << " = " << v << '\n';
        return 0;
    });
}
