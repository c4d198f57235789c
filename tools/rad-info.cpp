// rad-info: prints the header, provenance and summary of any file of the chain, or its
// data as CSV.
#include "radfmt/kinds.hpp"
#include "tool.hpp"

#include <filesystem>
#include <iostream>

int main(int argc, char** argv) {
    CLI::App app{"Inspect any file of the radiosity chain (mesh, form factors, radiosity).\n"
                 "Prints the header (kind, version, provenance, input hashes, counts, sizes);\n"
                 "with --csv prints the data as CSV instead."};
    std::string path;
    bool csv = false;
    app.add_option("FILE", path, "File to inspect")->required();
    std::string csv_help = "Print the data as CSV:";
    for (const auto& kind : radfmt::kind_table())
        csv_help += " " + std::string(kind.name) + ": " + std::string(kind.csv_columns) + ";";
    app.add_flag("--csv", csv, csv_help);
    if (int rc = rad::tool::parse_arguments(app, argc, argv); rc >= 0) return rc;

    return rad::tool::run_tool("rad-info", [&] {
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
