// rad-info: prints the header, provenance and summary of any file of the chain, or its
// data as CSV.
#include "radfmt/kinds.hpp"
#include "radiosity/cli.hpp"

#include <filesystem>
#include <iostream>

int main(int argc, char** argv) {
    CLI::App app{"Inspect any file of the radiosity chain (mesh, form factors, radiosity).\n"
                 "Prints the header (kind, version, provenance, input hashes, counts, sizes);\n"
                 "with --csv prints the data as CSV instead."};
    std::string path;
    bool csv = false;
    app.add_option("FILE", path, "File to inspect")->required();
    app.add_flag("--csv", csv,
                 "Print the data as CSV: mesh: patch,group,material,area,cx,cy,cz,nx,ny,nz,"
                 "rho_r,rho_g,rho_b,e_r,e_g,e_b; form factors: row,col,f; radiosity: "
                 "patch,b_r,b_g,b_b");
    if (int rc = rad::parse_arguments(app, argc, argv); rc >= 0) return rc;

    return rad::run_tool("rad-info", [&] {
        if (csv) {
            std::ios::sync_with_stdio(false);
            radfmt::write_csv(path, std::cout);
            std::cout.flush();
            return 0;
        }
        // Read the whole file so checksums and structure are validated, not just the header.
        radfmt::Header h;
        const auto kind = radfmt::read_header(path).kind;
        std::string summary;
        if (kind == radfmt::Kind::Mesh) {
            const auto mesh = radfmt::read_mesh(path, &h);
            std::size_t quads = 0;
            for (const auto& p : mesh.patches) quads += p.corner_count() == 4;
            summary = std::to_string(mesh.patches.size()) + " patches (" + std::to_string(quads) +
                      " quads, " + std::to_string(mesh.patches.size() - quads) + " triangles), " +
                      std::to_string(mesh.vertices.size()) + " vertices";
        } else if (kind == radfmt::Kind::FormFactors) {
            const auto ff = radfmt::read_form_factors(path, &h);
            const double n = static_cast<double>(ff.patch_count);
            char text[160];
            std::snprintf(text, sizeof text, "%llu x %llu, %llu non-zeros (%.2f%% dense)",
                          static_cast<unsigned long long>(ff.patch_count),
                          static_cast<unsigned long long>(ff.patch_count),
                          static_cast<unsigned long long>(ff.nonzeros()),
                          n > 0 ? 100.0 * ff.nonzeros() / (n * n) : 0.0);
            summary = text;
        } else {
            const auto r = radfmt::read_radiosity(path, &h);
            summary = std::to_string(r.radiosity.size()) + " patches";
        }
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
